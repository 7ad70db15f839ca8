// SPDX-License-Identifier: GPL-3.0-or-later
// Ordinary Kriging (Jones, Schonlau & Welch 1998; Forrester, Sobester & Keane 2008, ch. 2):
//   y(x) = mu + Z(x),  corr(Z(x), Z(x')) = exp(-sum_k theta_k (x_k - x'_k)^2),
// on inputs scaled to [0, 1]^d and outputs standardised to zero mean and unit variance. mu and the
// process variance sigma^2 are profiled out (generalised least squares), and theta maximises the
// concentrated log-likelihood  -n/2 ln(sigma^2) - 1/2 ln|R|  over log10(theta) in the bounds,
// with NLopt's L-BFGS and the analytic gradient from several deterministic starts. When R is
// ill-conditioned a nugget is added to its diagonal, growing tenfold until the Cholesky
// factorisation succeeds with a bounded condition estimate.
#pragma once

#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace auvloop::optimizer {

struct KrigingOptions {
  double theta_min = 1e-2;  // bounds on theta, per dimension, on [0, 1]-scaled inputs
  double theta_max = 10.0;
  int starts = 5;               // likelihood optimisation starts (deterministic)
  double max_condition = 1e12;  // of R, estimated from the Cholesky diagonal
};

struct Prediction {
  double mean = 0;
  double variance = 0;  // ordinary-Kriging mean squared error, including the mean's uncertainty
};

class Kriging {
 public:
  // X: n x d in [0, 1]^d, y: n values. Fits theta by maximum likelihood.
  Kriging(Eigen::MatrixXd X, Eigen::VectorXd y, KrigingOptions options = {});
  // Same, with theta fixed (no likelihood optimisation): used for batch "believer" updates.
  Kriging(Eigen::MatrixXd X, Eigen::VectorXd y, Eigen::VectorXd theta, KrigingOptions options = {});

  [[nodiscard]] Prediction predict(const Eigen::VectorXd& x) const;
  [[nodiscard]] const Eigen::VectorXd& theta() const { return theta_; }
  [[nodiscard]] double nugget() const { return nugget_; }
  [[nodiscard]] double log_likelihood() const { return log_likelihood_; }
  // Leave-one-out cross-validation errors (closed form, theta fixed), in units of y.
  [[nodiscard]] Eigen::VectorXd loo_errors() const;
  // Root mean square of the LOO errors divided by the standard deviation of y: < 1 means the
  // surrogate predicts better than the mean.
  [[nodiscard]] double loo_rmse_normalised() const;

  // Concentrated log-likelihood of the standardised data and its gradient with respect to
  // log10(theta); public so that tests can check the gradient against finite differences.
  static double concentrated_likelihood(const Eigen::MatrixXd& X, const Eigen::VectorXd& y_std,
                                        const Eigen::VectorXd& log10_theta, double nugget,
                                        Eigen::VectorXd* gradient);

 private:
  void standardise(const Eigen::VectorXd& y);
  void factorise();
  void fit_theta();

  Eigen::MatrixXd X_;
  Eigen::VectorXd y_;  // standardised
  double y_mean_ = 0, y_scale_ = 1;
  KrigingOptions options_;
  Eigen::VectorXd theta_;
  double nugget_ = 0;
  double log_likelihood_ = 0;
  // Factorisation at theta_: R = L L^T, mu, sigma^2, R^-1 (y - mu 1), R^-1 1.
  Eigen::LLT<Eigen::MatrixXd> llt_;
  double mu_ = 0, sigma2_ = 0, one_rinv_one_ = 0;
  Eigen::VectorXd rinv_residual_, rinv_one_;
};

}  // namespace auvloop::optimizer
