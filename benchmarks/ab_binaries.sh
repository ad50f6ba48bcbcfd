#!/usr/bin/env bash
# ab_binaries.sh: two raydrive binaries (e.g. before and after a change) on the same
# scenes, renders alternated so the shared machine's drift hits both alike; prints the
# median of one kernel's device time (`--stats`), of the frame time and of the whole
# command's wall time (program load, scene reading and the image's writing included)
# for each, and their ratio (B / A). Scenes: SPD names (balls, gears, ...) or RIB paths.
# Usage: benchmarks/ab_binaries.sh BIN_A BIN_B RUNS KERNEL SCENE...
set -euo pipefail
source "$(dirname "$0")/common.sh"
[ $# -ge 5 ] || { sed -n '2,6p' "$0"; exit 2; }
a="$1" b="$2" runs="$3" kernel="$4"
shift 4
spd="${SPD_DIR:-$bench_root/../shared/scenes/spd}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for s in "$@"; do
  f="$spd/$s.rib.gz"
  [ -f "$f" ] || f="$s"
  for i in $(seq "$runs"); do
    t0=$(date +%s%N)
    "$a" -q -o "$work/a.exr" --stats "$work/a$i.json" "$f"
    t1=$(date +%s%N)
    "$b" -q -o "$work/b.exr" --stats "$work/b$i.json" "$f"
    t2=$(date +%s%N)
    echo $(( (t1 - t0) / 1000 )) > "$work/a$i.wall"
    echo $(( (t2 - t1) / 1000 )) > "$work/b$i.wall"
  done
  python3 - "$s" "$work" "$runs" "$kernel" <<'PY'
import json, statistics, sys
s, work, runs, kernel = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
def med(v):
    d = [json.load(open(f"{work}/{v}{i}.json")) for i in range(1, runs + 1)]
    k = statistics.median(x["kernels"].get(kernel, {}).get("device_ms", 0) for x in d)
    w = statistics.median(int(open(f"{work}/{v}{i}.wall").read()) / 1e3 for i in range(1, runs + 1))
    return k, statistics.median(x["elapsed_s"] * 1e3 for x in d), w
(ka, fa, wa), (kb, fb, wb) = med("a"), med("b")
print(f"{s[-24:]:24s} {kernel} A {ka:7.1f} B {kb:7.1f} B/A {kb / ka if ka else 0:.3f} | "
      f"frame A {fa:6.0f} B {fb:6.0f} B/A {fb / fa:.3f} | "
      f"command A {wa:6.0f} B {wb:6.0f} B/A {wb / wa:.3f}")
PY
done
