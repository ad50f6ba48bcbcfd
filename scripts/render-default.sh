#!/usr/bin/env bash
# render-default.sh: Quick start, first command: set up, build, and render the bundled
# default scene to default.exr in the current directory.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/setup.sh"
"$root/build/bin/raydrive" --stats - "$root/examples/default.rib" "$@"
