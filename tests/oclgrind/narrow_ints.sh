#!/usr/bin/env bash
# narrow_ints.sh OCLGRIND_KERNEL LLVM_AS WORKDIR: whether the installed Oclgrind still
# gets narrow integers wrong (narrow_ints.ll). While it does, the two tests that depend
# on them stay out of the Oclgrind subsets (CMakeLists.txt) and this check passes; once
# an Oclgrind wraps them, it fails and says to put those tests back.
set -eu
kernel=$1 llvm_as=$2 dir=$3
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$dir"
"$llvm_as" "$here/narrow_ints.ll" -o "$dir/narrow_ints.bc"
answers() {
  printf '%s\nnarrow_ints\n1 1 1\n1 1 1\n<size=12 int dump>\n%s 0 0\n' "$dir/narrow_ints.bc" "$1" \
    > "$dir/narrow_ints.sim"
  "$kernel" "$dir/narrow_ints.sim" | sed -n 's/.*out\[\([12]\)\] = \(-*[0-9]*\).*/\2/p' | tr '\n' ' '
}
a5=$(answers 5) a1=$(answers 1)
echo "out[1] out[2] for 5: $a5(right: 0 1); for 1: $a1(right: 1 1)"
if [ "$a5" = "0 1 " ] && [ "$a1" = "1 1 " ]; then
  echo "this Oclgrind wraps narrow integers: put Shading.HoistedUniformWorkEqualsPerPointWork"
  echo "and Derivatives.FilterstepIsAntialiased back into tests/oclgrind/CMakeLists.txt"
  exit 1
fi
if [ -z "$a5" ] || [ -z "$a1" ]; then echo "oclgrind-kernel gave no answer"; exit 1; fi
echo "narrow integers still wrong in this Oclgrind: the two tests stay out of its subsets"
