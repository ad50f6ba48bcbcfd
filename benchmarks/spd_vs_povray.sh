#!/usr/bin/env bash
# spd_vs_povray.sh: the SPD benchmark scenes (../shared/scenes/spd: balls, gears, mount,
# rings, teapot, tetra, tree at 512x512) rendered by RayDrive and by POV-Ray 3.7 (Debian
# `povray`, installed if missing) in one run, each timed as wall time of the whole
# command, median of N runs (default 3). RayDrive renders with PixelSamples 1 1 as the
# RIB says; POV-Ray with +WT2 -D -A (2 threads, no display, no antialiasing), as the
# scenes' README measured it. RayDrive's first render of a scene builds its OpenCL
# program (about 2 s on PoCL); that warm-up run is not timed.
set -euo pipefail
source "$(dirname "$0")/common.sh"
runs="${1:-3}"
peer_benchmark_setup
printf '%-8s %12s %12s %8s\n' scene raydrive_ms povray_ms ratio
tot_r=0; tot_p=0
for s in balls gears mount rings teapot tetra tree; do
  zcat "$spd/$s.pov.gz" > "$work/$s.pov"
  "$bin" -q -o "$work/$s.exr" "$spd/$s.rib.gz"  # warm-up: program build
  r=$(for i in $(seq "$runs"); do wall "$bin" -q -o "$work/$s.exr" "$spd/$s.rib.gz"; done | median)
  p=$(for i in $(seq "$runs"); do wall povray +I"$work/$s.pov" +O"$work/$s.png" +W512 +H512 +WT2 -D -A; done | median)
  printf '%-8s %12d %12d %8.2f\n' "$s" "$r" "$p" "$(ratio "$r" "$p")"
  tot_r=$((tot_r + r)); tot_p=$((tot_p + p))
done
printf '%-8s %12d %12d %8.2f\n' total "$tot_r" "$tot_p" "$(ratio "$tot_r" "$tot_p")"
echo "(ratio = RayDrive time / POV-Ray time: below 1 is faster)"
