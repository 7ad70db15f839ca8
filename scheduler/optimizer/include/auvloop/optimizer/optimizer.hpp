// SPDX-License-Identifier: GPL-3.0-or-later
// Surrogate-based optimisation of an expensive black box over a box (the paper's section 5):
// a maximin Latin hypercube as the first batch, then per iteration a Kriging fit, an infill batch
// of the expected-improvement (EI) point and the minimum-surrogate-prediction (MSP) point (the MSP
// point is dropped when within normalised distance 0.01 of the EI point), and the stopping rule
// |f_best(k) - f_best(k-1)| < eps or k = max_iterations.
//
// Ask/tell: ask() returns the next batch, whose points may be evaluated in parallel; tell() takes
// their values (or failures). The optimizer's state is a pure function of the configuration,
// the seed and the ordered evaluations: replaying them (from_json) proposes the same points bit
// for bit, which is how an interrupted optimisation resumes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "auvloop/optimizer/infill.hpp"
#include "auvloop/optimizer/kriging.hpp"

namespace auvloop::optimizer {

struct OptimizerConfig {
  std::vector<std::string> names;  // one per dimension
  Eigen::VectorXd lower, upper;    // the box, in the user's units
  int initial_points = 20;         // Latin hypercube batch
  int max_iterations = 15;         // infill batches
  double epsilon = 1e-3;           // stop when the best value improves by less than this ...
  bool relative_epsilon = false;   // ... (or by less than epsilon * |f_best|)
  int patience = 1;                // ... for this many consecutive iterations (the paper: 1)
  int batch_size = 2;              // q: EI + MSP (the paper); q > 2 adds kriging-believer EI points
  double msp_drop_distance = 0.01;  // normalised distance |dx| / sqrt(d) on the unit cube
  std::string solver = "pso";  // sub-problems: "pso" (the paper) or "nlopt" (multistart BOBYQA)
  PsoOptions pso;
  int nlopt_starts = 10;
  KrigingOptions kriging;
  // Failed evaluations: "classify" (default) fits the objective on successes only and a second
  // Kriging model on the success indicator (1 / 0); EI is weighted by the predicted probability of
  // success and the MSP point must have it above one half. "impute" puts failed points into the
  // fit at the worst observed value instead.
  std::string failure_policy = "classify";
  // The surrogate's output scale (output_transform.hpp): "none", "log" (ln of the values, shifted
  // when some are not positive) or "auto" (per fit, the one with the smaller leave-one-out error).
  std::string output_transform = "none";
  std::uint64_t seed = 1;
};

struct Evaluation {
  int batch = 0;
  std::string origin;           // "lhs", "ei", "msp", "believer", "explore"
  Eigen::VectorXd x;            // user units
  std::optional<double> value;  // empty: the evaluation failed
  std::string failure;          // why, when it failed
};

struct Batch {
  int index = 0;                        // 0: the initial design; k >= 1: infill iteration k
  std::vector<Eigen::VectorXd> points;  // user units
  std::vector<std::string> origins;
};

class SurrogateOptimizer {
 public:
  explicit SurrogateOptimizer(OptimizerConfig config);

  // The next batch to evaluate, or nothing once the optimisation has stopped (stop_reason()).
  // Asking again before telling returns the same batch.
  std::optional<Batch> ask();
  // Results for the batch returned by ask(): one per point, in order; a failure as
  // std::nullopt with a reason in `failures` (same length, may be empty).
  void tell(const Batch& batch, const std::vector<std::optional<double>>& values,
            const std::vector<std::string>& failures = {});
  // One result of the pending batch, in any order; the batch is committed (in point order) once
  // every point has a result. Partial results survive to_json / from_json, so an optimisation
  // interrupted in the middle of a batch does not evaluate its finished points again.
  void tell_one(const Batch& batch, std::size_t point, std::optional<double> value,
                const std::string& failure = {});
  // Results already known for the pending batch (after from_json of an interrupted run).
  [[nodiscard]] std::vector<std::optional<Evaluation>> pending_results() const { return partial_; }

  [[nodiscard]] const OptimizerConfig& config() const { return config_; }
  [[nodiscard]] const std::vector<Evaluation>& evaluations() const { return evaluations_; }
  [[nodiscard]] std::optional<Evaluation> best() const;
  [[nodiscard]] const std::string& stop_reason() const { return stop_reason_; }
  [[nodiscard]] int iterations() const { return next_batch_ - 1 < 0 ? 0 : next_batch_ - 1; }
  [[nodiscard]] int failures() const;
  // Best value after each batch (index 0: the initial design).
  [[nodiscard]] std::vector<double> best_history() const;
  // The surrogate's leave-one-out quality at the last fit (normalised RMSE), if any.
  [[nodiscard]] std::optional<double> last_loo_rmse() const { return loo_rmse_; }
  // The output transform of the last fit ("none" or "log"; "" before the first fit).
  [[nodiscard]] const std::string& last_transform() const { return transform_; }

  // Configuration, seed and evaluations; derived values (best, history) are included for readers
  // and ignored on load.
  [[nodiscard]] nlohmann::json to_json() const;
  // Replays the evaluations; throws std::runtime_error if they are not the points this version of
  // the optimizer proposes (a different configuration or version).
  static SurrogateOptimizer from_json(const nlohmann::json& j);

 private:
  [[nodiscard]] Eigen::VectorXd to_unit(const Eigen::VectorXd& x) const;
  [[nodiscard]] Eigen::VectorXd from_unit(const Eigen::VectorXd& u) const;
  Batch propose();
  bool should_stop();

  OptimizerConfig config_;
  std::vector<Evaluation> evaluations_;
  int next_batch_ = 0;
  std::optional<Batch> pending_;
  std::vector<std::optional<Evaluation>> partial_;  // results of pending_ told so far
  std::string stop_reason_;
  std::optional<double> loo_rmse_;
  std::string transform_;
};

nlohmann::json config_to_json(const OptimizerConfig& c);
OptimizerConfig config_from_json(const nlohmann::json& j);

}  // namespace auvloop::optimizer
