// SPDX-License-Identifier: GPL-3.0-or-later
// The indices reported for each manoeuvre type (docs/indices.md), from a run's time series.
#pragma once

#include <nlohmann/json.hpp>

#include "auvloop/engine/case.hpp"
#include "auvloop/engine/time_series.hpp"

namespace auvloop::results {

nlohmann::json manoeuvre_metrics(const engine::CaseSpec& c, const engine::TimeSeries& series);

}  // namespace auvloop::results
