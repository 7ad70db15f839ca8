// SPDX-License-Identifier: GPL-3.0-or-later
// Recorded signals of a run, column by column, each with its unit.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "auvloop/engine/state_archive.hpp"

namespace auvloop::engine {

struct Signal {
  std::string name;  // e.g. "psi"
  std::string unit;  // e.g. "deg"
  std::vector<double> values;
};

class TimeSeries {
 public:
  // Adds an empty column; returns its index.
  std::size_t add(std::string name, std::string unit);
  void push(std::size_t column, double value) { signals_[column].values.push_back(value); }
  [[nodiscard]] const Signal& operator[](std::string_view name) const;  // throws if absent
  [[nodiscard]] bool has(std::string_view name) const;
  [[nodiscard]] const std::vector<Signal>& signals() const { return signals_; }
  [[nodiscard]] std::size_t rows() const {
    return signals_.empty() ? 0 : signals_.front().values.size();
  }
  // Exact checkpoint of the values; load() requires the same columns (names) and throws
  // std::runtime_error otherwise, leaving the series unchanged.
  void save(StateWriter& out) const;
  void load(StateReader& in);

 private:
  std::vector<Signal> signals_;
};

}  // namespace auvloop::engine
