// estep_2d.cpp - the fused E-step for D = 2 (paper eq. 1), with or without a wrapped angle on
// dimension 1 (the planner's (d, theta) features): the hot loop of EM on the benchmark data and
// on demonstrations. The kernel (estep_2d_kernel.inc) takes 2 points at a time in vector
// registers on the baseline target (SSE2 on x86-64, NEON on ARM) and, compiled once more for
// AVX2 on x86-64, 4 at a time when the CPU has AVX2 (checked once at run time, so binaries still
// run on any x86-64). The AVX2 kernel also fuses multiply-adds (FMA, which every AVX2 CPU has;
// this file is compiled with -ffp-contract=fast): about 6 % of the benchmark fit's CPU time.
// The two agree up to the order of the sums and that rounding (see the .inc). exp() is our own vectorised one: the library exp is a scalar call per
// value, and Eigen's packet exp is slow on the baseline target; log() likewise (one per point). Contract in estep_2d.hpp.
#include "estep_2d.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "parallel.hpp"

#include "gmmrrt/limits.h"

namespace gmmrrt {
namespace learn {
namespace detail {

namespace {

// Points per accumulation block: partial sums of a block are added to the totals, which keeps
// the rounding of sums over N = 1e5..1e6 points small (each lane adds at most 256 values).
constexpr long kBlock = 512;

// Points per task of the threaded E-step (a multiple of kBlock): large enough that a task's
// K x 6 partial sums are negligible next to its work, small enough that 20 000 screening
// points still make tasks for two threads.
constexpr long kChunkPoints = 8192;

// A term below exp(-37) = 8.5e-17 times the largest one is taken as 0: the sum it joins is >= 1
// (the largest term is exp(0)), and it is below half an ulp of 1 (2^-53 = 1.1e-16), so adding
// it alone would not change that sum; its responsibility would add at most N * 8.5e-17
// (1.7e-11 for N = 200 000) to a component's effective count, which is >= D + 1 or re-seeded.
// Skipping such terms (the exp and the six moment updates) is most of the saving when K is
// large: on the benchmark fit a cut at -37 makes 18 % fewer exp calls than one at -50, with the
// same log-likelihood after 16 iterations to 16 digits.
constexpr double kNegligible = -37.0;

// Points per group whose terms are culled together (ActiveTerms in the kernel): the
// points are in spatial order (FitMixture), so a group's bounding box is small, and on the
// benchmark data (K = 19) about a fifth of the terms survive it; the bounds cost about 1 200
// instructions per group with K = 19 (4 components per vector), 19 per point. Groups of 128
// would now cost a little less on the benchmark fit (docs/learner.md), but the culling tests'
// clumps of points are placed for groups of 64. A multiple of both lane counts.
constexpr long kCullPoints = 64;
static_assert(kCullPoints % 4 == 0 && kBlock % kCullPoints == 0, "groups must hold whole vectors and blocks");

// Component slots: GMMRRT_MAX_K rounded up to whole vectors of the widest kernel (4 lanes), so the
// culling bounds (ActiveTerms) load the parameters of 4 components at a time.
constexpr int kParamSlots = (GMMRRT_MAX_K + 3) / 4 * 4;

// Per component: mean, the rows of L^-1 scaled by sqrt(1/2) (which folds the 1/2 of the
// exponent), the log coefficient, a lower bound of the smallest eigenvalue of the quadratic form
// (for culling); and the image offsets on dimension 1. Slots k..kParamSlots-1 hold a harmless
// finite component (unit scale at 0), which the kernel masks out.
struct Params2d {
  int k = 0;
  int images = 1;
  bool cull = true;
  double mu0[kParamSlots], mu1[kParamSlots], a[kParamSlots], b[kParamSlots], c[kParamSlots],
      coef[kParamSlots], lam[kParamSlots];
  double offset1[3] = {0.0, 2.0 * M_PI, -2.0 * M_PI};  // ImageOffsets' order: n = 0, +1, -1
};

struct MomentPtrs {
  double *n, *m0, *m1, *s00, *s01, *s11;
};

// The kernel's scratch for one group of points: each term's values, and with the angle each
// component's wrapped differences (kCullPoints doubles each).
long KernelScratchDoubles(const Params2d& p) {
  return static_cast<long>(p.k * p.images + (p.images == 3 ? p.k : 0)) * kCullPoints;
}

}  // namespace

// The 256-bit vectors of the kernel are passed between its inlined static helpers only; on the
// baseline target GCC notes that such a signature would differ under AVX (no ABI is crossed).
// GCC reports it at the end of the file, so the note is off for all of this file.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace kernel_baseline {
using Moments2d = MomentPtrs;
constexpr int kW = 2;
#define GMMRRT_KERNEL_LANES 2
#define GMMRRT_KERNEL_ATTR
#include "estep_2d_kernel.inc"
#undef GMMRRT_KERNEL_ATTR
#undef GMMRRT_KERNEL_LANES
}  // namespace kernel_baseline

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define GMMRRT_ESTEP_HAVE_AVX2 1
namespace kernel_avx2 {
using Moments2d = MomentPtrs;
constexpr int kW = 4;
#define GMMRRT_KERNEL_LANES 4
#define GMMRRT_KERNEL_ATTR __attribute__((target("avx2,fma")))
#include "estep_2d_kernel.inc"
#undef GMMRRT_KERNEL_ATTR
#undef GMMRRT_KERNEL_LANES
}  // namespace kernel_avx2
#endif

bool EStep2dAvx2Available() {
#ifdef GMMRRT_ESTEP_HAVE_AVX2
  static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return has;
#else
  return false;
#endif
}

void VectorExp4(const double* x, double* out, Simd simd) {
#ifdef GMMRRT_ESTEP_HAVE_AVX2
  if (simd != Simd::kBaseline && EStep2dAvx2Available()) {
    kernel_avx2::ExpOf4(x, out);
    return;
  }
#endif
  (void)simd;
  kernel_baseline::ExpOf4(x, out);
}

void VectorLog4(const double* x, double* out, Simd simd) {
#ifdef GMMRRT_ESTEP_HAVE_AVX2
  if (simd != Simd::kBaseline && EStep2dAvx2Available()) {
    kernel_avx2::LogOf4(x, out);
    return;
  }
#endif
  (void)simd;
  kernel_baseline::LogOf4(x, out);
}

double EStep2d(const Mixture& m, const double* x0, const double* x1, Eigen::Index n_points,
               double* point_ll, Moments2d* moments, Simd simd, int threads, bool cull) {
  Params2d p;
  p.k = m.k();
  p.images = m.angle_mask == 0u ? 1 : 3;
  p.cull = cull;
  const double h = std::sqrt(0.5), log_2pi = std::log(2.0 * M_PI);
  for (int i = 0; i < p.k; ++i) {
    const Eigen::MatrixXd& l = m.chol[i];
    p.mu0[i] = m.means(0, i);
    p.mu1[i] = m.means(1, i);
    p.a[i] = h / l(0, 0);
    p.b[i] = -h * l(1, 0) / (l(0, 0) * l(1, 1));
    p.c[i] = h / l(1, 1);
    p.coef[i] = std::log(m.weights[i]) - log_2pi - std::log(l(0, 0)) - std::log(l(1, 1));
    // |z|^2 = y^T A y with A = M^T M, M = [[a, 0], [b, c]]: the smaller eigenvalue of A is
    // det / (larger one) = 2 a^2 c^2 / (tr + sqrt((a^2 + b^2 - c^2)^2 + 4 b^2 c^2)) (no
    // cancellation), taken 1e-9 smaller for its rounding.
    const double a2 = p.a[i] * p.a[i], b2 = p.b[i] * p.b[i], c2 = p.c[i] * p.c[i];
    const double disc = std::sqrt((a2 + b2 - c2) * (a2 + b2 - c2) + 4.0 * b2 * c2);
    p.lam[i] = (1.0 - 1e-9) * 2.0 * a2 * c2 / (a2 + b2 + c2 + disc);
  }
  for (int i = p.k; i < kParamSlots; ++i) {
    p.mu0[i] = p.mu1[i] = p.b[i] = p.coef[i] = 0.0;
    p.a[i] = p.c[i] = p.lam[i] = 1.0;
  }
  // The points are cut into chunks of a fixed size (independent of the thread count); each
  // chunk sums into its own slot and the slots are added in chunk order: the same bits for
  // any number of threads.
  const long n = static_cast<long>(n_points);
  const long chunks = (n + kChunkPoints - 1) / kChunkPoints;
  std::vector<double> slots(static_cast<size_t>(chunks) * (6 * p.k + 1), 0.0);
  const bool avx2 = simd == Simd::kAvx2 || (simd == Simd::kAuto && EStep2dAvx2Available());
  ParallelFor(threads, chunks, [&](long c) {
    double* slot = slots.data() + static_cast<size_t>(c) * (6 * p.k + 1);
    MomentPtrs out{slot, slot + p.k, slot + 2 * p.k, slot + 3 * p.k, slot + 4 * p.k, slot + 5 * p.k};
    const long first = c * kChunkPoints, count = std::min(kChunkPoints, n - first);
    // One block per task (38 KB for K = 19 with the angle, 9.5 KB without), not per point.
    const std::unique_ptr<double[]> scratch(new double[static_cast<size_t>(KernelScratchDoubles(p))]);
#ifdef GMMRRT_ESTEP_HAVE_AVX2
    if (avx2 && EStep2dAvx2Available()) {
      slot[6 * p.k] = kernel_avx2::Kernel(p, x0 + first, x1 + first, count, point_ll + first, &out, scratch.get());
      return;
    }
#endif
    slot[6 * p.k] = kernel_baseline::Kernel(p, x0 + first, x1 + first, count, point_ll + first, &out, scratch.get());
  });
  (void)avx2;
  std::vector<double>* dst[6] = {&moments->n, &moments->m0, &moments->m1, &moments->s00, &moments->s01, &moments->s11};
  for (std::vector<double>* v : dst) v->assign(p.k, 0.0);
  double total = 0.0;
  for (long c = 0; c < chunks; ++c) {
    const double* slot = slots.data() + static_cast<size_t>(c) * (6 * p.k + 1);
    for (int q = 0; q < 6; ++q)
      for (int i = 0; i < p.k; ++i) (*dst[q])[i] += slot[q * p.k + i];
    total += slot[6 * p.k];
  }
  return total / static_cast<double>(n_points);
}

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt
