#!/usr/bin/env bash
# run_trace.sh: builds the benchmarks (Embree 3 from Debian is installed if missing) and
# runs bench_trace: RayDrive's intersect kernels against Embree on the same rays, on two
# procedural sphere fields and the Stanford bunny (bunny00.off from Debian's
# libcgal-demo, fetched once into build/bench-data; not committed: not ours).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
dpkg-query -W -f='${Status}' libembree-dev 2>/dev/null | grep -q "install ok installed" ||
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libembree-dev >/dev/null
RAYDRIVE_CMAKE_ARGS="-DRT_WITH_BENCHMARKS=ON" "$root/scripts/setup.sh"
data="$root/build/bench-data"
bunny="$data/bunny00.off"
if [ ! -f "$bunny" ]; then
  mkdir -p "$data/deb"
  (cd "$data/deb" && apt-get download libcgal-demo >/dev/null 2>&1 &&
     dpkg -x libcgal-demo_*.deb x &&
     tar xzf x/usr/share/doc/libcgal-dev/data.tar.gz -C "$data" data/meshes/bunny00.off &&
     mv "$data/data/meshes/bunny00.off" "$bunny") || echo "bunny not available: sphere fields only"
  rm -rf "$data/deb" "$data/data"
fi
mesh=()
[ -f "$bunny" ] && mesh=(--mesh "$bunny")
"$root/build/bin/bench_trace" "${mesh[@]}" "$@"
