// delta_quantile.cpp - the q-quantile of a mixture's density over its training points, the
// data-driven delta of the task cost c(f) = delta / max(p(f), delta) (paper Sect. 4).
// See delta_quantile.hpp for why.
#include "gmmrrt_learner/delta_quantile.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace gmmrrt {
namespace learn {

Status DensityQuantile(const Mixture& m, const Eigen::MatrixXd& points, double q, double* delta) {
  if (!(q >= 0.0 && q <= 1.0))
    return Status::Error(StatusCode::kInvalidArgument, "delta quantile " + std::to_string(q) + " is not in [0, 1]");
  if (points.cols() < 1) return Status::Error(StatusCode::kNotEnoughData, "no points for the delta quantile");
  Eigen::VectorXd logp;
  LogDensity(m, points, &logp);
  std::vector<double> p(static_cast<size_t>(logp.size()));
  for (Eigen::Index i = 0; i < logp.size(); ++i) p[static_cast<size_t>(i)] = std::exp(logp[i]);
  std::sort(p.begin(), p.end());
  const double pos = q * static_cast<double>(p.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(pos));
  const size_t hi = std::min(lo + 1, p.size() - 1);
  const double value = p[lo] + (pos - static_cast<double>(lo)) * (p[hi] - p[lo]);
  if (!(value > 0.0) || !std::isfinite(value))
    return Status::Error(StatusCode::kNumericalFailure,
                         "the density quantile is not a positive number (" + std::to_string(value) +
                             "): the mixture gives its own training points no density; use --delta");
  *delta = value;
  return Status::Ok();
}

}  // namespace learn
}  // namespace gmmrrt
