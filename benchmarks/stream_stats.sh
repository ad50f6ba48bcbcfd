#!/usr/bin/env bash
# stream_stats.sh: how well the streaming core keeps the device fed, on the SPD scenes
# (512x512, one sample a pixel): pool fill (rays a round over the pool's capacity; issue
# 5's goal >= 0.7), rounds, device busy (kernel time over the sampling loop) and host
# overhead (loop time with no kernel running, over the frame; goal < 5%) and the part of
# it that is the host's (host_sync: waits at round ends, planning, the film's final sync;
# the rest is the OpenCL runtime's gap between kernels queued back to back), each the
# median of N renders (default 3) after an untimed warm-up, from `raydrive --stats FILE`.
# Usage: benchmarks/stream_stats.sh [runs] [extra raydrive options...]
set -euo pipefail
source "$(dirname "$0")/common.sh"
runs="${1:-3}"
shift || true
spd="${SPD_DIR:-$bench_root/../shared/scenes/spd}"
bin="$(raydrive_bin)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
printf '%-8s %9s %8s %7s %7s %12s %14s %10s %8s\n' scene frame_ms pool fill rounds device_busy host_overhead host_sync plan_ms
for s in balls gears mount rings teapot tetra tree; do
  "$bin" -q -o "$work/$s.exr" "$spd/$s.rib.gz" "$@"  # warm-up: program build
  for i in $(seq "$runs"); do
    "$bin" -q -o "$work/$s.exr" --stats "$work/$s.$i.json" "$spd/$s.rib.gz" "$@"
  done
  python3 - "$s" "$work" "$runs" <<'PY'
import json, statistics, sys
s, work, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
d = [json.load(open(f"{work}/{s}.{i}.json")) for i in range(1, runs + 1)]
med = lambda f: statistics.median(f(x) for x in d)
st = lambda k: (lambda x: x["scene_stats"][k])
print(f"{s:8s} {med(lambda x: x['elapsed_s']) * 1e3:9.0f} {d[0]['scene_stats']['pool_capacity']:8d} "
      f"{med(st('pool_fill')):7.3f} {med(st('rounds')):7.0f} {med(st('device_busy')):12.3f} "
      f"{med(st('host_overhead')):14.3f} {med(st('host_sync_overhead')):10.3f} "
      f"{med(st('plan_ms')):8.1f}")
PY
done
