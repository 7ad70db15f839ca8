#!/usr/bin/env bash
# Configures and builds one auvloop build directory. Usage: scripts/build.sh DIR [cmake options...]
# Uses Ninja, and ccache when installed, so that repeated builds are quick.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=$1
shift
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  # Paths inside this checkout are hashed relative to it, and the build directory is not hashed,
  # so another checkout of the same sources (a clean clone for CI) reuses the cached objects.
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
  export CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-1}
fi
cmake -S . -B "$dir" -G Ninja "${launcher[@]}" "$@" >/dev/null
cmake --build "$dir" --parallel "$(nproc)"
