// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/optimizer/kriging.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <nlopt.hpp>

#include "auvloop/optimizer/design.hpp"

namespace auvloop::optimizer {
namespace {

Eigen::MatrixXd correlation(const Eigen::MatrixXd& X, const Eigen::VectorXd& theta, double nugget) {
  const Eigen::Index n = X.rows();
  Eigen::MatrixXd R(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    R(i, i) = 1 + nugget;
    for (Eigen::Index j = i + 1; j < n; ++j) {
      R(i, j) = R(j, i) =
          std::exp(-(theta.array() * (X.row(i) - X.row(j)).transpose().array().square()).sum());
    }
  }
  return R;
}

// Numerical jitter always on the diagonal: (10 + n) machine epsilons (Forrester et al. 2008).
double base_nugget(Eigen::Index n) {
  return (10.0 + static_cast<double>(n)) * std::numeric_limits<double>::epsilon();
}

bool well_conditioned(const Eigen::LLT<Eigen::MatrixXd>& llt, double max_condition) {
  if (llt.info() != Eigen::Success) return false;
  const Eigen::VectorXd d = llt.matrixLLT().diagonal();
  if (d.minCoeff() <= 0) return false;
  const double ratio = d.maxCoeff() / d.minCoeff();
  return ratio * ratio <= max_condition;  // the squared ratio bounds-from-below cond(R)
}

}  // namespace

double Kriging::concentrated_likelihood(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                                        const Eigen::VectorXd& log10_theta, double nugget,
                                        Eigen::VectorXd* gradient) {
  const Eigen::Index n = X.rows(), d = X.cols();
  const Eigen::VectorXd theta = log10_theta.unaryExpr([](double t) { return std::pow(10.0, t); });
  const Eigen::MatrixXd R = correlation(X, theta, nugget);
  const Eigen::LLT<Eigen::MatrixXd> llt(R);
  if (llt.info() != Eigen::Success) {
    if (gradient != nullptr) gradient->setZero(d);
    return -1e300;  // not positive definite at this theta: the optimizer moves away
  }
  const Eigen::VectorXd one = Eigen::VectorXd::Ones(n);
  const Eigen::VectorXd rinv_one = llt.solve(one);
  const double mu = rinv_one.dot(y) / rinv_one.sum();
  const Eigen::VectorXd rinv_res = llt.solve(y - mu * one);
  const double sigma2 = std::max((y - mu * one).dot(rinv_res) / static_cast<double>(n), 1e-300);
  const double logdet = 2 * llt.matrixLLT().diagonal().array().log().sum();
  const double L = -0.5 * static_cast<double>(n) * std::log(sigma2) - 0.5 * logdet;
  if (gradient != nullptr) {
    // dL/dtheta_k = 1/2 sum_ij Q_ij dR_ij/dtheta_k with Q = r r^T / sigma^2 - R^-1 and
    // dR_ij/dtheta_k = -(x_ik - x_jk)^2 R_ij; times theta_k ln 10 for log10(theta).
    const Eigen::MatrixXd Q =
        rinv_res * rinv_res.transpose() / sigma2 - llt.solve(Eigen::MatrixXd::Identity(n, n));
    gradient->setZero(d);
    for (Eigen::Index i = 0; i < n; ++i) {
      for (Eigen::Index j = i + 1; j < n; ++j) {
        const double w = Q(i, j) * R(i, j);  // both (i, j) and (j, i): the 1/2 cancels
        for (Eigen::Index k = 0; k < d; ++k) {
          const double dx = X(i, k) - X(j, k);
          (*gradient)[k] -= w * dx * dx;
        }
      }
    }
    *gradient = gradient->cwiseProduct(theta) * std::numbers::ln10;
  }
  return L;
}

Kriging::Kriging(Eigen::MatrixXd X, Eigen::VectorXd y, KrigingOptions options)
    : X_(std::move(X)), options_(options) {
  standardise(y);
  fit_theta();
  factorise();
}

Kriging::Kriging(Eigen::MatrixXd X, Eigen::VectorXd y, Eigen::VectorXd theta,
                 KrigingOptions options)
    : X_(std::move(X)), options_(options), theta_(std::move(theta)) {
  standardise(y);
  factorise();
}

void Kriging::standardise(const Eigen::VectorXd& y) {
  if (X_.rows() < 2 || X_.rows() != y.size()) {
    throw std::invalid_argument("Kriging: need at least two samples");
  }
  y_mean_ = y.mean();
  const double sd = std::sqrt((y.array() - y_mean_).square().sum() / static_cast<double>(y.size()));
  y_scale_ = sd > 0 ? sd : 1.0;  // a constant response keeps its scale
  y_ = (y.array() - y_mean_) / y_scale_;
}

void Kriging::fit_theta() {
  const auto d = static_cast<int>(X_.cols());
  const double lo = std::log10(options_.theta_min), hi = std::log10(options_.theta_max);
  const double nugget = base_nugget(X_.rows());
  // Deterministic starts: the centre of the log box, then a Latin hypercube in it.
  Eigen::MatrixXd starts(options_.starts, d);
  starts.row(0).setConstant(0.5 * (lo + hi));
  if (options_.starts > 1) {
    starts.bottomRows(options_.starts - 1) =
        (lo + (hi - lo) * latin_hypercube(options_.starts - 1, d, 20240917, 1, 0).array()).matrix();
  }
  struct Data {
    const Eigen::MatrixXd* X;
    const Eigen::VectorXd* y;
    double nugget;
  } data{&X_, &y_, nugget};
  auto objective = [](const std::vector<double>& t, std::vector<double>& grad, void* raw) {
    const auto* dd = static_cast<const Data*>(raw);
    Eigen::VectorXd g;
    const double L = concentrated_likelihood(
        *dd->X, *dd->y,
        Eigen::Map<const Eigen::VectorXd>(t.data(), static_cast<Eigen::Index>(t.size())),
        dd->nugget, grad.empty() ? nullptr : &g);
    for (std::size_t k = 0; k < grad.size(); ++k) grad[k] = g[static_cast<Eigen::Index>(k)];
    return L;
  };
  double best = -std::numeric_limits<double>::infinity();
  Eigen::VectorXd best_t = starts.row(0).transpose();
  for (int s = 0; s < options_.starts; ++s) {
    nlopt::opt opt(nlopt::LD_LBFGS, static_cast<unsigned>(d));
    opt.set_lower_bounds(std::vector<double>(static_cast<std::size_t>(d), lo));
    opt.set_upper_bounds(std::vector<double>(static_cast<std::size_t>(d), hi));
    opt.set_max_objective(objective, &data);
    opt.set_maxeval(200);
    opt.set_xtol_rel(1e-8);
    std::vector<double> t(starts.row(s).data(), starts.row(s).data() + d);
    for (int k = 0; k < d; ++k) t[static_cast<std::size_t>(k)] = starts(s, k);
    double value = -std::numeric_limits<double>::infinity();
    try {
      opt.optimize(t, value);
    } catch (const std::exception&) {
      // Round-off limited or similar: L-BFGS still leaves its best point in t.
      value = concentrated_likelihood(X_, y_, Eigen::Map<const Eigen::VectorXd>(t.data(), d),
                                      nugget, nullptr);
    }
    if (value > best) {
      best = value;
      best_t = Eigen::Map<const Eigen::VectorXd>(t.data(), d);
    }
  }
  theta_ = best_t.unaryExpr([](double t) { return std::pow(10.0, t); });
}

void Kriging::factorise() {
  const Eigen::Index n = X_.rows();
  nugget_ = base_nugget(n);
  for (;;) {
    llt_.compute(correlation(X_, theta_, nugget_));
    if (well_conditioned(llt_, options_.max_condition) || nugget_ > 1e-2) break;
    nugget_ *= 10;
  }
  if (llt_.info() != Eigen::Success)
    throw std::runtime_error("Kriging: correlation matrix not positive definite");
  const Eigen::VectorXd one = Eigen::VectorXd::Ones(n);
  rinv_one_ = llt_.solve(one);
  one_rinv_one_ = rinv_one_.sum();
  mu_ = rinv_one_.dot(y_) / one_rinv_one_;
  rinv_residual_ = llt_.solve(y_ - mu_ * one);
  sigma2_ = std::max((y_ - mu_ * one).dot(rinv_residual_) / static_cast<double>(n), 1e-300);
  log_likelihood_ = -0.5 * static_cast<double>(n) * std::log(sigma2_) -
                    llt_.matrixLLT().diagonal().array().log().sum();
}

Prediction Kriging::predict(const Eigen::VectorXd& x) const {
  const Eigen::Index n = X_.rows();
  Eigen::VectorXd r(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    r[i] = std::exp(-(theta_.array() * (X_.row(i).transpose() - x).array().square()).sum());
  }
  const Eigen::VectorXd rinv_r = llt_.solve(r);
  const double mean = mu_ + r.dot(rinv_residual_);
  const double gap = 1 - rinv_one_.dot(r);
  const double mse = sigma2_ * (1 - r.dot(rinv_r) + gap * gap / one_rinv_one_);
  return {y_mean_ + y_scale_ * mean, y_scale_ * y_scale_ * std::max(0.0, mse)};
}

Eigen::VectorXd Kriging::loo_errors() const {
  // Dubrule (1983): e_i = [R^-1 (y - mu)]_i / [R^-1]_ii, with theta and mu held.
  const Eigen::MatrixXd rinv = llt_.solve(Eigen::MatrixXd::Identity(X_.rows(), X_.rows()));
  return y_scale_ * rinv_residual_.cwiseQuotient(rinv.diagonal());
}

double Kriging::loo_rmse_normalised() const {
  const Eigen::VectorXd e = loo_errors() / y_scale_;
  return std::sqrt(e.squaredNorm() / static_cast<double>(e.size()));
}

}  // namespace auvloop::optimizer
