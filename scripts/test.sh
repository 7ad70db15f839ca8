#!/usr/bin/env bash
# The test suite: installs what is missing, then
#   1. checks formatting (clang-format),
#   2. builds with warnings as errors and runs the unit tests and the validation tests,
#   3. builds with AddressSanitizer + UndefinedBehaviorSanitizer and runs the unit tests again.
# Options: --full also runs the tests labelled "slow" (long validations, not part of CI);
#          --no-sanitizers skips step 3 (quicker local runs).
set -euo pipefail
cd "$(dirname "$0")/.."
full=0
sanitizers=1
for arg in "$@"; do
  case "$arg" in
    --full) full=1 ;;
    --no-sanitizers) sanitizers=0 ;;
    *) echo "test.sh: unknown option $arg (use --full or --no-sanitizers)" >&2; exit 2 ;;
  esac
done
jobs=$(nproc)
scripts/install-deps.sh
scripts/check-format.sh

scripts/build.sh build/release -DCMAKE_BUILD_TYPE=Release -DAUVLOOP_WERROR=ON -DAUVLOOP_BUILD_TESTS=ON -DAUVLOOP_BUILD_BENCH=ON
labels="unit|validation"
[ $full -eq 1 ] && labels="unit|validation|slow"
ctest --test-dir build/release --output-on-failure -j "$jobs" -L "$labels"

if [ $sanitizers -eq 1 ]; then
  # -g1 (line tables and function names, enough for sanitizer reports) instead of full debug
  # information: the instrumented build is the longest step of CI.
  scripts/build.sh build/sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DAUVLOOP_WERROR=ON -DAUVLOOP_BUILD_TESTS=ON \
    -DAUVLOOP_BUILD_BENCH=OFF -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
    -DAUVLOOP_SANITIZE=ON -DAUVLOOP_TEST_LABELS=unit
  # The comparisons of whole runs on one, two and three threads (names ending in
  # "...OnOneAndTwoThreads" / "...ForOneTwoAndThreeThreads" that take minutes instrumented) are
  # left to the release pass: they run the code the other unit tests run here, two or three
  # times over, and what they check (the reductions' order) is not what these sanitizers see
  # (data races would need ThreadSanitizer). The quick thread tests still run here.
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build/sanitize --output-on-failure -j "$jobs" -L unit \
    -E 'BitwiseTheSameOnOneAndTwoThreads|BitwiseIdenticalForOneTwoAndThreeThreads'
fi
