#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) into build-fuzz/ and runs each for
# SECONDS (default 60) from its seed corpus in tests/fuzz/corpus/, as many at once as there
# are cores. Findings are written to build-fuzz/findings/; the script fails when a target
# crashes, leaks or hangs. The random
# seed is FUZZ_SEED (default 1), so a run can be repeated; FUZZ_SEED=0 draws one.
#
#   tests/fuzz/run_fuzzers.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds="${1:-60}"
seed="${FUZZ_SEED:-1}"
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCONTOUR_REG_BUILD_FUZZERS=ON \
  -DBUILD_TESTING=OFF -DCONTOUR_REG_BUILD_APPS=OFF -DCONTOUR_REG_WITH_ROSBAG=ON >/dev/null
targets=(carmen pcd_folder rosbag2 mcap pipeline map)
# The bag reader's target exists where rosbag_storage is installed.
if cmake --build build-fuzz --target help | grep -q rosbag_fuzzer; then targets+=(rosbag); fi
cmake --build build-fuzz -j"$(nproc)" --target "${targets[@]/%/_fuzzer}"
mkdir -p build-fuzz/findings

# Runs one target; its summary (or the end of its log, on a finding) goes to stdout.
run_target() {
  local target="$1"
  local corpus="build-fuzz/corpus/${target}"
  mkdir -p "$corpus"
  local seeds="tests/fuzz/corpus/${target%_folder}"
  # rosbag_storage leaks what it has read of a corrupt bag's connections when it gives up on
  # the bag: not ours to free, so leaks are not findings there.
  local leaks=1
  [ "$target" = rosbag ] && leaks=0
  echo "fuzz: ${target} for ${seconds} s"
  if ! ASAN_OPTIONS="detect_leaks=$leaks" "build-fuzz/bin/${target}_fuzzer" "$corpus" "$seeds" \
      -max_total_time="$seconds" -seed="$seed" -timeout=10 -detect_leaks="$leaks" \
      -rss_limit_mb=2048 -max_len=65536 -artifact_prefix="build-fuzz/findings/${target}-" -print_final_stats=1 \
      2> "build-fuzz/findings/${target}.log"; then
    echo "fuzz: ${target} FOUND A PROBLEM, see build-fuzz/findings/${target}.log"
    tail -40 "build-fuzz/findings/${target}.log"
    return 1
  fi
  grep -E "stat::number_of_executed_units|cov:" "build-fuzz/findings/${target}.log" | tail -2 || true
}

# One target per core at a time; their summaries are printed in the targets' order.
for target in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$(nproc)" ]; do wait -n || true; done
  { run_target "$target" && echo ok || echo failed; } > "build-fuzz/findings/${target}.summary" 2>&1 &
done
wait
status=0
for target in "${targets[@]}"; do
  head -n -1 "build-fuzz/findings/${target}.summary"
  [ "$(tail -n 1 "build-fuzz/findings/${target}.summary")" = ok ] || status=1
done
exit "$status"
