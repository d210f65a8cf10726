#!/usr/bin/env bash
# Sets up contour_reg on Debian 12 and runs it.
#
#   ./setup.sh build       install missing Debian packages, configure and build Release into build/
#   ./setup.sh run         build, then run the main jobs on the bundled data: the method comparison on
#                          the bundled log and the paper's experiment on the built-in office map
#   ./setup.sh test        build, then run every test with ctest
#   ./setup.sh sanitize    build with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/, run the tests
#   ./setup.sh fuzz [S]    build the libFuzzer targets with clang into build-fuzz/, run each for S seconds (60),
#                          one per core at a time
set -euo pipefail
cd "$(dirname "$0")"

PACKAGES=(cmake g++ make pkg-config libeigen3-dev libpcl-dev libflann-dev libopencv-dev
          libcli11-dev zlib1g-dev libyaml-cpp-dev libsqlite3-dev libzstd-dev liblz4-dev libgtest-dev libbenchmark-dev
          librosbag-storage-dev libsensor-msgs-dev libnav-msgs-dev libtf2-msgs-dev clang-format
          python3-dev python3-numpy python3-pytest pybind11-dev parallel)

FUZZ_PACKAGES=(clang libclang-rt-14-dev)

install_packages() {
  local missing=()
  for package in "$@"; do
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
  install_packages "${PACKAGES[@]}"
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCONTOUR_REG_BUILD_BENCHMARKS=ON
  cmake --build build -j"$(nproc)"
}

case "${1:-build}" in
  build) build ;;
  run)
    build
    # Contour odometry against PCL ICP, point-to-line ICP and NDT2D on the bundled simulated office log:
    # table, CSV, trajectories and their picture in build/results/office.
    ./build/bin/contour_reg compare data/office/L-hokuyo-2hz.clf --methods contour contour+icp icp icp-pl ndt2d \
        --out build/results/office
    # The paper's experiment (its Table 1) on the built-in office: paths S, L, Y, O x 5, 2, 1 Hz x
    # 10 arrivals; contour, ICP and NDT2D on the same scans. Table, CSV and plots in build/results/experiment.
    ./build/bin/contour_reg experiment --out build/results/experiment
    ;;
  test)
    build
    ctest --test-dir build --output-on-failure -j"$(nproc)"
    ;;
  sanitize)
    install_packages "${PACKAGES[@]}"
    # -O1 with line tables only: reports still name the file and line of every frame, and the
    # instrumented build compiles in about half the time of -O2 -g.
    cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCONTOUR_REG_SANITIZE=ON \
      "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
    cmake --build build-asan -j"$(nproc)"
    # The consumer project installs and links the package without the sanitizer runtime.
    ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
      ctest --test-dir build-asan --output-on-failure -j"$(nproc)" -E consumer_project
    ;;
  fuzz)
    install_packages "${PACKAGES[@]}" "${FUZZ_PACKAGES[@]}"
    tests/fuzz/run_fuzzers.sh "${2:-60}"
    ;;
  *) echo "usage: $0 [build|run|test|sanitize|fuzz [SECONDS]]" >&2; exit 2 ;;
esac
