#!/usr/bin/env bash
# Installs posekit's build and test dependencies from Debian packages.
# Idempotent: packages already present are not fetched again.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libtbb-dev libnanoflann-dev libspectra-dev
  libcli11-dev nlohmann-json3-dev libsuitesparse-dev libopenblas-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  mesa-vulkan-drivers libvulkan-dev glslang-tools vulkan-validationlayers spirv-tools
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo
  pybind11-dev python3-dev python3-numpy python3-pytest python3-distributed
  libjs-three chromium fonts-dejavu-core libpng-dev
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
