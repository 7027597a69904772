// estep_2d.hpp (private to learner/src) - the E-step specialised for D = 2 (paper eq. 1): the
// benchmark's and generic 2-D features without angles, and the planner's (d, theta) features
// with theta wrapped (angle on dimension 1, 3 images as in gmm.h). It returns the same quantities as the general E-step of em.cpp (component_terms.hpp):
// per-point log-likelihood and the responsibility-weighted moments around the current means,
// in one fused pass, without heap allocation per point (one scratch block per task of 8192
// points) and with a closed-form 2x2 Mahalanobis term.
#ifndef GMMRRT_LEARNER_ESTEP_2D_HPP
#define GMMRRT_LEARNER_ESTEP_2D_HPP

#include <Eigen/Dense>
#include <vector>

#include "gmmrrt_learner/mixture.hpp"

namespace gmmrrt {
namespace learn {
namespace detail {

// Responsibility-weighted sums of one E-step, per component i, with y = x - mu_i:
// n[i] = sum r, m0/m1 = sum r y_0 / y_1, s00/s01/s11 = sum r y_0 y_0 / y_0 y_1 / y_1 y_1.
struct Moments2d {
  std::vector<double> n, m0, m1, s00, s01, s11;
};

// True when EStep2d handles D-dimensional data or mixtures with this angle mask (and so when
// FitMixture puts the points in spatial order for it): D = 2, and no angle dimension or the
// angle on dimension 1.
inline bool EStep2dApplies(int dim, uint32_t angle_mask) {
  return dim == 2 && (angle_mask == 0u || angle_mask == 2u);
}
inline bool EStep2dApplies(const Mixture& m) { return EStep2dApplies(m.dim, m.angle_mask); }

// Which compiled kernel runs: kAuto takes AVX2 when the CPU has it; kAvx2 falls back to the
// baseline when it does not (tests compare the two).
enum class Simd { kAuto, kBaseline, kAvx2 };

// True when this build has the AVX2 kernel and the CPU runs it.
bool EStep2dAvx2Available();

// x0, x1: the two coordinates of n_points >= 1 points (contiguous arrays, caller-owned); with
// the angle (angle_mask 2), x1 and the means' angle row must be in (-pi, pi] (FitMixture wraps
// them). m must be valid and EStep2dApplies(m). Writes point_ll[p] = log sum_i w_i N(x_p; mu_i,
// Sigma_i) (wrapped normal over 3 images with the angle; n_points entries, caller-owned) and
// *moments (resized to K; y = x - mu_i with the angle coordinate unwrapped per image, as the
// general E-step); returns the mean of point_ll. Deterministic: a fixed summation order (2
// lanes on the baseline kernel, 4 on the AVX2 one; blocks of 512 points; chunks of 8192 points,
// which run on up to `threads` threads and are added in chunk order): the two kernels agree up
// to rounding (same machine, same kernel -> same bits, for any thread count). Terms
// (component, image) are culled per group of 64 points by bounds over the group's bounding box
// (a term is skipped only where every point's term is below the negligible cut, which the
// per-point code would have set to 0): the same bits as cull = false (tested), and fewer
// operations when the points come in spatial order.
double EStep2d(const Mixture& m, const double* x0, const double* x1, Eigen::Index n_points,
               double* point_ll, Moments2d* moments, Simd simd = Simd::kAuto, int threads = 1,
               bool cull = true);

// exp(x) for 4 doubles at a time, as the kernel computes it (relative error < 1e-15 against
// std::exp for x in [-700, 0]; x below -700 gives 0): exposed for the unit test.
void VectorExp4(const double* x, double* out, Simd simd = Simd::kAuto);

// log(x) for 4 positive normal doubles at a time, as the kernel computes it (relative error
// < 4e-16 against std::log away from x = 1, absolute < 1e-16 near it): exposed for the unit test.
void VectorLog4(const double* x, double* out, Simd simd = Simd::kAuto);

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_ESTEP_2D_HPP
