// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/time_series.hpp"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

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

void TimeSeries::save(StateWriter& out) const {
  out.tag("time series");
  out.put(static_cast<std::int64_t>(signals_.size()));
  for (const auto& s : signals_) {
    out.put(std::string_view(s.name));
    out.put(s.values);
  }
}

void TimeSeries::load(StateReader& in) {
  in.expect_tag("time series");
  const auto n = in.get<std::int64_t>();
  if (n != static_cast<std::int64_t>(signals_.size()))
    in.fail(fmt::format("{} recorded signals, this run records {}", n, signals_.size()));
  std::vector<std::vector<double>> values;
  for (const auto& s : signals_) {
    const auto name = in.get_string();
    if (name != s.name)
      in.fail(fmt::format("signal \"{}\" recorded where this run records \"{}\"", name, s.name));
    values.push_back(in.get_vector());
    if (values.back().size() != values.front().size())
      in.fail(fmt::format("signal \"{}\" has {} rows, the first {}", name, values.back().size(),
                          values.front().size()));
  }
  for (std::size_t i = 0; i < signals_.size(); ++i) signals_[i].values = std::move(values[i]);
}

}  // namespace auvloop::engine
