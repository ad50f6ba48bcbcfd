#!/usr/bin/env bash
# run_trace.sh: builds the benchmarks (Embree 3 from Debian is installed if missing) and
# runs bench_trace: RayDrive's intersect kernels against Embree on the same rays.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
dpkg-query -W -f='${Status}' libembree-dev 2>/dev/null | grep -q "install ok installed" ||
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libembree-dev >/dev/null
RAYDRIVE_CMAKE_ARGS="-DRT_WITH_BENCHMARKS=ON" "$root/scripts/setup.sh"
"$root/build/bin/bench_trace" "$@"
