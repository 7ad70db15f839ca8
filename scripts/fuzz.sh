#!/usr/bin/env bash
# Coverage-guided fuzzing of the daemon's request and case parsers with libFuzzer (clang).
# Usage: scripts/fuzz.sh [SECONDS] [extra libFuzzer flags...]      (default 300 s)
# Builds build/fuzz (clang, AUVLOOP_FUZZ=ON: ASan + UBSan + coverage), then runs
# tests/fuzz/fuzz_requests.cpp on a corpus in build/fuzz/corpus seeded from examples/ and
# tests/fuzz/seeds/. A crash leaves its input as build/fuzz/crash-*; reproduce it with
#   build/fuzz/tests/fuzz_requests build/fuzz/crash-...
# CI runs the same target for a short time without coverage feedback (tests/fuzz/fuzz_driver.cpp).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-300}
shift || true
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
CC=clang CXX=clang++ cmake -S . -B build/fuzz -G Ninja "${launcher[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DAUVLOOP_FUZZ=ON -DAUVLOOP_BUILD_BENCH=OFF -DAUVLOOP_WERROR=OFF >/dev/null
cmake --build build/fuzz --target fuzz_requests
mkdir -p build/fuzz/corpus
cp -n examples/*.toml tests/fuzz/seeds/* build/fuzz/corpus/ 2>/dev/null || true
cd build/fuzz
./tests/fuzz_requests -max_total_time="$seconds" -max_len=65536 -artifact_prefix=./ "$@" corpus
