#!/usr/bin/env bash
# Installs the Debian packages skein builds against (Debian 12). Safe to run again.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libopenmesh-dev libeigen3-dev libosd-dev libassimp-dev
  libgtest-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev libspdlog-dev libtbb-dev libpng-dev
  qt6-base-dev libqt6opengl6-dev libxkbcommon-dev xvfb xauth libgl1-mesa-dri
  clang libclang-rt-14-dev libomp-dev
  gnuplot-nox
  libopenmpi-dev openmpi-bin
  libtinygltf-dev
  libcgal-dev
  libsuitesparse-dev libopenblas0-serial
  libexpat1-dev
  libopenvdb-dev libboost-iostreams-dev
)
missing=()
for p in "${packages[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
if [ ${#missing[@]} -eq 0 ]; then exit 0; fi
sudo_cmd=""
[ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
echo "installing: ${missing[*]}"
$sudo_cmd apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
