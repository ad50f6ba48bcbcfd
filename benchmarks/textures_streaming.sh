#!/usr/bin/env bash
# textures_streaming.sh: a texture-heavy scene rendered with every tile resident on the
# device and with tile caches far smaller than its textures (tiles streamed on demand, the
# points that missed shaded again). Prints wall time (median of RUNS, default 3), the
# ratio to the resident render, the tile hit rate, tiles and bytes uploaded and reshade
# passes (from --stats), and checks that every image equals the resident one.
# The textures are made here: RayDrive renders four noise patterns (2048x2048) and the
# scene's MakeTexture turns them into mip-maps (4 x 5461 tiles, 358 MB of float texels).
# usage: [RAYDRIVE_BUILD=build] benchmarks/textures_streaming.sh [RUNS]
set -euo pipefail
source "$(dirname "$0")/common.sh"
runs="${1:-3}"
bin="$(raydrive_bin)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"

cat > pattern.sl <<'SL'
surface pattern(float seed = 0; float freq = 64;) {
    Ci = color(noise(s * freq + seed, t * freq), noise(s * freq * 0.5 + 7, t * freq * 0.5 + seed),
               cellnoise(s * freq * 0.25 + seed, t * freq * 0.25));
    Oi = 1;
}
SL
for i in 0 1 2 3; do
  cat > pattern$i.rib <<RIB
Option "searchpath" "shader" [".:&"]
Format 2048 2048 1
PixelSamples 1 1
Projection "orthographic"
Display "pattern$i.exr" "file" "rgb"
WorldBegin
Translate 0 0 5
Surface "pattern" "seed" $((i * 13)) "freq" $((32 << i))
Patch "bilinear" "P" [-1 1 0  1 1 0  -1 -1 0  1 -1 0]
WorldEnd
RIB
  "$bin" -q pattern$i.rib
done

{
  for i in 0 1 2 3; do echo "MakeTexture \"pattern$i.exr\" \"pattern$i.tex\" \"periodic\" \"periodic\" \"box\" 1 1"; done
  cat <<'RIB'
Format 512 512 1
PixelSamples 2 2
Projection "perspective" "fov" 45
Display "scene.exr" "file" "rgba"
Translate 0 -1 12
Rotate -20 1 0 0
WorldBegin
LightSource "ambientlight" 1 "intensity" 0.3
LightSource "distantlight" 2 "intensity" 0.8 "from" [1 2 -1] "to" [0 0 0]
AttributeBegin
Surface "paintedplastic" "texturename" "pattern0.tex"
Polygon "P" [-20 0 -20  20 0 -20  20 0 20  -20 0 20] "st" [0 0  8 0  8 8  0 8]
AttributeEnd
RIB
  for x in -3 -1 1 3; do
    for z in -3 -1 1 3; do
      m=$(( (x + z + 8) / 2 % 4 ))
      echo "AttributeBegin"
      echo "Translate $x 1 $z"
      echo "Surface \"paintedplastic\" \"texturename\" \"pattern$m.tex\""
      echo "Sphere 0.9 -0.9 0.9 360"
      echo "AttributeEnd"
    done
  done
  echo "WorldEnd"
} > scene.rib
"$bin" -q -o warm.exr scene.rib  # makes the textures and the cached program

printf "%-22s %9s %7s %9s %10s %12s %8s %s\n" cache "wall ms" ratio "hit rate" "tiles up" "MB up" reshade image
resident_ms=""
for cache in 22000 4096 1024 256 64; do
  times=()
  for r in $(seq "$runs"); do
    times+=("$(wall "$bin" -q --texture-cache "$cache" -o "c$cache.exr" --stats "c$cache.json" scene.rib)")
  done
  ms="$(printf "%s\n" "${times[@]}" | median)"
  [ -n "$resident_ms" ] || resident_ms="$ms"
  same="$(python3 - "c22000.exr" "c$cache.exr" <<'PY'
import sys
a, b = (open(f, "rb").read() for f in sys.argv[1:3])
print("same" if a == b else "DIFFERS")
PY
)"
  python3 - "c$cache.json" "$cache" "$ms" "$resident_ms" "$same" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))["textures"]
cache, ms, res, same = sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), sys.argv[5]
label = f"{cache} tiles ({int(cache) * 16 // 1024} MB)" + (" resident" if d["resident"] else "")
print(f"{label:<22} {ms:9.0f} {ms / res:7.2f} {d['tile_hit_rate']:9.3f} {d['tiles_uploaded']:10d} "
      f"{d['bytes_uploaded'] / 1e6:12.1f} {d['reshade_passes']:8d} {same}")
PY
done
