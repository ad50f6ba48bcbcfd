#!/usr/bin/env bash
# setup.sh: installs what RayDrive needs on Debian 12 (as root) and builds it into build/.
# Installs only the packages that are missing, so a machine that has them is not touched.
set -euo pipefail
cd "$(dirname "$0")/.."
packages=(cmake g++ make pkg-config pocl-opencl-icd ocl-icd-opencl-dev opencl-headers
          opencl-clhpp-headers clinfo libopenexr-dev libglm-dev zlib1g-dev libgtest-dev
          nlohmann-json3-dev libcli11-dev libfmt-dev libosd-dev libopenimageio-dev python3
          clang libclang-rt-14-dev oclgrind mesa-opencl-icd libre2-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}"
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo ${RAYDRIVE_CMAKE_ARGS:-} >/dev/null
cmake --build build -j "$(nproc)"
