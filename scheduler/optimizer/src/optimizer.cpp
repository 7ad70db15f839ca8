// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/optimizer/optimizer.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>

#include "auvloop/optimizer/design.hpp"
#include "auvloop/optimizer/output_transform.hpp"
#include "random.hpp"

namespace auvloop::optimizer {
namespace {
using nlohmann::json;

// Two points closer than this (normalised) are the same point: never evaluate one twice.
constexpr double kDuplicate = 1e-6;

double normalised_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).norm() / std::sqrt(static_cast<double>(a.size()));
}

void validate(const OptimizerConfig& c) {
  const auto d = c.lower.size();
  if (d == 0 || c.upper.size() != d || static_cast<Eigen::Index>(c.names.size()) != d) {
    throw std::invalid_argument(
        "optimizer: names, lower and upper bounds must have one entry per dimension");
  }
  for (Eigen::Index k = 0; k < d; ++k) {
    if (!(c.lower[k] < c.upper[k])) {
      throw std::invalid_argument("optimizer: dimension \"" + c.names[static_cast<std::size_t>(k)] +
                                  "\" needs lower < upper");
    }
  }
  if (c.initial_points < 2)
    throw std::invalid_argument("optimizer: the initial design needs at least 2 points");
  if (c.batch_size < 1) throw std::invalid_argument("optimizer: batch_size must be at least 1");
  if (c.patience < 1) throw std::invalid_argument("optimizer: patience must be at least 1");
  if (c.max_iterations < 0) throw std::invalid_argument("optimizer: max_iterations must be >= 0");
  if (c.failure_policy != "classify" && c.failure_policy != "impute") {
    throw std::invalid_argument("optimizer: failure_policy must be \"classify\" or \"impute\"");
  }
  if (c.solver != "pso" && c.solver != "nlopt")
    throw std::invalid_argument("optimizer: solver must be \"pso\" or \"nlopt\"");
  if (c.output_transform != "none" && c.output_transform != "log" && c.output_transform != "auto")
    throw std::invalid_argument(
        "optimizer: output_transform must be \"none\", \"log\" or \"auto\"");
}

}  // namespace

SurrogateOptimizer::SurrogateOptimizer(OptimizerConfig config) : config_(std::move(config)) {
  validate(config_);
}

Eigen::VectorXd SurrogateOptimizer::to_unit(const Eigen::VectorXd& x) const {
  return (x - config_.lower).cwiseQuotient(config_.upper - config_.lower);
}

Eigen::VectorXd SurrogateOptimizer::from_unit(const Eigen::VectorXd& u) const {
  return config_.lower + u.cwiseProduct(config_.upper - config_.lower);
}

std::optional<Evaluation> SurrogateOptimizer::best() const {
  std::optional<Evaluation> b;
  for (const auto& e : evaluations_) {
    if (e.value && (!b || *e.value < *b->value)) b = e;
  }
  return b;
}

int SurrogateOptimizer::failures() const {
  int n = 0;
  for (const auto& e : evaluations_) n += e.value ? 0 : 1;
  return n;
}

std::vector<double> SurrogateOptimizer::best_history() const {
  std::vector<double> h;
  double best = std::numeric_limits<double>::infinity();
  for (int b = 0; b < next_batch_; ++b) {
    for (const auto& e : evaluations_) {
      if (e.batch == b && e.value) best = std::min(best, *e.value);
    }
    h.push_back(best);
  }
  return h;
}

bool SurrogateOptimizer::should_stop() {
  const auto h = best_history();
  const int k = next_batch_ - 1;  // the last infill iteration told
  if (k < config_.patience) return false;
  for (int i = 0; i < config_.patience; ++i) {
    const double now = h[static_cast<std::size_t>(k - i)],
                 before = h[static_cast<std::size_t>(k - i - 1)];
    const double tol =
        config_.relative_epsilon ? config_.epsilon * std::abs(before) : config_.epsilon;
    if (!(std::abs(now - before) < tol)) return false;
  }
  stop_reason_ =
      config_.patience == 1
          ? "converged: the best value improved by less than epsilon in the last iteration"
          : "converged: the best value improved by less than epsilon in " +
                std::to_string(config_.patience) + " consecutive iterations";
  return true;
}

std::optional<Batch> SurrogateOptimizer::ask() {
  if (!stop_reason_.empty()) return std::nullopt;
  if (pending_) return pending_;
  if (next_batch_ >= 2 && should_stop()) return std::nullopt;
  if (next_batch_ > config_.max_iterations) {
    stop_reason_ = "maximum number of iterations reached";
    return std::nullopt;
  }
  Batch b = propose();
  if (b.points.empty()) return std::nullopt;  // propose() set the reason
  pending_ = std::move(b);
  partial_.assign(pending_->points.size(), std::nullopt);
  return pending_;
}

Batch SurrogateOptimizer::propose() {
  const auto d = static_cast<int>(config_.lower.size());
  Batch batch;
  batch.index = next_batch_;
  if (next_batch_ == 0) {
    const Eigen::MatrixXd u = latin_hypercube(config_.initial_points, d, config_.seed);
    for (Eigen::Index i = 0; i < u.rows(); ++i) {
      batch.points.push_back(from_unit(u.row(i).transpose()));
      batch.origins.emplace_back("lhs");
    }
    return batch;
  }
  // Data for the fit: successes, plus (policy "impute") failures at the worst observed value.
  std::vector<Eigen::VectorXd> xs, all_x;
  std::vector<double> ys, success;
  double worst = -std::numeric_limits<double>::infinity();
  for (const auto& e : evaluations_) {
    if (e.value) worst = std::max(worst, *e.value);
  }
  const bool impute = config_.failure_policy == "impute";
  for (const auto& e : evaluations_) {
    all_x.push_back(to_unit(e.x));
    success.push_back(e.value ? 1.0 : 0.0);
    if (e.value || (impute && std::isfinite(worst))) {
      xs.push_back(to_unit(e.x));
      ys.push_back(e.value ? *e.value : worst);
    }
  }
  const auto best_eval = best();
  if (!best_eval || xs.size() < 2) {
    stop_reason_ = "too few successful evaluations to fit a surrogate";
    return batch;
  }
  Eigen::MatrixXd X(static_cast<Eigen::Index>(xs.size()), d);
  for (std::size_t i = 0; i < xs.size(); ++i)
    X.row(static_cast<Eigen::Index>(i)) = xs[i].transpose();
  const Eigen::VectorXd y =
      Eigen::Map<const Eigen::VectorXd>(ys.data(), static_cast<Eigen::Index>(ys.size()));
  // The surrogate on the configured scale (output_transform.hpp): everything below works on g(y).
  const TransformedFit fitted = fit_transformed(X, y, config_.output_transform, config_.kriging);
  const Kriging& model = fitted.model;
  const OutputTransform& g = fitted.transform;
  const Eigen::VectorXd gy = g(y);
  loo_rmse_ = model.loo_rmse_normalised();
  transform_ = g.name();
  // Probability that an evaluation at x succeeds, from a Kriging model of the success indicator.
  std::optional<Kriging> feasibility;
  if (!impute && failures() > 0) {
    Eigen::MatrixXd A(static_cast<Eigen::Index>(all_x.size()), d);
    for (std::size_t i = 0; i < all_x.size(); ++i)
      A.row(static_cast<Eigen::Index>(i)) = all_x[i].transpose();
    feasibility.emplace(A,
                        Eigen::Map<const Eigen::VectorXd>(
                            success.data(), static_cast<Eigen::Index>(success.size())),
                        config_.kriging);
  }
  // P(indicator > 1/2) under the classifier's predictive distribution: near known failures the
  // mean is low and certain, so P vanishes; far from all data it tends to one half.
  auto p_success = [&](const Eigen::VectorXd& x) {
    if (!feasibility) return 1.0;
    const Prediction p = feasibility->predict(x);
    const double s = std::sqrt(std::max(p.variance, 1e-12));
    return 0.5 * std::erfc(-(p.mean - 0.5) / (s * std::numbers::sqrt2));
  };
  // Known failures are points to avoid, not merely to skip: their neighbourhood stays out.
  for (std::size_t i = 0; i < all_x.size(); ++i) {
    if (success[i] == 0.0) xs.push_back(all_x[i]);
  }

  const double f_min = g(*best_eval->value);
  const Eigen::VectorXd u_best = to_unit(best_eval->x);
  const std::uint64_t seed =
      detail::Random::mix(config_.seed, static_cast<std::uint64_t>(next_batch_));
  int solves = 0;
  auto solve = [&](const UnitObjective& f) {
    const std::uint64_t s = detail::Random::mix(seed, static_cast<std::uint64_t>(solves++));
    return config_.solver == "nlopt" ? nlopt_minimize(f, d, s, config_.nlopt_starts, {u_best})
                                     : pso_minimize(f, d, s, config_.pso, {u_best});
  };
  auto is_new = [&](const Eigen::VectorXd& u, const std::vector<Eigen::VectorXd>& chosen) {
    for (const auto& x : xs) {
      if (normalised_distance(u, x) <= kDuplicate) return false;
    }
    for (const auto& c : chosen) {
      if (normalised_distance(u, c) <= kDuplicate) return false;
    }
    return true;
  };
  std::vector<Eigen::VectorXd> chosen;
  std::vector<std::string> origins;
  // EI, then (q > 2) further EI points on a "kriging believer" surrogate that takes each chosen
  // point's prediction as observed, theta held.
  Eigen::MatrixXd Xb = X;
  Eigen::VectorXd yb = gy;
  const int ei_points = std::max(1, config_.batch_size - 1);
  for (int j = 0; j < ei_points; ++j) {
    const Kriging believer = j == 0 ? model : Kriging(Xb, yb, model.theta(), config_.kriging);
    const Eigen::VectorXd u = solve([&](const Eigen::VectorXd& x) {
      const Prediction p = believer.predict(x);
      return -expected_improvement(p.mean, p.variance, f_min) * p_success(x);
    });
    if (is_new(u, chosen)) {
      chosen.push_back(u);
      origins.emplace_back(j == 0 ? "ei" : "believer");
    }
    Xb.conservativeResize(Xb.rows() + 1, Eigen::NoChange);
    Xb.row(Xb.rows() - 1) = u.transpose();
    yb.conservativeResize(yb.size() + 1);
    yb[yb.size() - 1] = believer.predict(u).mean;
  }
  if (config_.batch_size >= 2) {
    // MSP where success is likely: outside, the prediction is raised by the data's full range.
    const double range = gy.maxCoeff() - gy.minCoeff();
    const Eigen::VectorXd u = solve([&](const Eigen::VectorXd& x) {
      return model.predict(x).mean + (p_success(x) < 0.5 ? range : 0.0);
    });
    bool near_ei = false;
    for (const auto& c : chosen)
      near_ei = near_ei || normalised_distance(u, c) <= config_.msp_drop_distance;
    if (!near_ei && is_new(u, chosen)) {
      chosen.push_back(u);
      origins.emplace_back("msp");
    }
  }
  if (chosen.empty()) {
    // Every proposal repeats a sample: explore where the surrogate is least certain instead.
    const Eigen::VectorXd u =
        solve([&](const Eigen::VectorXd& x) { return -model.predict(x).variance; });
    if (is_new(u, chosen)) {
      chosen.push_back(u);
      origins.emplace_back("explore");
    } else {
      stop_reason_ = "no new point to evaluate: every proposal repeats a sample";
      return batch;
    }
  }
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    batch.points.push_back(from_unit(chosen[i]));
    batch.origins.push_back(origins[i]);
  }
  return batch;
}

void SurrogateOptimizer::tell_one(const Batch& batch, std::size_t point,
                                  std::optional<double> value, const std::string& failure) {
  if (!pending_ || batch.index != pending_->index) {
    throw std::logic_error("optimizer: tell() must answer the batch returned by ask()");
  }
  if (point >= pending_->points.size())
    throw std::invalid_argument("optimizer: no such point in the batch");
  Evaluation e;
  e.batch = batch.index;
  e.origin = pending_->origins[point];
  e.x = pending_->points[point];
  if (value && std::isfinite(*value)) {
    e.value = value;
  } else {
    e.failure = failure.empty() ? "no finite value" : failure;
  }
  partial_[point] = std::move(e);
  for (const auto& r : partial_) {
    if (!r) return;
  }
  for (auto& r : partial_) evaluations_.push_back(std::move(*r));
  partial_.clear();
  pending_.reset();
  ++next_batch_;
}

void SurrogateOptimizer::tell(const Batch& batch, const std::vector<std::optional<double>>& values,
                              const std::vector<std::string>& failures) {
  if (!pending_ || values.size() != pending_->points.size() ||
      (!failures.empty() && failures.size() != values.size())) {
    throw std::invalid_argument("optimizer: one value (or failure) per point of the pending batch");
  }
  for (std::size_t i = 0; i < values.size(); ++i)
    tell_one(batch, i, values[i], failures.empty() ? "" : failures[i]);
}

json config_to_json(const OptimizerConfig& c) {
  return {{"names", c.names},
          {"lower", std::vector<double>(c.lower.data(), c.lower.data() + c.lower.size())},
          {"upper", std::vector<double>(c.upper.data(), c.upper.data() + c.upper.size())},
          {"initial_points", c.initial_points},
          {"max_iterations", c.max_iterations},
          {"epsilon", c.epsilon},
          {"relative_epsilon", c.relative_epsilon},
          {"patience", c.patience},
          {"batch_size", c.batch_size},
          {"msp_drop_distance", c.msp_drop_distance},
          {"solver", c.solver},
          {"pso",
           {{"particles", c.pso.particles},
            {"iterations", c.pso.iterations},
            {"inertia", c.pso.inertia},
            {"cognitive", c.pso.cognitive},
            {"social", c.pso.social},
            {"max_velocity", c.pso.max_velocity}}},
          {"nlopt_starts", c.nlopt_starts},
          {"kriging",
           {{"theta_min", c.kriging.theta_min},
            {"theta_max", c.kriging.theta_max},
            {"starts", c.kriging.starts},
            {"max_condition", c.kriging.max_condition}}},
          {"failure_policy", c.failure_policy},
          {"output_transform", c.output_transform},
          {"seed", c.seed}};
}

OptimizerConfig config_from_json(const json& j) {
  OptimizerConfig c;
  c.names = j.at("names").get<std::vector<std::string>>();
  const auto lo = j.at("lower").get<std::vector<double>>(),
             hi = j.at("upper").get<std::vector<double>>();
  c.lower = Eigen::Map<const Eigen::VectorXd>(lo.data(), static_cast<Eigen::Index>(lo.size()));
  c.upper = Eigen::Map<const Eigen::VectorXd>(hi.data(), static_cast<Eigen::Index>(hi.size()));
  c.initial_points = j.at("initial_points");
  c.max_iterations = j.at("max_iterations");
  c.epsilon = j.at("epsilon");
  c.relative_epsilon = j.at("relative_epsilon");
  c.patience = j.at("patience");
  c.batch_size = j.at("batch_size");
  c.msp_drop_distance = j.at("msp_drop_distance");
  c.solver = j.at("solver");
  const auto& p = j.at("pso");
  c.pso = {p.at("particles"), p.at("iterations"), p.at("inertia"),
           p.at("cognitive"), p.at("social"),     p.at("max_velocity")};
  c.nlopt_starts = j.at("nlopt_starts");
  const auto& k = j.at("kriging");
  c.kriging = {k.at("theta_min"), k.at("theta_max"), k.at("starts"), k.at("max_condition")};
  c.failure_policy = j.at("failure_policy");
  c.output_transform = j.value("output_transform", "none");  // states written before it existed
  c.seed = j.at("seed").get<std::uint64_t>();
  return c;
}

json SurrogateOptimizer::to_json() const {
  json evals = json::array();
  std::vector<Evaluation> all = evaluations_;
  for (const auto& r : partial_) {
    if (r) all.push_back(*r);
  }
  for (std::size_t i = 0; i < all.size(); ++i) {
    const auto& e = all[i];
    // The point's index within its batch lets a partial batch be replayed in any order.
    std::size_t point = 0;
    for (std::size_t j = 0; j < i; ++j) point += all[j].batch == e.batch ? 1U : 0U;
    if (i >= evaluations_.size()) {
      for (std::size_t k = 0; k < partial_.size(); ++k) {
        if (partial_[k] && partial_[k]->x == e.x) point = k;
      }
    }
    evals.push_back({{"batch", e.batch},
                     {"point", point},
                     {"origin", e.origin},
                     {"x", std::vector<double>(e.x.data(), e.x.data() + e.x.size())},
                     {"value", e.value ? json(*e.value) : json(nullptr)},
                     {"failure", e.failure}});
  }
  json j{{"config", config_to_json(config_)}, {"evaluations", evals}};
  // Derived, for readers; ignored by from_json.
  const auto b = best();
  j["best"] = b ? json{{"x", std::vector<double>(b->x.data(), b->x.data() + b->x.size())},
                       {"value", *b->value}}
                : json(nullptr);
  j["best_history"] = best_history();
  j["failures"] = failures();
  j["stop_reason"] = stop_reason_;
  return j;
}

SurrogateOptimizer SurrogateOptimizer::from_json(const json& j) {
  SurrogateOptimizer opt(config_from_json(j.at("config")));
  std::map<int, std::vector<const json*>> batches;
  for (const auto& e : j.at("evaluations")) batches[e.at("batch").get<int>()].push_back(&e);
  for (const auto& [index, evals] : batches) {
    const auto batch = opt.ask();
    if (!batch || batch->index != index || batch->points.size() < evals.size()) {
      throw std::runtime_error(
          "optimizer state: batch " + std::to_string(index) +
          " does not match what this optimizer proposes (different configuration or version)");
    }
    for (const json* e : evals) {
      const auto i = e->value("point", std::size_t{0});
      const auto x = e->at("x").get<std::vector<double>>();
      const Eigen::VectorXd xs =
          Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
      if (i >= batch->points.size() || xs != batch->points[i]) {
        throw std::runtime_error("optimizer state: point " + std::to_string(i) + " of batch " +
                                 std::to_string(index) + " differs from the replayed proposal");
      }
      const auto& v = e->at("value");
      opt.tell_one(*batch, i, v.is_null() ? std::nullopt : std::optional<double>(v.get<double>()),
                   e->value("failure", ""));
    }
  }
  return opt;
}

}  // namespace auvloop::optimizer
