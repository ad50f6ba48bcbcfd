#!/usr/bin/env bash
# color_samples.sh: what rendering in the scene's own colour channels costs. Each SPD
# scene as given (RGB), under a ColorSamples of three channels that is not RGB (red and
# blue swapped: the same work plus the conversions), and under ColorSamples 1 (every
# Color cut to its first value; two-float ray weights). Renders alternated after an
# untimed warm-up of each (program build), median frame time (`--stats` elapsed_s) of N
# runs (default 3), and each variant's ratio to RGB.
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
printf '%-8s %9s %9s %9s %11s %11s\n' scene rgb_ms swap3_ms one_ms swap3/rgb one/rgb
for s in "${scenes[@]}"; do
  zcat "$spd/$s.rib.gz" > "$work/$s.rgb.rib"
  { echo 'ColorSamples [0 0 1 0 1 0 1 0 0] [0 0 1 0 1 0 1 0 0]'; cat "$work/$s.rgb.rib"; } > "$work/$s.swap3.rib"
  { echo 'ColorSamples [1 1 1] [0.299 0.587 0.114]'
    sed -E 's/^Color \[ *([-0-9.e+]+) [^]]*\]/Color [ \1 ]/' "$work/$s.rgb.rib"; } > "$work/$s.one.rib"
  for v in rgb swap3 one; do "$bin" -q -o "$work/o.exr" "$work/$s.$v.rib"; done
  for i in $(seq "$runs"); do
    for v in rgb swap3 one; do
      "$bin" -q -o "$work/o.exr" --stats "$work/$s.$v.$i.json" "$work/$s.$v.rib"
    done
  done
  python3 - "$s" "$work" "$runs" <<'PY'
import json, statistics, sys
s, work, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
ms = {v: statistics.median(json.load(open(f"{work}/{s}.{v}.{i}.json"))["elapsed_s"] * 1e3
                           for i in range(1, runs + 1)) for v in ("rgb", "swap3", "one")}
print(f"{s:8s} {ms['rgb']:9.0f} {ms['swap3']:9.0f} {ms['one']:9.0f} "
      f"{ms['swap3'] / ms['rgb']:11.3f} {ms['one'] / ms['rgb']:11.3f}")
PY
done
