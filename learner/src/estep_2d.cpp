// estep_2d.cpp - the fused E-step for D = 2 without angle dimensions (paper eq. 1), the hot loop
// of EM on the benchmark data. Two points at a time in GCC/Clang vector registers (SSE2 on the baseline
// x86-64 build, NEON on ARM), structure of arrays:
//   t_i = log w_i - log 2 pi - log L_i00 - log L_i11 - |L_i^-1 (x - mu_i)|^2 / 2   (closed form),
//   lse = max_i t_i + log sum_i exp(t_i - max), r_i = exp(t_i - max) / sum,
// then the moments of r_i around mu_i are accumulated in the same pass. exp() is our own
// vectorised one (Cody-Waite reduction, degree-12 Taylor polynomial, exponent by bit
// arithmetic): the library exp is a scalar call per value, and Eigen's packet exp is slow on the
// baseline SSE2 target. Contract in estep_2d.hpp.
#include "estep_2d.hpp"

#include <cmath>
#include <cstring>

#include "gmmrrt/limits.h"

namespace gmmrrt {
namespace learn {
namespace detail {

namespace {

// Two doubles per vector: the width of SSE2 (baseline x86-64) and of NEON, so that every
// operation maps to one instruction. (With 4-double vectors on SSE2, GCC lowered the selects to
// scalar code: 86 instructions per term.)
constexpr int kLanes = 2;
typedef double V4 __attribute__((vector_size(8 * kLanes)));
typedef long long V4i __attribute__((vector_size(8 * kLanes)));

// Points per accumulation block: partial sums of a block are added to the totals, which keeps
// the rounding of sums over N = 1e5..1e6 points small (each lane adds at most 256 values).
constexpr Eigen::Index kBlock = 512;

// A term below exp(-50) = 2e-22 times the largest one is taken as 0: the sum it joins is >= 1,
// so it is below a double's resolution there, and its responsibility would add at most
// N * 2e-22 (4e-17 for N = 200 000) to a component's effective count. Skipping such pairs (the
// exp and the six moment updates) is most of the saving when K is large.
constexpr double kNegligible = -50.0;

inline V4 Splat(double v) { return V4{} + v; }

inline V4 Load(const double* p) {
  V4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline void Store(double* p, V4 v) { std::memcpy(p, &v, sizeof v); }

inline V4 Max(V4 a, V4 b) { return a > b ? a : b; }

// Below exp(-700) (1e-304) the result is 0 exactly: such a term is far below a double's
// resolution next to the largest term (which is 1 after subtracting the maximum), and products
// of tiny responsibilities would otherwise be subnormal numbers, which cost x86 cores about a
// hundred cycles per operation (measured: the E-step ran 5x slower with them).
inline V4 Exp(V4 x) {
  const V4 lo = Splat(-700.0);
  const auto underflow = x < lo;
  x = underflow ? lo : x;
  const V4 magic = Splat(6755399441055744.0);  // 1.5 * 2^52: adding it rounds to an integer
  const V4 t = x * Splat(1.4426950408889634) + magic;
  const V4 k = t - magic;  // round(x / ln 2), |k| <= 1022
  const V4 r = (x - k * Splat(6.93147180369123816490e-01)) - k * Splat(1.90821492927058770002e-10);
  V4 p = Splat(1.0 / 479001600.0);  // 1/12!
  p = p * r + Splat(1.0 / 39916800.0);
  p = p * r + Splat(1.0 / 3628800.0);
  p = p * r + Splat(1.0 / 362880.0);
  p = p * r + Splat(1.0 / 40320.0);
  p = p * r + Splat(1.0 / 5040.0);
  p = p * r + Splat(1.0 / 720.0);
  p = p * r + Splat(1.0 / 120.0);
  p = p * r + Splat(1.0 / 24.0);
  p = p * r + Splat(1.0 / 6.0);
  p = p * r + Splat(0.5);
  p = p * r + Splat(1.0);
  p = p * r + Splat(1.0);
  // 2^k: the low mantissa bits of t hold k (two's complement around magic's bit pattern).
  const V4i bits = (((V4i)t - (V4i)magic) + 1023) << 52;  // vector casts reinterpret the bits
  const V4 e = p * (V4)bits;
  return underflow ? Splat(0.0) : e;
}

inline double Sum(V4 v) { return v[0] + v[1]; }

}  // namespace

void VectorExp4(const double* x, double* out) {
  for (int q = 0; q < 4; q += kLanes) Store(out + q, Exp(Load(x + q)));
}

double EStep2d(const Mixture& m, const double* x0, const double* x1, Eigen::Index n_points,
               double* point_ll, Moments2d* moments) {
  const int k = m.k();
  // Per component: mean, scaled rows of L^-1 (factor sqrt(1/2) folds the 1/2 of the exponent)
  // and the log coefficient.
  double mu0[GMMRRT_MAX_K], mu1[GMMRRT_MAX_K], a[GMMRRT_MAX_K], b[GMMRRT_MAX_K], c[GMMRRT_MAX_K],
      coef[GMMRRT_MAX_K];
  const double h = std::sqrt(0.5), log_2pi = std::log(2.0 * M_PI);
  for (int i = 0; i < k; ++i) {
    const Eigen::MatrixXd& l = m.chol[i];
    mu0[i] = m.means(0, i);
    mu1[i] = m.means(1, i);
    a[i] = h / l(0, 0);
    b[i] = -h * l(1, 0) / (l(0, 0) * l(1, 1));
    c[i] = h / l(1, 1);
    coef[i] = std::log(m.weights[i]) - log_2pi - std::log(l(0, 0)) - std::log(l(1, 1));
  }
  moments->n.assign(k, 0.0);
  moments->m0.assign(k, 0.0);
  moments->m1.assign(k, 0.0);
  moments->s00.assign(k, 0.0);
  moments->s01.assign(k, 0.0);
  moments->s11.assign(k, 0.0);
  V4 t[GMMRRT_MAX_K];
  V4 acc_n[GMMRRT_MAX_K], acc_m0[GMMRRT_MAX_K], acc_m1[GMMRRT_MAX_K], acc_s00[GMMRRT_MAX_K],
      acc_s01[GMMRRT_MAX_K], acc_s11[GMMRRT_MAX_K];
  double ll_total = 0.0;
  for (Eigen::Index start = 0; start < n_points; start += kBlock) {
    const Eigen::Index end = std::min(n_points, start + kBlock);
    for (int i = 0; i < k; ++i) acc_n[i] = acc_m0[i] = acc_m1[i] = acc_s00[i] = acc_s01[i] = acc_s11[i] = Splat(0.0);
    V4 acc_ll = Splat(0.0);
    for (Eigen::Index p = start; p < end; p += kLanes) {
      const int lanes = static_cast<int>(std::min<Eigen::Index>(kLanes, end - p));
      V4 px0, px1, valid = Splat(1.0);
      if (lanes == kLanes) {
        px0 = Load(x0 + p);
        px1 = Load(x1 + p);
      } else {  // the last points: pad with the last one, weight 0
        double b0[kLanes], b1[kLanes];
        for (int q = 0; q < kLanes; ++q) {
          const Eigen::Index src = p + std::min(q, lanes - 1);
          b0[q] = x0[src];
          b1[q] = x1[src];
          valid[q] = q < lanes ? 1.0 : 0.0;
        }
        px0 = Load(b0);
        px1 = Load(b1);
      }
      V4 mx = Splat(-HUGE_VAL);
      for (int i = 0; i < k; ++i) {
        const V4 y0 = px0 - mu0[i], y1 = px1 - mu1[i];
        const V4 z0 = a[i] * y0, z1 = b[i] * y0 + c[i] * y1;
        t[i] = coef[i] - (z0 * z0 + z1 * z1);
        mx = Max(mx, t[i]);
      }
      V4 sum = Splat(0.0);
      for (int i = 0; i < k; ++i) {
        const V4 e = t[i] - mx;
        const auto negligible = e < Splat(kNegligible);
        if (negligible[0] && negligible[1]) {  // far from both points: most pairs when K is large
          t[i] = Splat(0.0);
          continue;
        }
        t[i] = negligible ? Splat(0.0) : Exp(e);
        sum += t[i];
      }
      V4 lse;
      for (int q = 0; q < kLanes; ++q) lse[q] = mx[q] + std::log(sum[q]);
      for (int q = 0; q < lanes; ++q) point_ll[p + q] = lse[q];
      acc_ll += lse * valid;
      const V4 inv = valid / sum;
      for (int i = 0; i < k; ++i) {
        if (t[i][0] == 0.0 && t[i][1] == 0.0) continue;  // nothing to accumulate
        const V4 r = t[i] * inv;
        const V4 y0 = px0 - mu0[i], y1 = px1 - mu1[i];
        const V4 ry0 = r * y0, ry1 = r * y1;
        acc_n[i] += r;
        acc_m0[i] += ry0;
        acc_m1[i] += ry1;
        acc_s00[i] += ry0 * y0;
        acc_s01[i] += ry0 * y1;
        acc_s11[i] += ry1 * y1;
      }
    }
    for (int i = 0; i < k; ++i) {
      moments->n[i] += Sum(acc_n[i]);
      moments->m0[i] += Sum(acc_m0[i]);
      moments->m1[i] += Sum(acc_m1[i]);
      moments->s00[i] += Sum(acc_s00[i]);
      moments->s01[i] += Sum(acc_s01[i]);
      moments->s11[i] += Sum(acc_s11[i]);
    }
    ll_total += Sum(acc_ll);
  }
  return ll_total / static_cast<double>(n_points);
}

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt
