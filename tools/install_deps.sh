#!/usr/bin/env bash
# Installs the Debian 12 packages sandcastle needs, if any is missing (run as root).
set -euo pipefail
packages=(build-essential cmake libeigen3-dev libboost-test-dev libgsl-dev nlohmann-json3-dev libcli11-dev
          libtinyobjloader-dev libopenvdb-dev libboost-iostreams-dev libopenmpi-dev openmpi-bin
          clang libclang-rt-14-dev libomp-14-dev
          libpugixml-dev libpng-dev povray ffmpeg
          python3 python3-matplotlib python3-numpy git)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq "${missing[@]}" >/dev/null
fi
