#!/usr/bin/env bash
# Installs every package scanstation needs from Debian bookworm.
# Non-interactive and idempotent: when everything is installed it only checks
# and returns in well under a second.
set -euo pipefail

packages=(
  # toolchain
  cmake g++ ninja-build pkg-config
  # libraries
  libcgal-dev libeigen3-dev libopencv-dev libgpiod-dev libusb-1.0-0-dev linux-libc-dev
  libtbb-dev libembree-dev libcli11-dev libspdlog-dev nlohmann-json3-dev libtomlplusplus-dev libpugixml-dev
  libopencv-contrib-dev  # ximgproc: WLS disparity filtering for stereo
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  umockdev libumockdev-dev  # emulated sysfs/udev/usbfs for the libusb and libgpiod tests
  # public data used by the tests: CGAL's meshes and scans, OpenCV's stereo
  # images, and assimp's model files (held out: read and reconstructed only)
  libcgal-demo opencv-doc assimp-testmodels
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages are installed"
  exit 0
fi

sudo=()
if [ "$(id -u)" -ne 0 ]; then sudo=(sudo); fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
