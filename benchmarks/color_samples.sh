#!/usr/bin/env bash
# color_samples.sh: what rendering in the scene's own colour channels costs. Each SPD
# scene as given (RGB), under a ColorSamples of three channels that is not RGB (red and
# blue swapped: the same work plus the conversions), under ColorSamples 1 (every Color cut
# to its first value; two-float ray weights), and under 6 and 12 channels that repeat
# RGB's (every Color written twice or four times: float8 and float16 colours and ray
# weights; the image is the RGB one). Renders alternated after an untimed warm-up of each
# (program build), median frame time (`--stats` elapsed_s) of N runs (default 3), and each
# variant's ratio to RGB.
# Usage: benchmarks/color_samples.sh [runs] [scenes...]
set -euo pipefail
source "$(dirname "$0")/common.sh"
runs="${1:-3}"
shift || true
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(balls gears mount teapot)
spd="${SPD_DIR:-$bench_root/../shared/scenes/spd}"
bin="$(raydrive_bin)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cp "$spd/spd.sl" "$work/"
variants=(rgb swap3 one six twelve)
printf '%-8s' scene; for v in "${variants[@]}"; do printf ' %8s' "${v}_ms"; done
for v in "${variants[@]:1}"; do printf ' %11s' "$v/rgb"; done; echo
# ColorSamples of n channels that repeat RGB's: nRGB 3/n per copy, RGBn ones
repeated() {
  local n=$1 to="" from="" i j
  for ((i = 0; i < n; ++i)); do for ((j = 0; j < 3; ++j)); do
    if ((i % 3 == j)); then to+=" $(awk -v n="$n" 'BEGIN { printf "%.6g", 3 / n }')"; else to+=" 0"; fi
  done; done
  for ((j = 0; j < 3; ++j)); do for ((i = 0; i < n; ++i)); do
    if ((i % 3 == j)); then from+=" 1"; else from+=" 0"; fi
  done; done
  echo "ColorSamples [$to] [$from]"
}
for s in "${scenes[@]}"; do
  zcat "$spd/$s.rib.gz" > "$work/$s.rgb.rib"
  { echo 'ColorSamples [0 0 1 0 1 0 1 0 0] [0 0 1 0 1 0 1 0 0]'; cat "$work/$s.rgb.rib"; } > "$work/$s.swap3.rib"
  { echo 'ColorSamples [1 1 1] [0.299 0.587 0.114]'
    sed -E 's/^Color \[ *([-0-9.e+]+) [^]]*\]/Color [ \1 ]/' "$work/$s.rgb.rib"; } > "$work/$s.one.rib"
  { repeated 6; sed -E 's/^Color \[([^]]*)\]/Color [\1 \1]/' "$work/$s.rgb.rib"; } > "$work/$s.six.rib"
  { repeated 12; sed -E 's/^Color \[([^]]*)\]/Color [\1 \1 \1 \1]/' "$work/$s.rgb.rib"; } > "$work/$s.twelve.rib"
  for v in "${variants[@]}"; do "$bin" -q -o "$work/o.exr" "$work/$s.$v.rib"; done
  for i in $(seq "$runs"); do
    for v in "${variants[@]}"; do
      "$bin" -q -o "$work/o.exr" --stats "$work/$s.$v.$i.json" "$work/$s.$v.rib"
    done
  done
  python3 - "$s" "$work" "$runs" <<'PY'
import json, statistics, sys
s, work, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
variants = ("rgb", "swap3", "one", "six", "twelve")
ms = {v: statistics.median(json.load(open(f"{work}/{s}.{v}.{i}.json"))["elapsed_s"] * 1e3
                           for i in range(1, runs + 1)) for v in variants}
print(f"{s:8s}" + "".join(f" {ms[v]:8.0f}" for v in variants) +
      "".join(f" {ms[v] / ms['rgb']:11.3f}" for v in variants[1:]))
PY
done
