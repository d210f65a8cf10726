#!/usr/bin/env bash
# Sets up contour_reg on Debian 12 and runs it.
#
#   ./setup.sh build   install missing Debian packages, configure and build Release into build/
#   ./setup.sh run     build, then run the main job on the bundled data
#   ./setup.sh test    build, then run every test with ctest
set -euo pipefail
cd "$(dirname "$0")"

PACKAGES=(cmake g++ make pkg-config libeigen3-dev libpcl-dev libflann-dev libopencv-dev
          libcli11-dev zlib1g-dev libyaml-cpp-dev libgtest-dev libbenchmark-dev
          librosbag-storage-dev libsensor-msgs-dev libnav-msgs-dev)

install_packages() {
  local missing=()
  for package in "${PACKAGES[@]}"; do
    dpkg -s "$package" >/dev/null 2>&1 || missing+=("$package")
  done
  [ ${#missing[@]} -eq 0 ] && return
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "setup: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

build() {
  install_packages
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCONTOUR_REG_BUILD_BENCHMARKS=ON
  cmake --build build -j"$(nproc)"
}

case "${1:-build}" in
  build) build ;;
  run)
    build
    # Contour odometry against PCL ICP and NDT2D on the bundled simulated office log:
    # table, CSV, trajectories and their picture in build/results/office.
    ./build/bin/contour_reg compare data/office/L-hokuyo-2hz.clf --methods contour contour+icp icp ndt2d \
        --out build/results/office
    ;;
  test)
    build
    ctest --test-dir build --output-on-failure -j"$(nproc)"
    ;;
  *) echo "usage: $0 [build|run|test]" >&2; exit 2 ;;
esac
