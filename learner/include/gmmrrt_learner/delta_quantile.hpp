// delta_quantile.hpp - a data-driven delta for the task cost c(f) = delta / max(p(f), delta)
// (paper Sect. 4): the q-quantile of the fitted mixture's own density p over its training points.
//
// Why: the paper's fixed delta = 0.001 is in the units of p (1/(m rad) for (d, theta)), so its
// effect depends on how spread out a model is; with the demonstrations' models p is ~0.05-1 over
// their support, c is ~0 there and the planner hugs the support's inner edge. With delta = the
// q-quantile, a fraction q of the training points lies where c = 1 and the rest is graded by
// delta / p, whatever the model's scale. Evidence and the chosen q: docs/planner.md ("What delta does").
#ifndef GMMRRT_LEARNER_DELTA_QUANTILE_HPP
#define GMMRRT_LEARNER_DELTA_QUANTILE_HPP

#include <Eigen/Dense>

#include "gmmrrt_learner/mixture.hpp"
#include "gmmrrt_learner/status.hpp"

namespace gmmrrt {
namespace learn {

// The q-quantile (0 <= q <= 1; linear interpolation between order statistics, numpy's default)
// of p(x_n) = exp(LogDensity) over the columns of points (D x N, N >= 1) into *delta.
// kInvalidArgument for q outside [0, 1] or NaN, kNotEnoughData for no points, kNumericalFailure
// when the quantile is not a positive finite number (every density underflowed): a delta must be > 0.
Status DensityQuantile(const Mixture& m, const Eigen::MatrixXd& points, double q, double* delta);

}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_DELTA_QUANTILE_HPP
