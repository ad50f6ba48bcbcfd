#!/usr/bin/env bash
# packets.sh: what tracing rays in packets of eight (the default for triangle scenes on the
# eight-wide BVH) does in the renderer: intersect_closest's and intersect_shadow's device
# time with packets over their time with one ray a work-item (--no-closest-packets
# --no-shadow-packets), the median of N alternating renders each (default 5), on the SPD
# triangle scenes and, when
# build/bench-data/bunny00.off is there (benchmarks/run_trace.sh fetches it), the Stanford
# bunny on a floor under three point lights. The scenes are rendered at 3x3 samples a pixel
# (the SPD files ask for one) so that the kernel times are well above this machine's noise.
# Also checks that both images are the same, pixel for pixel, or within 1e-5 (idiff, where
# installed).
# Usage: benchmarks/packets.sh [runs]
set -euo pipefail
source "$(dirname "$0")/common.sh"
runs="${1:-5}"
spd="${SPD_DIR:-$bench_root/../shared/scenes/spd}"
bin="$(raydrive_bin)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
scenes=()
for s in gears teapot tetra; do
  zcat "$spd/$s.rib.gz" | sed 's/PixelSamples 1 1/PixelSamples 3 3/' >"$work/$s.rib"
  cp "$spd/spd.sl" "$work/" 2>/dev/null || true
  scenes+=("$s")
done
bunny="${RAYDRIVE_BUILD:-$bench_root/build}/bench-data/bunny00.off"
if [ -f "$bunny" ]; then
  python3 - "$bunny" "$work/bunny.rib" <<'PY'
import sys
words = [w for line in open(sys.argv[1]) for w in line.split("#")[0].split()]
assert words[0] == "OFF"
nv, nf = int(words[1]), int(words[2])
v = [words[4 + 3 * i: 7 + 3 * i] for i in range(nv)]
pos, faces = 4 + 3 * nv, []
for _ in range(nf):
    k = int(words[pos]); faces.append(words[pos + 1: pos + 1 + k]); pos += 1 + k
lo = [min(float(p[a]) for p in v) for a in range(3)]
hi = [max(float(p[a]) for p in v) for a in range(3)]
c = [(l + h) / 2 for l, h in zip(lo, hi)]
size = max(hi[0] - lo[0], hi[1] - lo[1])
with open(sys.argv[2], "w") as f:
    f.write('Format 512 512 1\nPixelSamples 3 3\nProjection "perspective" "fov" 30\n')
    f.write(f"Translate 0 0 {size * 2.2}\nRotate 180 0 1 0\nTranslate {-c[0]} {-c[1]} {-c[2]}\n")
    f.write("WorldBegin\n")
    for i, (x, y, z) in enumerate([(1, 1, -1), (-1, 0.5, -1), (0, 1, 1)]):
        f.write(f'LightSource "pointlight" {i + 1} "from" [{c[0] + x * size} {c[1] + y * size} '
                f'{c[2] + z * size}] "intensity" {size * size}\n')
    f.write('Surface "plastic"\n')
    y0 = lo[1]
    f.write(f'Polygon "P" [{lo[0] - size} {y0} {lo[2] - size} {lo[0] - size} {y0} {hi[2] + size} '
            f'{hi[0] + size} {y0} {hi[2] + size} {hi[0] + size} {y0} {lo[2] - size}]\n')
    f.write("PointsPolygons [" + " ".join(str(len(t)) for t in faces) + "] [" +
            " ".join(" ".join(t) for t in faces) + '] "P" [' + " ".join(" ".join(p) for p in v) + "]\n")
    f.write("WorldEnd\n")
PY
  scenes+=(bunny)
fi
one=(--no-closest-packets --no-shadow-packets)
printf '%-8s %13s %13s %7s %13s %13s %7s %9s %9s %s\n' scene closest_pkt closest_one ratio \
  shadow_pkt shadow_one ratio frame_pkt frame_one image
for s in "${scenes[@]}"; do
  "$bin" -q -o "$work/$s.exr" "$work/$s.rib"  # warm-up: program builds
  "$bin" -q -o "$work/$s.one.exr" "${one[@]}" "$work/$s.rib"
  for i in $(seq "$runs"); do
    "$bin" -q -o "$work/$s.exr" --stats "$work/$s.p.$i.json" "$work/$s.rib"
    "$bin" -q -o "$work/$s.one.exr" --stats "$work/$s.o.$i.json" "${one[@]}" "$work/$s.rib"
  done
  same="n/a"
  if command -v idiff >/dev/null; then
    if idiff -fail 0 -warn 0 "$work/$s.exr" "$work/$s.one.exr" >/dev/null 2>&1; then same=same
    elif idiff -fail 1e-5 -warn 1e-5 "$work/$s.exr" "$work/$s.one.exr" >/dev/null 2>&1; then
      same="within 1e-5"  # the rounding of a few sums, not a different hit
    else same=DIFFERENT; fi
  fi
  python3 - "$s" "$work" "$runs" "$same" <<'PY'
import json, statistics, sys
s, work, runs, same = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
def med(tag, f):
    return statistics.median(f(json.load(open(f"{work}/{s}.{tag}.{i}.json"))) for i in range(1, runs + 1))
k = lambda name: (lambda d: d["kernels"][name]["device_ms"])
e = lambda d: d["elapsed_s"] * 1e3
cp, co = med("p", k("intersect_closest")), med("o", k("intersect_closest"))
sp, so = med("p", k("intersect_shadow")), med("o", k("intersect_shadow"))
print(f"{s:8s} {cp:13.1f} {co:13.1f} {cp / co:7.3f} {sp:13.1f} {so:13.1f} {sp / so:7.3f} "
      f"{med('p', e):9.0f} {med('o', e):9.0f} {same}")
PY
done
