// wrap_difference.hpp (private to learner/src) - gmmrrt_wrap_angle (planner/src/features.c) for
// the difference of two wrapped angles, inline: k-means (kmeans.cpp) wraps one such difference
// per point, centre and iteration, and the library call was a fifth of a (d, theta) fit
// (callgrind). Angles on a seam are the point of the planner's features (paper Sect. 3).
#ifndef GMMRRT_LEARNER_WRAP_DIFFERENCE_HPP
#define GMMRRT_LEARNER_WRAP_DIFFERENCE_HPP

#include <cmath>

#include "gmmrrt/features.h"

namespace gmmrrt {
namespace learn {
namespace detail {

// The same bits as gmmrrt_wrap_angle(v) for every v [rad]: the result in (-pi, pi]. For
// |v| < 2 pi (two angles in (-pi, pi] differ by less) it performs the library's operations
// inline: there fmod(v + pi, 2 pi) is v + pi, or v + pi - 2 pi when v + pi >= 2 pi (exact by
// Sterbenz's lemma). Other v (and NaN) go to the library function.
inline double WrapDifference(double v) {
  if (v > -M_PI && v <= M_PI) return v;
  if (!(v > -2.0 * M_PI && v < 2.0 * M_PI)) return gmmrrt_wrap_angle(v);
  double a = v + M_PI;
  if (a >= 2.0 * M_PI) a -= 2.0 * M_PI;
  if (a <= 0.0) a += 2.0 * M_PI;
  return a - M_PI;
}

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_WRAP_DIFFERENCE_HPP
