// SPDX-License-Identifier: GPL-3.0-or-later
// Output transforms of the surrogate (output_transform.hpp states them):
//   1. log: c from the data (0 if every value is positive, else a tenth of the range below the
//      smallest), g(y) = ln(y - c);
//   2. the Kriging fit of g(y) (theta by maximum likelihood on that scale);
//   3. auto: both fits, and the one with the smaller normalised closed-form leave-one-out RMSE
//      on its own scale kept (none on a tie).
#include "auvloop/optimizer/output_transform.hpp"

#include <cmath>
#include <stdexcept>

namespace auvloop::optimizer {

OutputTransform log_transform(const Eigen::VectorXd& y) {
  const double lo = y.minCoeff(), hi = y.maxCoeff();
  if (!(hi > lo)) return {};
  if (lo > 0) return {true, 0.0};
  return {true, lo - 0.1 * (hi - lo)};
}

double loo_rmse_in_y(const Kriging& model, const Eigen::VectorXd& y, const OutputTransform& t) {
  const Eigen::VectorXd e = model.loo_errors();  // g(y_i) - prediction_i, on the fitted scale
  double sum = 0;
  for (Eigen::Index i = 0; i < y.size(); ++i) {
    const double d = y[i] - t.inverse(t(y[i]) - e[i]);
    sum += d * d;
  }
  return std::sqrt(sum / static_cast<double>(y.size()));
}

TransformedFit fit_transformed(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                               const std::string& choice, const KrigingOptions& options) {
  if (choice != "none" && choice != "log" && choice != "auto")
    throw std::invalid_argument(
        "optimizer: output_transform must be \"none\", \"log\" or \"auto\"");
  const auto fit = [&](const OutputTransform& t) {
    Kriging model(X, t(y), options);
    const double loo = loo_rmse_in_y(model, y, t);
    return TransformedFit{t, std::move(model), loo};
  };
  const OutputTransform log = log_transform(y);
  if (choice == "none" || !log.log) return fit({});
  if (choice == "log") return fit(log);
  TransformedFit plain = fit({});
  TransformedFit logged = fit(log);
  return logged.model.loo_rmse_normalised() < plain.model.loo_rmse_normalised() ? std::move(logged)
                                                                                : std::move(plain);
}

}  // namespace auvloop::optimizer
