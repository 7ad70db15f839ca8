// SPDX-License-Identifier: GPL-3.0-or-later
// Deterministic random numbers: std::mt19937_64 is specified bit for bit by the standard, but the
// std::*_distribution classes are not, so they are replaced here to keep replays identical
// across standard libraries.
#pragma once

#include <cstdint>
#include <random>

namespace auvloop::optimizer::detail {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
  std::uint64_t below(std::uint64_t n) { return engine_() % n; }                 // bias < n / 2^64
  // Seeds derived from (seed, stream) for independent, reproducible streams.
  static std::uint64_t mix(std::uint64_t seed, std::uint64_t stream) {
    std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (stream + 1);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace auvloop::optimizer::detail
