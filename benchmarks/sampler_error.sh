#!/usr/bin/env bash
# sampler_error.sh: the error of `--sampler sobol` against independent samples at the same
# samples a pixel (sampler_error.py says how), on the area-light scene, the convergence
# benchmark's spheres and the Cornell box of gi_vs_cycles (diffuse GI through random()).
# Usage: benchmarks/sampler_error.sh [more sampler_error.py options, e.g. --seeds 5]
set -euo pipefail
source "$(dirname "$0")/common.sh"
/usr/bin/python3 -c 'import numpy, OpenImageIO' 2>/dev/null ||
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-numpy python3-openimageio >/dev/null
bin="$(raydrive_bin)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 - "$work/cornell.rib" "$bench_root/benchmarks/scenes" <<'PY'
import sys
sys.path.insert(0, sys.argv[2] + "/..")
import cornell
open(sys.argv[1], "w").write(cornell.rib("cornell.exr", 64, 3, sys.argv[2]))
PY
exec /usr/bin/python3 "$bench_root/benchmarks/sampler_error.py" --raydrive "$bin" "$@" \
  "$bench_root/benchmarks/scenes/area_light.rib" "$bench_root/benchmarks/scenes/spheres_small.rib" \
  "$work/cornell.rib"
