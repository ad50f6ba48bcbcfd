#!/usr/bin/env bash
# against_pocl.sh RAYDRIVE EXR_COMPARE SCENE OUT_PREFIX FLAGS...: renders SCENE with FLAGS
# on PoCL, then on Mesa's rusticl over llvmpipe (RUSTICL_ENABLE=llvmpipe, --device
# llvmpipe), and requires the two images to agree within 1e-5. rusticl compiles through
# SPIR-V and NIR, as Mesa's GPU drivers do. Its only allowed message is Mesa's note that
# it treats kernel arguments read inside control flow as uniform (they are).
set -u
raydrive=$1 compare=$2 scene=$3 out=$4
shift 4
"$raydrive" -q "$@" -o "${out}_pocl.exr" "$scene" || exit 1
RUSTICL_ENABLE=llvmpipe "$raydrive" --device llvmpipe -q "$@" -o "${out}_rusticl.exr" \
  "$scene" 2> "${out}_rusticl.log"
rc=$?
others=$(grep -v "MESA: warning: Treating load_kernel_arg in control flow as uniform" \
  "${out}_rusticl.log")
if [ $rc -ne 0 ] || [ -n "$others" ]; then
  echo "rusticl run: exit $rc"
  cat "${out}_rusticl.log"
  exit 1
fi
"$compare" "${out}_pocl.exr" "${out}_rusticl.exr" 1e-5
