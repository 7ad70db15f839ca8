#!/usr/bin/env bash
# Configures and builds one auvloop build directory. Usage: scripts/build.sh DIR [cmake options...]
# Uses Ninja, and ccache when installed, so that repeated builds are quick.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=$1
shift
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B "$dir" -G Ninja "${launcher[@]}" "$@" >/dev/null
cmake --build "$dir" --parallel "$(nproc)"
