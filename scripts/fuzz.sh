#!/usr/bin/env bash
# Builds the fuzz targets (clang, AddressSanitizer + UndefinedBehaviorSanitizer +
# libFuzzer) into build-fuzz/ and runs each for SECONDS seconds (default 25),
# starting from its corpus in tests/fuzz/corpus/TARGET. Inputs libFuzzer finds
# go to build-fuzz/corpus/TARGET, not into the repository; a crash, a sanitizer
# report, a hang (10 s) or more than 2 GB of memory leaves the input in
# build-fuzz/artifacts/ and fails the script. The suite runs it bounded
# (fuzz_bounded); by hand, for hours:
#   build-fuzz/bin/fuzz_scene build-fuzz/corpus/fuzz_scene tests/fuzz/corpus/fuzz_scene
#   scripts/fuzz.sh SECONDS
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_PER_TARGET=${1:-25}
TARGETS=(fuzz_scene fuzz_checkpoint fuzz_samples)
cmake -S . -B build-fuzz -DCOSIM_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER="${FUZZ_CXX:-clang++-14}" -DCMAKE_C_COMPILER="${FUZZ_CC:-clang-14}" >/dev/null
cmake --build build-fuzz -j "${JOBS:-$(nproc)}" --target "${TARGETS[@]}"
rm -rf build-fuzz/artifacts && mkdir -p build-fuzz/artifacts  # this run's findings only
for t in "${TARGETS[@]}"; do
  mkdir -p "build-fuzz/corpus/$t"
  echo "fuzz: $t for ${SECONDS_PER_TARGET} s"
  "build-fuzz/bin/$t" "build-fuzz/corpus/$t" "tests/fuzz/corpus/$t" -max_total_time="$SECONDS_PER_TARGET" \
    -timeout=10 -rss_limit_mb=2048 -max_len=65536 -artifact_prefix="build-fuzz/artifacts/$t-" \
    -print_final_stats=1 2>&1 | grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb|Done|INFO: seed corpus)|ERROR|SUMMARY|==[0-9]+==|Test unit written" || true
  # The pipe hides libFuzzer's exit code: an artifact is the failure.
  if compgen -G "build-fuzz/artifacts/$t-*" >/dev/null; then
    echo "fuzz: $t failed; the input is in build-fuzz/artifacts/" >&2
    exit 1
  fi
done
