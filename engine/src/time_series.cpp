// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/time_series.hpp"

#include <algorithm>
#include <stdexcept>

namespace auvloop::engine {

std::size_t TimeSeries::add(std::string name, std::string unit) {
  signals_.push_back({std::move(name), std::move(unit), {}});
  return signals_.size() - 1;
}

bool TimeSeries::has(std::string_view name) const {
  return std::any_of(signals_.begin(), signals_.end(),
                     [&](const Signal& s) { return s.name == name; });
}

const Signal& TimeSeries::operator[](std::string_view name) const {
  for (const auto& s : signals_) {
    if (s.name == name) return s;
  }
  throw std::out_of_range("time series has no signal \"" + std::string(name) + "\"");
}

}  // namespace auvloop::engine
