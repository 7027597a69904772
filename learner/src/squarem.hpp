// squarem.hpp (private to learner/src) - the extrapolation step of SQUAREM (Varadhan and Roland
// 2008, "Simple and globally convergent methods for accelerating the convergence of any EM
// algorithm", Scand. J. Statist. 35, scheme S3) for the mixtures of em.cpp.
//
// From three successive EM iterates theta0, theta1 = F(theta0), theta2 = F(theta1), with
// r = theta1 - theta0 and v = theta2 - theta1 - r, the step length s = |r| / |v| (clamped to
// [1, step_max]) gives theta' = theta0 + 2 s r + s^2 v; s = 1 gives theta2 itself. EM near an
// optimum moves along a slowly shrinking direction (the overlapping-components case, where the
// fraction of missing information is large); the extrapolation takes many such steps at once.
// The parameters are extrapolated in coordinates where the constraints hold by construction:
// log weights (renormalised), means (wrapped differences on angle dimensions), and the Cholesky
// factors with log diagonals (positive definite for any value). The caller keeps EM's
// monotonicity by evaluating theta' and falling back to theta2 when it is worse (em.cpp).
#ifndef GMMRRT_LEARNER_SQUAREM_HPP
#define GMMRRT_LEARNER_SQUAREM_HPP

#include <Eigen/Dense>

#include "gmmrrt_learner/mixture.hpp"

namespace gmmrrt {
namespace learn {
namespace detail {

// theta' from m0, m1, m2 (same K, D and angle mask, all valid). step_max >= 1 bounds s (the
// trust region of SQUAREM's step.max, grown by the caller while full steps succeed). min_var[j]
// is the smallest variance allowed on dimension j (the fit's regularisation): a result whose
// factor has L_jj^2 below it is refused, so a step cannot shrink a component onto a point.
// *wanted is |r| / |v| before clamping (set whenever r is not zero). Returns false (out
// untouched) when r is zero, or the result is not finite or refused; otherwise *out and *step
// (the s used).
bool SquaremExtrapolate(const Mixture& m0, const Mixture& m1, const Mixture& m2, double step_max,
                        const Eigen::VectorXd& min_var, Mixture* out, double* step, double* wanted);

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_SQUAREM_HPP
