// SPDX-License-Identifier: GPL-3.0-or-later
// Output transforms of the surrogate (docs/optimization.md, "Output transforms"). Objectives such
// as ITAE span orders of magnitude across a design (750 to 30,000 deg s^2 for the paper's PID
// bounds on the derivative plant), which a stationary Gaussian process fits badly; the
// logarithm of such data is closer to stationary (Jones, Schonlau & Welch 1998 fit log y for
// Goldstein-Price). The Kriging model itself standardises whatever it is given (kriging.hpp).
//
//   none: g(y) = y
//   log:  g(y) = ln(y - c); c = 0 when every value is positive (ln y, free of the objective's
//         scale), else c = y_min - 0.1 (y_max - y_min), so that the smallest value sits a tenth
//         of the data's range above the pole (no single point becomes an outlier of the fit);
//         none when every value is the same.
//
// g is increasing, so the minima are the same points on either scale: the optimizer fits the
// surrogate to g(y), takes EI against g(f_min) and the MSP point of the g-scale prediction, all
// on the transformed scale; the stopping rule and every reported value stay in y.
//
// auto: per fit, the transform whose Kriging model has the smaller normalised leave-one-out
// RMSE, each on its own scale (the RMSE over the standard deviation of the data it was fitted
// to: scale-free, as Jones et al. compare transforms by standardised cross-validated residuals);
// none on a tie. (Measured first in y's units, each left-out prediction mapped back by g^-1: that
// RMSE is dominated by the largest values, far from the minimum; it chose none on every test
// problem as well.)
#pragma once

#include <cmath>
#include <string>

#include <Eigen/Core>

#include "auvloop/optimizer/kriging.hpp"

namespace auvloop::optimizer {

struct OutputTransform {
  bool log = false;
  double shift = 0;  // c
  [[nodiscard]] double operator()(double y) const { return log ? std::log(y - shift) : y; }
  [[nodiscard]] double inverse(double g) const { return log ? std::exp(g) + shift : g; }
  [[nodiscard]] Eigen::VectorXd operator()(const Eigen::VectorXd& y) const {
    return y.unaryExpr([this](double v) { return (*this)(v); });
  }
  [[nodiscard]] std::string name() const { return log ? "log" : "none"; }
};

// The log transform of these data (none when they are all equal).
OutputTransform log_transform(const Eigen::VectorXd& y);

// Leave-one-out RMSE of `model` (fitted to t(y)) in y's units.
double loo_rmse_in_y(const Kriging& model, const Eigen::VectorXd& y, const OutputTransform& t);

// A model fitted to the data on the chosen scale. `choice`: "none", "log" or "auto".
struct TransformedFit {
  OutputTransform transform;
  Kriging model;
  double loo_rmse = 0;  // in y's units (loo_rmse_in_y), for reports
};
TransformedFit fit_transformed(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                               const std::string& choice, const KrigingOptions& options);

}  // namespace auvloop::optimizer
