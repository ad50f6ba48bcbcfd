#!/usr/bin/env bash
# run_under_oclgrind.sh OCLGRIND LOG COMMAND...: runs COMMAND with Oclgrind's simulated
# OpenCL device in place of PoCL: a second OpenCL implementation (a simulated device with
# its own compiler) that checks every work-item's memory accesses (out of bounds, writes to
# read-only buffers) and the API calls. Fails when COMMAND fails or when Oclgrind reports
# anything. Oclgrind's data-race and uninitialised-value checks are not run: the first
# reports only the plain first read of the float atomics' compare-and-swap loop
# (cl/lib/atomics.clh), which the swap corrects; the second does not know LLVM 14's
# `freeze` and crashes.
set -u
oclgrind=$1 log=$2
shift 2
rm -f "$log"
export RAYDRIVE_NO_CACHE=1  # every program built by Oclgrind's compiler, none from a cache
"$oclgrind" --check-api --max-errors 20 --log "$log" "$@"
rc=$?
if [ -f "$log" ] && grep -q '[^[:space:]]' "$log"; then
  echo "Oclgrind reported errors:"
  cat "$log"
  exit 1
fi
exit $rc
