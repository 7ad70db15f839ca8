#!/usr/bin/env bash
# Installs every Debian 12 package auvloop needs to build, test and run.
# Idempotent: packages already present are skipped, and apt-get is not called at all when nothing is missing.
# Run as root (or through sudo). Set AUVLOOP_EXTRA_PACKAGES to add packages (e.g. peer programs for benches).
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config git ccache clang-format
  # required by design
  libeigen3-dev libsuitesparse-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libnlopt-dev libnlopt-cxx-dev libassimp-dev
  # chosen: threads, configuration, CLI, logging
  libtbb-dev libtomlplusplus-dev nlohmann-json3-dev libcli11-dev libspdlog-dev libfmt-dev
  # scheduler: RPC and persistent state
  libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler libsqlite3-dev
  libsqlitecpp-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # results: plots (PNG and SVG through cairo) and content hashes
  gnuplot-nox fonts-dejavu-core libssl-dev
)
# shellcheck disable=SC2206
packages+=(${AUVLOOP_EXTRA_PACKAGES:-})

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${#missing[@]} missing packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
