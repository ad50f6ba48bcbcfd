#!/usr/bin/env bash
# quadrics_vs_povray.sh: scenes built of quadrics rendered three ways in one run: RayDrive
# with exact quadrics, RayDrive with the same quadrics tessellated (--tessellate-quadrics,
# 0.1 pixel chord error), and POV-Ray 3.7 (Debian `povray`, exact quadrics, +WT2 -D -A).
# Scenes: SPD balls (a sphereflake of 7381 spheres), SPD rings (4200 cylinders and 4200
# spheres) and a generated forest of 900 cones on cylinder trunks. Reported: wall time
# (median of N runs, default 3, after an untimed warm-up that builds the OpenCL program),
# peak resident memory, RayDrive's device geometry bytes, and the time ratios.
set -euo pipefail
source "$(dirname "$0")/common.sh"
runs="${1:-3}"
peer_benchmark_setup

# The forest, as RIB and as POV-Ray scene of the same camera, light and trees.
python3 - "$work" <<'PY'
import random, sys
w = sys.argv[1]
random.seed(5)
trees = [(x * 0.6 - 9 + random.uniform(-0.15, 0.15), z * 0.6 - 9 + random.uniform(-0.15, 0.15))
         for x in range(30) for z in range(30)]
with open(w + "/forest.rib", "w") as f:
    f.write('Format 512 512 1\nPixelSamples 1 1\nProjection "perspective" "fov" 45\n'
            'Rotate -16.7 1 0 0\nTranslate 0 -3 10\nWorldBegin\n'
            'LightSource "shadowspot" 1 "from" [-10 20 -10] "to" [0 0 0] "coneangle" 1.2 '
            '"intensity" [600] "shadowname" ["raytrace"]\n'
            'LightSource "ambientlight" 2 "intensity" 0.2\nSurface "matte"\n'
            'Color [0.4 0.8 0.3]\nPolygon "P" [-12 0 -12  -12 0 12  12 0 12  12 0 -12]\n'
            'Rotate -90 1 0 0\n')
    for x, z in trees:
        # after Rotate -90 about x, object z is world y and object y is world -z
        f.write('AttributeBegin Translate %.4f %.4f 0 Color [0.5 0.3 0.1] '
                'Cylinder 0.05 0 0.4 360 Color [0.1 0.6 0.2] Translate 0 0 0.4 '
                'Cone 0.8 0.25 360 AttributeEnd\n' % (x, -z))
    f.write('WorldEnd\n')
with open(w + "/forest.pov", "w") as f:
    f.write('camera { location <0, 3, -10> look_at <0, 0, 0> angle 45 }\n'
            'light_source { <-10, 20, -10> color rgb 1 }\n'
            '#default { finish { ambient 0.2 diffuse 0.8 } }\n'
            'plane { y, 0 pigment { color rgb <0.4, 0.8, 0.3> } }\n')
    for x, z in trees:
        f.write('cylinder { <%.4f, 0, %.4f>, <%.4f, 0.4, %.4f>, 0.05 open pigment { color rgb <0.5, 0.3, 0.1> } }\n'
                'cone { <%.4f, 0.4, %.4f>, 0.25, <%.4f, 1.2, %.4f>, 0 open pigment { color rgb <0.1, 0.6, 0.2> } }\n'
                % (x, z, x, z, x, z, x, z))
PY
for s in balls rings; do zcat "$spd/$s.pov.gz" > "$work/$s.pov"; done

printf '%-7s %9s %9s %9s %8s %8s %8s %8s %10s %10s\n' scene exact_ms tess_ms povray_ms \
  exact/tess exact/pov exactMiB tessMiB exact_geomB tess_geomB
for s in balls rings forest; do
  rib="$work/$s.rib"
  [ "$s" = forest ] || rib="$spd/$s.rib.gz"  # beside spd.sl, the shader it uses
  "$bin" -q -o "$work/$s.exr" "$rib"                        # warm-up: program builds
  "$bin" -q --tessellate-quadrics -o "$work/$s.exr" "$rib"
  e=$(for i in $(seq "$runs"); do wall "$bin" -q -o "$work/$s.exr" "$rib"; done | median)
  t=$(for i in $(seq "$runs"); do wall "$bin" -q --tessellate-quadrics -o "$work/$s.exr" "$rib"; done | median)
  p=$(for i in $(seq "$runs"); do wall povray +I"$work/$s.pov" +O"$work/$s.png" +W512 +H512 +WT2 -D -A; done | median)
  em=$(peak_mib "$bin" -q -o "$work/$s.exr" "$rib")
  tm=$(peak_mib "$bin" -q --tessellate-quadrics -o "$work/$s.exr" "$rib")
  "$bin" -q --stats "$work/e.json" -o "$work/$s.exr" "$rib"
  "$bin" -q --tessellate-quadrics --stats "$work/t.json" -o "$work/$s.exr" "$rib"
  geom() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['scene_stats']['geometry_bytes'])" "$1"; }
  printf '%-7s %9d %9d %9d %8s %8s %8s %8s %10s %10s\n' "$s" "$e" "$t" "$p" "$(ratio "$e" "$t")" \
    "$(ratio "$e" "$p")" "$em" "$tm" "$(geom "$work/e.json")" "$(geom "$work/t.json")"
done
echo "(ratios are times: below 1 means exact quadrics are faster; MiB = peak resident memory)"
