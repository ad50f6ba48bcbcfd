#!/usr/bin/env bash
# run_convergence.sh: builds the benchmarks and runs the convergence benchmark on the
# bundled scenes; installs gnuplot for the plots if it is missing. Output in
# build/convergence-out (the reference images are cached there).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
command -v gnuplot >/dev/null || { apt-get install -y -qq gnuplot-nox >/dev/null || true; }
RAYDRIVE_CMAKE_ARGS="-DRT_WITH_BENCHMARKS=ON" "$root/scripts/setup.sh"
"$root/build/bin/convergence" --out "$root/build/convergence-out" "$@" \
  "$root/benchmarks/scenes/stripes.rib" "$root/benchmarks/scenes/spheres_small.rib"
