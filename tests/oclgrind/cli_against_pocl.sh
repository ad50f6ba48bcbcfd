#!/usr/bin/env bash
# cli_against_pocl.sh OCLGRIND RAYDRIVE EXR_COMPARE SCENE OUT_PREFIX FLAGS...: renders SCENE
# with FLAGS on PoCL, then on Oclgrind (run_under_oclgrind.sh: no reported error allowed),
# and requires the two images to agree within 1e-5.
set -u
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
oclgrind=$1 raydrive=$2 compare=$3 scene=$4 out=$5
shift 5
"$raydrive" -q "$@" -o "${out}_pocl.exr" "$scene" || exit 1
"$here/run_under_oclgrind.sh" "$oclgrind" "${out}.log" "$raydrive" -q "$@" \
  -o "${out}_oclgrind.exr" "$scene" || exit 1
"$compare" "${out}_pocl.exr" "${out}_oclgrind.exr" 1e-5
