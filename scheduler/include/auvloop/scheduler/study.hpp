// SPDX-License-Identifier: GPL-3.0-or-later
// An optimisation study (docs/optimization.md): what to tune (a heading-step case's PID gains, or
// a test function), the objective (an index or a weighted sum of indices), constraints, and the
// optimizer settings. Shared by the in-process `auvloop optimize` and the daemon's driver.
#pragma once

#include <map>
#include <optional>
#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "auvloop/engine/case.hpp"
#include "auvloop/optimizer/optimizer.hpp"
#include "auvloop/optimizer/test_functions.hpp"
#include "auvloop/scheduler/bundle.hpp"

namespace auvloop::scheduler {

struct Study {
  std::string name;
  std::optional<engine::CaseSpec> base_case;        // a case, or ...
  std::string case_name;                            // (its name in the study's bundle)
  std::optional<optimizer::TestFunction> function;  // ... a test function
  optimizer::OptimizerConfig config;
  std::map<std::string, double> weights;                     // objective = sum w * index
  std::optional<double> max_overshoot, max_saturation_time;  // constraints (%, s)

  // "itae", or "1*itae + 50*overshoot" for a weighted sum.
  [[nodiscard]] std::string objective_text() const;
};

// Reads a study; the case it names comes from `files` (throws input::InputError).
Study parse_study(std::string_view text, const std::string& source_name, const FileSource& files);
Study parse_study_bundle(const SourceBundle& bundle);

// The study's case with the gains of point x (names in config.names).
engine::CaseSpec with_gains(const Study& s, const Eigen::VectorXd& x);

struct Outcome {
  std::optional<double> value;  // empty: a failed evaluation ...
  std::string failure;          // ... and why
  nlohmann::json metrics = nlohmann::json::object();
};

// The objective and constraints from a finished run's metrics (metrics.json); `duration` (s)
// stands in for a settling time that was never reached.
Outcome objective_from_metrics(const Study& s, const nlohmann::json& metrics, double duration);

// Evaluates a point in-process (a test function, or the case on its own plant).
Outcome evaluate_in_process(const Study& s, const Eigen::VectorXd& x);

// "kp 1.2, ki 0.3, kd 0.9"
std::string point_text(const Study& s, const Eigen::VectorXd& x);

}  // namespace auvloop::scheduler
