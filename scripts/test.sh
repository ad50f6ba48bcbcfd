#!/usr/bin/env bash
# test.sh: Quick start, second command: set up, build, and run the whole test suite
# through CTest (on PoCL). CI (.ci/run) calls exactly this.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/setup.sh"
cd "$root/build"
ctest --output-on-failure -j "$(nproc)" "$@"
