#!/usr/bin/env bash
# many_lights.sh: shading cost against the number of lights. The SPD gears with each of
# its five spotlights split into K nearby ones of 1/K the intensity (K = 1, 4, 8: 5, 20
# and 40 lights), rendered with --stats: medians of RUNS of the frame and of the shade
# kernel. With two binaries, they are compared scene by scene (ab_binaries.sh).
# Usage: benchmarks/many_lights.sh [RUNS] [BIN_A BIN_B]
set -euo pipefail
source "$(dirname "$0")/common.sh"
runs="${1:-3}"
spd="${SPD_DIR:-$bench_root/../shared/scenes/spd}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cp "$spd/spd.sl" "$work/"  # the scenes' shader, found beside them
for k in 1 4 8; do
  zcat "$spd/gears.rib.gz" | python3 -c '
import re, sys
k = int(sys.argv[1])
for line in sys.stdin:
    m = re.match(r"(LightSource \"shadowspot\" )(\d+)( \"from\" \[ )([-\d. ]+)( \] \"intensity\" \[)([\d.]+)(\].*)", line)
    if not m:
        sys.stdout.write(line)
        continue
    x, y, z = (float(v) for v in m.group(4).split())
    for j in range(k):
        d = 0.3 * j
        sys.stdout.write(f"{m.group(1)}{int(m.group(2)) * 10 + j}{m.group(3)}{x + d:.3f} {y - d:.3f} {z + 0.1 * j:.3f}"
                         f"{m.group(5)}{float(m.group(6)) / k:g}{m.group(7)}\n")
' "$k" > "$work/gears_$((5 * k))lights.rib"
done
if [ $# -ge 3 ]; then
  "$(dirname "$0")/ab_binaries.sh" "$2" "$3" "$runs" shade_spd "$work"/gears_5lights.rib \
    "$work"/gears_20lights.rib "$work"/gears_40lights.rib
  exit
fi
bin="$(raydrive_bin)"
printf '%-8s %9s %9s\n' lights frame_ms shade_ms
for n in 5 20 40; do
  "$bin" -q -o "$work/x.exr" "$work/gears_${n}lights.rib"  # warm-up: program build
  for i in $(seq "$runs"); do
    "$bin" -q -o "$work/x.exr" --stats "$work/s$i.json" "$work/gears_${n}lights.rib"
  done
  python3 - "$n" "$work" "$runs" <<'PY'
import json, statistics, sys
n, work, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
d = [json.load(open(f"{work}/s{i}.json")) for i in range(1, runs + 1)]
f = statistics.median(x["elapsed_s"] * 1e3 for x in d)
s = statistics.median(x["kernels"]["shade_spd"]["device_ms"] for x in d)
print(f"{n:8s} {f:9.0f} {s:9.1f}")
PY
done
