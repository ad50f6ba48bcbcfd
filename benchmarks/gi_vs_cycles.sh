#!/usr/bin/env bash
# gi_vs_cycles.sh: RayDrive against Cycles (Debian's Blender 3.4, installed if missing) on
# a diffuse global-illumination scene, error against time (gi_vs_cycles.py says how).
# Usage: benchmarks/gi_vs_cycles.sh [runs] [more gi_vs_cycles.py options, e.g.
# --samples 4,16,64 --reference 1024 --depth 3]. References are cached in
# build/gi-vs-cycles (delete them after changing the scene).
set -euo pipefail
source "$(dirname "$0")/common.sh"
runs="${1:-3}"
shift || true
command -v blender >/dev/null ||
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends blender >/dev/null
/usr/bin/python3 -c 'import numpy, OpenImageIO' 2>/dev/null ||
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-numpy python3-openimageio >/dev/null
bin="$(raydrive_bin)"
blender --version | head -1
exec /usr/bin/python3 "$bench_root/benchmarks/gi_vs_cycles.py" --raydrive "$bin" --runs "$runs" "$@"
