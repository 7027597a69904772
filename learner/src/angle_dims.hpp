// angle_dims.hpp (private to learner/src) - which dimensions of a data set or mixture are angles:
// bit j of an angle mask (model.h: angle_mask) marks dimension j as a wrapped angle.
#ifndef GMMRRT_LEARNER_ANGLE_DIMS_HPP
#define GMMRRT_LEARNER_ANGLE_DIMS_HPP

#include <cstdint>

#include "gmmrrt/features.h"

namespace gmmrrt {
namespace learn {
namespace detail {

// 1 when dimension j is an angle under `mask` (dimensions from 32 on never are).
inline bool IsAngleDim(uint32_t mask, long j) { return j < 32 && ((mask >> j) & 1u); }

// Value v of dimension j as the fit reads it: an angle wrapped into (-pi, pi], anything else as
// given (the planner core's wrapping: features.h).
inline double AsFitValue(uint32_t mask, long j, double v) {
  return IsAngleDim(mask, j) ? gmmrrt_wrap_angle_inline(v) : v;
}

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt

#endif
