// spatial_order.hpp (private to learner/src) - an order of 2-D points that keeps neighbours
// together, for the fused E-step (estep_2d.hpp): it takes 2 or 4 consecutive points at a time
// and skips a component only when its term is negligible (paper eq. 1; below estep_2d.cpp's cut,
// exp(-37) of the largest) for all of them, which happens far more often when they lie close
// together; and it culls components per group of 64 consecutive points by the group's bounding
// box, which is small only in such an order. On the benchmark's 200 000 points, without the
// culling, this order takes a third fewer E-step instructions than the points' random order.
#ifndef GMMRRT_LEARNER_SPATIAL_ORDER_HPP
#define GMMRRT_LEARNER_SPATIAL_ORDER_HPP

#include <Eigen/Dense>
#include <cstdint>
#include <vector>

namespace gmmrrt {
namespace learn {
namespace detail {

// A permutation of N point numbers. An Eigen vector rather than a std::vector: it is made
// uninitialised, so the tasks that fill it take its pages' first-write faults on all threads
// (a std::vector zero-fills on the calling thread first: 0.8 ms of serial time for 200 000
// points, docs/learner.md).
//
// points: 2 x N, one point per column (FitMixture's input), finite; a dimension flagged in
// angle_mask is read wrapped into (-pi, pi] (AsFitValue, angle_dims.hpp), as the fit reads it.
// Returns a permutation (N point numbers): points sorted by the Morton (Z-order) index of their
// cell in a 64 x 64 grid over the bounding box, ties in the original order (counting sort: O(N),
// deterministic). A constant coordinate is fine. Runs on up to `threads` threads (>= 1): each
// task of points counts its cells, and task t's points of a cell go after those of tasks
// 0..t-1, so the order is the same for any thread count. It reads the input where it is, with no
// copy of the points (fresh memory costs a page fault per 4 KiB on its first write: see
// FitMixture).
using PointOrder = Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1>;
PointOrder SpatialOrder2d(const Eigen::MatrixXd& points, uint32_t angle_mask, int threads = 1);

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_SPATIAL_ORDER_HPP
