// test_estep_2d.cpp - learner.estep_2d: the fused D = 2 E-step of learner/src/estep_2d.cpp (paper
// eq. 1) against oracles: its vector exp against std::exp, its per-point log-likelihood against
// LogDensity (the density that matches the C gmm.h), its moments against a direct computation of
// the responsibilities from single-component densities, on an odd point count (tail lanes) and
// with points far from every component (the negligible-term cut); the same with theta wrapped
// (the planner's (d, theta) features) against the general E-step's building blocks; the
// baseline and AVX2 kernels against each other; k-means' inline angle wrap against
// gmmrrt_wrap_angle; and FitMixture's screening
// subsample: deterministic, and the fit on all points still recovers the generating mixture.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <vector>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>

#include "component_terms.hpp"
#include "estep_2d.hpp"
#include "gmmrrt/features.h"
#include "gmmrrt_learner/em.hpp"
#include "gmmrrt_learner/mixture.hpp"
#include "parallel.hpp"
#include "spatial_order.hpp"
#include "test_support.hpp"

// cmocka last: its fail() macro would clash with the standard library.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
extern "C" {
#include <cmocka.h>
}

using namespace gmmrrt::learn;

namespace {

bool Close(double got, double want, double rel, double abs_floor) {
  return std::fabs(got - want) <= rel * std::fabs(want) + abs_floor;
}

// Component i of a 2-D mixture without an angle, alone with weight 1: its own density.
Mixture ComponentAlone(const Mixture& m, int i) {
  Mixture one;
  one.dim = 2;
  one.angle_mask = 0;
  one.weights = Eigen::VectorXd::Ones(1);
  one.means = m.means.col(i);
  one.chol = {m.chol[i]};
  return one;
}

void test_vector_exp_matches_std_exp(void** state) {
  (void)state;
  double worst = 0.0;
  for (int i = 0; i <= 200000; ++i) {
    double x[4], e[4];
    for (int q = 0; q < 4; ++q) x[q] = -700.0 * (i * 4 + q) / 800003.0;
    detail::VectorExp4(x, e);
    for (int q = 0; q < 4; ++q) worst = std::max(worst, std::fabs(e[q] - std::exp(x[q])) / std::exp(x[q]));
  }
  assert_true(worst < 1e-15);
  const double big[4] = {-701.0, -800.0, -1e300, -HUGE_VAL};
  double e[4];
  detail::VectorExp4(big, e);
  for (int q = 0; q < 4; ++q) assert_true(e[q] == 0.0);
}

void test_vector_log_matches_std_log(void** state) {
  (void)state;
  // The kernel's sums lie in [1, 3 K]; the function is checked on [1e-300, 1e300] too.
  for (detail::Simd simd : {detail::Simd::kBaseline, detail::Simd::kAuto}) {
    double worst = 0.0;
    for (int i = 0; i < 200000; ++i) {
      double x[4], l[4];
      for (int q = 0; q < 4; ++q) x[q] = 1.0 + 3071.0 * (i * 4 + q) / 800000.0;
      detail::VectorLog4(x, l, simd);
      for (int q = 0; q < 4; ++q) worst = std::max(worst, std::fabs(l[q] - std::log(x[q])) / std::max(std::log(x[q]), 1.0));
    }
    assert_true(worst < 4e-16);  // 2 units in the last place (1 measured)
    const double wide[4] = {1e-300, 0.7071067811865476, 1.4142135623730951, 1e300};
    double l[4];
    detail::VectorLog4(wide, l, simd);
    for (int q = 0; q < 4; ++q) assert_true(Close(l[q], std::log(wide[q]), 4e-16, 1e-16));
    const double one[4] = {1.0, 2.0, 0.5, 1.0 + 1e-15};
    detail::VectorLog4(one, l, simd);
    assert_true(l[0] == 0.0);
    for (int q = 1; q < 4; ++q) assert_true(Close(l[q], std::log(one[q]), 4e-16, 1e-30));
  }
}

Mixture RandomMixture(int k, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Mixture m;
  m.dim = 2;
  m.angle_mask = 0;
  m.weights.resize(k);
  m.means.resize(2, k);
  m.chol.assign(k, Eigen::MatrixXd::Zero(2, 2));
  for (int i = 0; i < k; ++i) {
    m.weights[i] = 0.2 + std::fabs(normal(rng));
    m.means(0, i) = 100.0 + 4.0 * normal(rng);  // away from the origin, as real positions are
    m.means(1, i) = -50.0 + 4.0 * normal(rng);
    m.chol[i](0, 0) = 0.3 + std::fabs(normal(rng));
    m.chol[i](1, 1) = 0.3 + std::fabs(normal(rng));
    m.chol[i](1, 0) = 0.5 * normal(rng);
  }
  m.weights /= m.weights.sum();
  return m;
}

void test_fused_estep_matches_the_density_and_direct_moments(void** state) {
  (void)state;
  const int k = 7;
  const Mixture m = RandomMixture(k, 5);
  std::mt19937_64 rng(9);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::Index n = 2001;  // odd: the last vector holds one point
  Eigen::MatrixXd pts(2, n);
  for (Eigen::Index c = 0; c < n; ++c) {
    pts(0, c) = 100.0 + 6.0 * normal(rng);
    pts(1, c) = -50.0 + 6.0 * normal(rng);
  }
  pts(0, 0) = 1e4;  // far from every component: only its nearest term is not negligible
  const Eigen::VectorXd x0 = pts.row(0).transpose(), x1 = pts.row(1).transpose();
  Eigen::VectorXd ll(n);
  detail::Moments2d mo;
  const double mean_ll = detail::EStep2d(m, x0.data(), x1.data(), n, ll.data(), &mo);

  Eigen::VectorXd want_ll;
  LogDensity(m, pts, &want_ll);
  for (Eigen::Index c = 0; c < n; ++c) assert_true(Close(ll[c], want_ll[c], 1e-12, 1e-12));
  assert_true(Close(mean_ll, want_ll.mean(), 1e-12, 1e-12));

  // Responsibilities from one-component densities: r_i = w_i N_i / p.
  for (int i = 0; i < k; ++i) {
    Eigen::VectorXd li;
    LogDensity(ComponentAlone(m, i), pts, &li);
    double nk = 0, m0 = 0, m1 = 0, s00 = 0, s01 = 0, s11 = 0;
    for (Eigen::Index c = 0; c < n; ++c) {
      const double r = std::exp(std::log(m.weights[i]) + li[c] - want_ll[c]);
      const double y0 = pts(0, c) - m.means(0, i), y1 = pts(1, c) - m.means(1, i);
      nk += r;
      m0 += r * y0;
      m1 += r * y1;
      s00 += r * y0 * y0;
      s01 += r * y0 * y1;
      s11 += r * y1 * y1;
    }
    assert_true(Close(mo.n[i], nk, 1e-11, 1e-12));
    assert_true(Close(mo.m0[i], m0, 1e-11, 1e-10));
    assert_true(Close(mo.m1[i], m1, 1e-11, 1e-10));
    assert_true(Close(mo.s00[i], s00, 1e-11, 1e-10));
    assert_true(Close(mo.s01[i], s01, 1e-11, 1e-10));
    assert_true(Close(mo.s11[i], s11, 1e-11, 1e-10));
  }
  double total = 0.0;
  for (int i = 0; i < k; ++i) total += mo.n[i];
  assert_true(Close(total, static_cast<double>(n), 1e-12, 0.0));
}

// The planner's (d, theta) features: theta wrapped (angle_mask 2), means and points spread over
// the seam at +-pi. The fused kernel (both compiled variants) against the general E-step's own
// building blocks (component_terms.hpp: log terms over the 3 images, log-sum-exp, then the
// moments of delta + offset as em.cpp's EStep sums them).
void test_fused_estep_with_angle_matches_the_general_path(void** state) {
  (void)state;
  const int k = 6;
  std::mt19937_64 rng(17);
  std::normal_distribution<double> normal(0.0, 1.0);
  Mixture m;
  m.dim = 2;
  m.angle_mask = 2u;
  m.weights.resize(k);
  m.means.resize(2, k);
  m.chol.assign(k, Eigen::MatrixXd::Zero(2, 2));
  for (int i = 0; i < k; ++i) {
    m.weights[i] = 0.2 + std::fabs(normal(rng));
    m.means(0, i) = 1.0 + 0.5 * i;                                      // d [m]
    m.means(1, i) = i < 3 ? M_PI - 0.1 * i : -M_PI + 0.3 + 0.2 * i;     // theta near the seam
    m.chol[i](0, 0) = 0.2 + 0.3 * std::fabs(normal(rng));
    m.chol[i](1, 1) = 0.3 + (i == 5 ? 1.5 : 0.4 * std::fabs(normal(rng)));  // one wide in theta
    m.chol[i](1, 0) = 0.1 * normal(rng);
  }
  m.weights /= m.weights.sum();
  assert_true(ValidateMixture(m).ok());
  const Eigen::Index n = 1003;  // not a multiple of 2 or 4: tail lanes
  Eigen::MatrixXd pts(2, n);
  for (Eigen::Index c = 0; c < n; ++c) {
    pts(0, c) = 2.0 + 1.2 * normal(rng);
    pts(1, c) = gmmrrt_wrap_angle(M_PI + 0.8 * normal(rng));
  }
  pts(1, 0) = M_PI;  // on the seam itself
  pts(0, 1) = 1e3;   // far from every component
  const Eigen::VectorXd x0 = pts.row(0).transpose(), x1 = pts.row(1).transpose();

  // The general path's quantities.
  detail::PreparedMixture prep;
  detail::Prepare(m, &prep);
  assert_int_equal(prep.images, 3);
  Eigen::MatrixXd block = pts.transpose(), terms;
  std::vector<Eigen::MatrixXd> deltas;
  Eigen::VectorXd want_ll;
  detail::LogTerms(m, prep, block, &terms, &deltas);
  detail::LogSumExpToResponsibilities(&terms, &want_ll);  // terms: responsibilities now
  std::vector<double> wn(k, 0.0), w0(k, 0.0), w1(k, 0.0), w00(k, 0.0), w01(k, 0.0), w11(k, 0.0);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < prep.images; ++j)
      for (Eigen::Index c = 0; c < n; ++c) {
        const double r = terms(c, i * prep.images + j);
        const double y0 = deltas[i](c, 0) + prep.offsets(0, j), y1 = deltas[i](c, 1) + prep.offsets(1, j);
        wn[i] += r;
        w0[i] += r * y0;
        w1[i] += r * y1;
        w00[i] += r * y0 * y0;
        w01[i] += r * y0 * y1;
        w11[i] += r * y1 * y1;
      }
  Eigen::VectorXd density;
  LogDensity(m, pts, &density);  // the model's density (gmm.h's wrapped normal)
  for (Eigen::Index c = 0; c < n; ++c) assert_true(Close(density[c], want_ll[c], 1e-12, 1e-12));

  for (detail::Simd simd : {detail::Simd::kBaseline, detail::Simd::kAvx2}) {
    Eigen::VectorXd ll(n);
    detail::Moments2d mo;
    const double mean_ll = detail::EStep2d(m, x0.data(), x1.data(), n, ll.data(), &mo, simd);
    for (Eigen::Index c = 0; c < n; ++c) assert_true(Close(ll[c], want_ll[c], 1e-12, 1e-12));
    assert_true(Close(mean_ll, want_ll.mean(), 1e-12, 1e-12));
    for (int i = 0; i < k; ++i) {
      assert_true(Close(mo.n[i], wn[i], 1e-11, 1e-12));
      assert_true(Close(mo.m0[i], w0[i], 1e-11, 1e-10));
      assert_true(Close(mo.m1[i], w1[i], 1e-11, 1e-10));
      assert_true(Close(mo.s00[i], w00[i], 1e-11, 1e-10));
      assert_true(Close(mo.s01[i], w01[i], 1e-11, 1e-10));
      assert_true(Close(mo.s11[i], w11[i], 1e-11, 1e-10));
    }
  }
}

// The baseline (2 lanes) and AVX2 (4 lanes) kernels: the same values up to the order of sums.
void test_baseline_and_avx2_kernels_agree(void** state) {
  (void)state;
  if (!detail::EStep2dAvx2Available())
    print_message("no AVX2 on this CPU: the kAvx2 request runs the baseline kernel (compared with itself)\n");
  const Mixture m = RandomMixture(19, 8);
  std::mt19937_64 rng(4);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::Index n = 5001;
  Eigen::VectorXd x0(n), x1(n), la(n), lb(n);
  for (Eigen::Index c = 0; c < n; ++c) {
    x0[c] = 100.0 + 5.0 * normal(rng);
    x1[c] = -50.0 + 5.0 * normal(rng);
  }
  detail::Moments2d a, b;
  const double ma = detail::EStep2d(m, x0.data(), x1.data(), n, la.data(), &a, detail::Simd::kBaseline);
  const double mb = detail::EStep2d(m, x0.data(), x1.data(), n, lb.data(), &b, detail::Simd::kAvx2);
  assert_true(Close(ma, mb, 1e-14, 0.0));
  for (Eigen::Index c = 0; c < n; ++c) assert_true(Close(la[c], lb[c], 1e-14, 1e-14));
  for (int i = 0; i < 19; ++i) {
    assert_true(Close(a.n[i], b.n[i], 1e-12, 1e-13));
    assert_true(Close(a.s01[i], b.s01[i], 1e-12, 1e-12));
  }
  double e[4], f[4];
  const double x[4] = {-1e-3, -3.7, -45.0, -699.0};
  detail::VectorExp4(x, e, detail::Simd::kBaseline);
  detail::VectorExp4(x, f, detail::Simd::kAvx2);
  // Lane-wise the same operations, but the AVX2 copy may fuse a multiply and an add (FMA) where
  // the compiler contracts them: within 2 ulps, not necessarily the same bits.
  for (int q = 0; q < 4; ++q) assert_true(Close(f[q], e[q], 4.5e-16, 0.0));
}

// The E-step with and without culling components per group of points gives the same bits
// (log-likelihoods, per-point values and moments), on the points in spatial order and as given,
// with the baseline and the vector kernels.
static void AssertCullingKeepsTheBits(const Mixture& m, const Eigen::MatrixXd& xt) {
  const Eigen::Index n = xt.rows();
  const detail::PointOrder order = detail::SpatialOrder2d(xt.transpose(), 0u);
  Eigen::MatrixXd sorted(n, 2);
  for (Eigen::Index c = 0; c < n; ++c) sorted.row(c) = xt.row(order[c]);
  const Eigen::MatrixXd* const both[2] = {&sorted, &xt};
  for (const Eigen::MatrixXd* pts : both) {
    const Eigen::VectorXd x0 = pts->col(0), x1 = pts->col(1);
    for (detail::Simd simd : {detail::Simd::kBaseline, detail::Simd::kAuto}) {
      Eigen::VectorXd la(n), lb(n);
      detail::Moments2d a, b;
      const double ma = detail::EStep2d(m, x0.data(), x1.data(), n, la.data(), &a, simd, 1, true);
      const double mb = detail::EStep2d(m, x0.data(), x1.data(), n, lb.data(), &b, simd, 1, false);
      assert_true(ma == mb);
      assert_true(la == lb);
      assert_true(a.n == b.n && a.m0 == b.m0 && a.m1 == b.m1);
      assert_true(a.s00 == b.s00 && a.s01 == b.s01 && a.s11 == b.s11);
    }
  }
}

// Culling components per group of points (bounds over the group's bounding box) skips only
// terms the per-point code sets to 0, so it gives the same bits as no culling: checked on 19
// components, some thin and tilted (condition number up to ~1e4, where the eigenvalue bound is
// loosest), with points in spatial order (as FitMixture hands them over: most groups cull), in
// random order (wide boxes: few cull), far away (1e4: one term survives) and in tight clumps
// (tight bounds: the boundary of the cut), on both compiled kernels and on an odd count. (With
// the cut moved by 1 nat in the culling's favour, this test fails.)
void test_culling_components_gives_the_same_bits(void** state) {
  (void)state;
  Mixture m = RandomMixture(19, 12);
  std::mt19937_64 rng(13);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int i = 0; i < 19; ++i)  // spread out: a group's box is near a few of them only
    m.means.col(i) << 100.0 + 12.0 * normal(rng), -50.0 + 12.0 * normal(rng);
  for (int i = 0; i < 19; i += 3) {  // thin, tilted components
    m.chol[i](0, 0) = 2.0;
    m.chol[i](1, 0) = 1.5;
    m.chol[i](1, 1) = 0.02;
  }
  const Eigen::Index n = 6001;  // odd: the last vector is partly padding
  Eigen::MatrixXd xt(n, 2);
  for (Eigen::Index c = 0; c < n; ++c) {
    const int i = static_cast<int>(rng() % 19);
    const Eigen::Vector2d z(normal(rng), normal(rng));
    xt.row(c) = (m.means.col(i) + 3.0 * m.chol[i] * z).transpose();
  }
  for (Eigen::Index c = 0; c < 40; ++c) xt.row(c) << 1e4 + c, -1e4;
  // Clumps of 128 points within ~1e-3 at random places: tiny boxes, where the bounds are tight,
  // so terms just above and just below the cut meet the margin.
  for (Eigen::Index c = 40; c + 128 <= 5040; c += 128) {  // 5040..5807: the clumps below
    const double u0 = 100.0 + 15.0 * normal(rng), u1 = -50.0 + 15.0 * normal(rng);
    for (Eigen::Index q = c; q < c + 128; ++q) xt.row(q) << u0 + 1e-3 * normal(rng), u1 + 1e-3 * normal(rng);
  }
  // Clumps where one component's term is 36.5 nats below the point's largest: 0.5 nat inside
  // the cut, the band a culling error of a nat would wrongly skip. Found on a ray from mu_j
  // (component j's term relative to the largest falls from about 0 to far below).
  auto gap_at = [&m](int j, const Eigen::Vector2d& x) {  // term j - largest term + 36.5
    Eigen::VectorXd one(1);
    double top = -HUGE_VAL, mine = 0.0;
    for (int i = 0; i < 19; ++i) {
      LogDensity(ComponentAlone(m, i), x, &one);
      const double term = std::log(m.weights[i]) + one[0];
      top = std::max(top, term);
      if (i == j) mine = term;
    }
    return mine - top + 36.5;
  };
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector2d dir(std::cos(j + 0.5), std::sin(j + 0.5));
    double lo = 0.0, hi = 1.0;
    assert_true(gap_at(j, m.means.col(j)) > 0.0);
    while (gap_at(j, m.means.col(j) + hi * dir) > 0.0) hi *= 2.0;
    for (int it = 0; it < 60; ++it) {  // bisection to the crossing
      const double mid = 0.5 * (lo + hi);
      (gap_at(j, m.means.col(j) + mid * dir) > 0.0 ? lo : hi) = mid;
    }
    const Eigen::Vector2d x = m.means.col(j) + lo * dir;
    assert_true(std::fabs(gap_at(j, x)) < 1e-6);
    for (Eigen::Index q = 5040 + 128 * j; q < 5040 + 128 * (j + 1); ++q)
      xt.row(q) << x[0] + 1e-6 * normal(rng), x[1] + 1e-6 * normal(rng);
  }
  AssertCullingKeepsTheBits(m, xt);
}

// The same with theta wrapped (angle_mask 2: 3 images per component): narrow and wide
// components spread over (-pi, pi], points in spatial order and not, clumps at the seam
// (+-pi: a group's box straddles the wrap for some components) and elsewhere.
void test_culling_terms_with_the_angle_gives_the_same_bits(void** state) {
  (void)state;
  std::mt19937_64 rng(17);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  Mixture m = RandomMixture(19, 14);
  m.angle_mask = 2u;
  for (int i = 0; i < 19; ++i) {
    m.means.col(i) << 3.0 + 2.0 * normal(rng), gmmrrt_wrap_angle(angle(rng));
    m.chol[i] << 0.1 + 0.3 * std::fabs(normal(rng)), 0.0, 0.2 * normal(rng), 0.05 + (i % 4 == 0 ? 1.5 : 0.3) * std::fabs(normal(rng));
  }
  m.means(1, 0) = M_PI;  // a mean on the seam
  const Eigen::Index n = 6001;
  Eigen::MatrixXd xt(n, 2);
  for (Eigen::Index c = 0; c < n; ++c) {
    const int i = static_cast<int>(rng() % 19);
    const Eigen::Vector2d z(normal(rng), normal(rng));
    const Eigen::Vector2d x = m.means.col(i) + 2.0 * m.chol[i] * z;
    xt.row(c) << x[0], gmmrrt_wrap_angle(x[1]);
  }
  for (Eigen::Index c = 0; c + 128 <= 3000; c += 128) {  // clumps, every third at the seam
    const double u0 = 3.0 + 2.0 * normal(rng);
    const double u1 = (c / 128) % 3 == 0 ? M_PI - 1e-4 : angle(rng);
    for (Eigen::Index q = c; q < c + 128; ++q)
      xt.row(q) << u0 + 1e-3 * normal(rng), gmmrrt_wrap_angle(u1 + 1e-3 * normal(rng));
  }
  AssertCullingKeepsTheBits(m, xt);
}

// Five separated blobs, 30 000 points: more than a 4 000-point screening sample.
Eigen::MatrixXd FiveBlobs() {
  using test_support::Diag;
  using test_support::Vec;
  return test_support::Sample({{Vec({0.0, 0.0}), Diag({0.5, 0.3}), 8000},
                               {Vec({6.0, 0.0}), Diag({0.4, 0.6}), 7000},
                               {Vec({0.0, 6.0}), Diag({0.3, 0.3}), 6000},
                               {Vec({6.0, 6.0}), Diag({0.6, 0.4}), 5000},
                               {Vec({3.0, 11.0}), Diag({0.5, 0.5}), 4000}},
                              0u, 21);
}

void test_screening_on_a_sample_is_deterministic_and_recovers_the_mixture(void** state) {
  (void)state;
  const Eigen::MatrixXd x = FiveBlobs();
  FitOptions o;
  o.k = 5;
  o.seed = 3;
  o.screen_points = 4000;
  Mixture a, b, all;
  FitSummary sa, sb, sall;
  assert_true(FitMixture(x, 0u, o, &a, &sa).ok());
  assert_true(FitMixture(x, 0u, o, &b, &sb).ok());
  assert_int_equal(sa.screened_on, 4000);
  assert_true(a.means == b.means && a.weights == b.weights);
  o.screen_points = 0;  // screening on all points: the same optimum
  assert_true(FitMixture(x, 0u, o, &all, &sall).ok());
  assert_int_equal(sall.screened_on, x.cols());
  assert_true(std::fabs(sa.final_mean_log_likelihood - sall.final_mean_log_likelihood) < 1e-4);
  const double want_w[5] = {8.0 / 30, 7.0 / 30, 6.0 / 30, 5.0 / 30, 4.0 / 30};
  const double want_mu[5][2] = {{0, 0}, {6, 0}, {0, 6}, {6, 6}, {3, 11}};
  for (int j = 0; j < 5; ++j) {
    int best = 0;
    for (int i = 1; i < 5; ++i)
      if ((a.means.col(i) - Eigen::Vector2d(want_mu[j][0], want_mu[j][1])).norm() <
          (a.means.col(best) - Eigen::Vector2d(want_mu[j][0], want_mu[j][1])).norm())
        best = i;
    assert_true((a.means.col(best) - Eigen::Vector2d(want_mu[j][0], want_mu[j][1])).norm() < 0.05);
    assert_true(std::fabs(a.weights[best] - want_w[j]) < 0.01);
  }
}

}  // namespace

// ParallelFor keeps its helper threads between passes: every task runs exactly once per pass,
// for passes in a row, a pass started from inside a task, and passes from two threads at once
// (the pool serves one; the other takes its own threads).
void test_parallel_for_runs_every_task_once(void** state) {
  (void)state;
  auto pass = [](int threads, long n, std::vector<int>* hits) {
    hits->assign(static_cast<size_t>(n), 0);
    gmmrrt::learn::detail::ParallelFor(threads, n, [hits](long t) { ++(*hits)[static_cast<size_t>(t)]; });
  };
  std::vector<int> hits;
  for (int threads : {1, 2, 3, 5})
    for (long n : {1L, 2L, 7L, 100L}) {
      pass(threads, n, &hits);
      for (int h : hits) assert_int_equal(h, 1);
    }
  std::vector<std::vector<int>> inner(6);
  gmmrrt::learn::detail::ParallelFor(3, 6, [&](long t) { pass(2, 50, &inner[static_cast<size_t>(t)]); });
  for (const std::vector<int>& v : inner)
    for (int h : v) assert_int_equal(h, 1);
  // Two callers at once: every pass of each is checked, not only the last.
  std::vector<int> a, b;
  std::atomic<int> bad_a{0};
  std::thread other([&] {
    for (int r = 0; r < 200; ++r) {
      pass(2, 33, &a);
      for (int h : a) bad_a += h != 1;
    }
  });
  int bad_b = 0;
  for (int r = 0; r < 200; ++r) {
    pass(3, 41, &b);
    for (int h : b) bad_b += h != 1;
  }
  other.join();
  assert_int_equal(bad_a.load(), 0);
  assert_int_equal(bad_b, 0);
  // A task that throws on the calling thread ends the pass: no task starts after it, the tasks
  // running on the other threads finish before the exception reaches the caller, and the next
  // pass runs every task once. The other threads' tasks wait for the caller's throw (so the
  // caller surely takes a task, and each of them holds at most one task when it throws), then
  // work 200 ms (time for the caller to end the pass, even on a loaded machine): at most 3 of the
  // 64 tasks start, and all but the thrown one have finished.
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<bool> caller_threw{false};
  std::atomic<int> started{0}, finished{0};
  std::vector<std::atomic<int>> runs(64);
  bool thrown = false;
  try {
    gmmrrt::learn::detail::ParallelFor(3, 64, [&](long t) {
      runs[static_cast<size_t>(t)].fetch_add(1);
      ++started;
      if (std::this_thread::get_id() == caller) {
        caller_threw = true;
        throw std::runtime_error("task failed");
      }
      while (!caller_threw) std::this_thread::yield();
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      ++finished;
    });
  } catch (const std::runtime_error&) {
    thrown = true;
  }
  assert_true(thrown);
  assert_int_equal(finished.load(), started.load() - 1);
  assert_in_range(started.load(), 1, 3);
  for (const std::atomic<int>& r : runs) assert_in_range(r.load(), 0, 1);
  for (int r = 0; r < 50; ++r) {
    pass(3, 41, &b);
    for (int h : b) assert_int_equal(h, 1);
  }
}

// Helpers join passes; the caller waits only for those that joined, and a helper that joins
// late runs only tasks that are left. Many short passes with gaps (so that the helper sleeps
// and joins late) on 2 and 3 threads: every task of every pass runs exactly once, and no task
// runs after its pass has returned (each pass's counts are checked again at the end).
static void test_late_helpers_never_run_a_finished_pass(void** state) {
  (void)state;
  using namespace gmmrrt::learn::detail;
  constexpr int kPasses = 600;
  std::vector<std::vector<std::atomic<int>>> hits(kPasses);
  const long joins_before = PoolHelperJoins(), sleeps_before = PoolHelperSleeps();
  for (int p = 0; p < kPasses; ++p) {
    const long n = 1 + (p * 7) % 23;
    hits[static_cast<size_t>(p)] = std::vector<std::atomic<int>>(static_cast<size_t>(n));
    std::vector<std::atomic<int>>& h = hits[static_cast<size_t>(p)];
    ParallelFor(2 + p % 2, n, [&h](long t) { h[static_cast<size_t>(t)].fetch_add(1); });
    for (const std::atomic<int>& c : h) assert_int_equal(c.load(), 1);
    if (p % 50 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));  // the helpers sleep
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(20));  // time for any late helper to act
  for (const std::vector<std::atomic<int>>& h : hits)
    for (const std::atomic<int>& c : h) assert_int_equal(c.load(), 1);
  // The pool was used (helpers joined) and its helpers slept in the gaps: the paths above ran.
  assert_true(PoolHelperJoins() > joins_before);
  assert_true(PoolHelperSleeps() > sleeps_before);
  // A sleeping helper is woken for the next pass: after a gap, each of two tasks waits (up to
  // 10 s, for a loaded machine) until both run at once, which only two threads can do.
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::atomic<int> inside{0};
  std::atomic<bool> met{false};
  ParallelFor(2, 2, [&](long) {
    ++inside;
    for (int w = 0; w < 10000 && inside.load() < 2; ++w) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (inside.load() == 2) met = true;
  });
  assert_true(met.load());
}

// The spatial order against a plain twin: each point's Morton index of its cell in a 64 x 64
// grid over the bounding box, then a stable sort by it. The parallel counting sort must give the
// same permutation on any thread count: points in several tasks of 8192 (30 000 here), a
// constant coordinate, a single point, a box that is a line; and a bearing column given beyond
// (-pi, pi], ordered as its wrapped values are.
static std::vector<Eigen::Index> AsVector(const detail::PointOrder& order) {
  return std::vector<Eigen::Index>(order.data(), order.data() + order.size());
}

static std::vector<Eigen::Index> PlainSpatialOrder(const Eigen::MatrixXd& xt) {
  const Eigen::Index n = xt.rows();
  double lo[2], scale[2];
  for (int j = 0; j < 2; ++j) {
    lo[j] = xt.col(j).minCoeff();
    const double span = xt.col(j).maxCoeff() - lo[j];
    scale[j] = span > 0.0 ? 64.0 / span : 0.0;
  }
  std::vector<uint32_t> key(n);
  for (Eigen::Index p = 0; p < n; ++p) {
    uint32_t cell[2];
    for (int j = 0; j < 2; ++j) {
      const double c = (xt(p, j) - lo[j]) * scale[j];
      cell[j] = c > 0.0 ? std::min<uint32_t>(static_cast<uint32_t>(c), 63u) : 0u;
    }
    uint32_t k = 0;
    for (int b = 0; b < 6; ++b) k |= ((cell[0] >> b) & 1u) << (2 * b) | ((cell[1] >> b) & 1u) << (2 * b + 1);
    key[p] = k;
  }
  std::vector<Eigen::Index> order(n);
  for (Eigen::Index p = 0; p < n; ++p) order[p] = p;
  std::stable_sort(order.begin(), order.end(), [&key](Eigen::Index a, Eigen::Index b) { return key[a] < key[b]; });
  return order;
}

static void test_spatial_order_matches_a_stable_sort_on_any_thread_count(void** state) {
  (void)state;
  std::mt19937_64 rng(17);
  std::normal_distribution<double> g(0.0, 3.0);
  Eigen::MatrixXd cloud(30000, 2), flat(20000, 2), one(1, 2);
  for (Eigen::Index p = 0; p < cloud.rows(); ++p) cloud.row(p) << g(rng), 0.3 * g(rng);
  for (Eigen::Index p = 0; p < flat.rows(); ++p) flat.row(p) << g(rng), 1.5;
  one << 0.25, -4.0;
  for (const Eigen::MatrixXd* xt : {&cloud, &flat, &one}) {
    const std::vector<Eigen::Index> want = PlainSpatialOrder(*xt);
    for (int threads : {1, 2, 3}) assert_true(AsVector(detail::SpatialOrder2d(xt->transpose(), 0u, threads)) == want);
  }
  // Bearings with a standard deviation of 9 rad, so about three quarters lie outside
  // (-pi, pi]; the order is that of the wrapped bearings (a different one than of the raw values).
  Eigen::MatrixXd bearing(30000, 2), wrapped(30000, 2);
  for (Eigen::Index p = 0; p < bearing.rows(); ++p) {
    bearing.row(p) << std::fabs(g(rng)), 3.0 * g(rng);
    wrapped.row(p) << bearing(p, 0), gmmrrt_wrap_angle(bearing(p, 1));
  }
  const std::vector<Eigen::Index> want = PlainSpatialOrder(wrapped);
  assert_true(PlainSpatialOrder(bearing) != want);
  for (int threads : {1, 2, 3}) assert_true(AsVector(detail::SpatialOrder2d(bearing.transpose(), 2u, threads)) == want);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_parallel_for_runs_every_task_once),
      cmocka_unit_test(test_late_helpers_never_run_a_finished_pass),
      cmocka_unit_test(test_vector_exp_matches_std_exp),
      cmocka_unit_test(test_vector_log_matches_std_log),
      cmocka_unit_test(test_fused_estep_matches_the_density_and_direct_moments),
      cmocka_unit_test(test_fused_estep_with_angle_matches_the_general_path),
      cmocka_unit_test(test_baseline_and_avx2_kernels_agree),
      cmocka_unit_test(test_culling_components_gives_the_same_bits),
      cmocka_unit_test(test_spatial_order_matches_a_stable_sort_on_any_thread_count),
      cmocka_unit_test(test_culling_terms_with_the_angle_gives_the_same_bits),
      cmocka_unit_test(test_screening_on_a_sample_is_deterministic_and_recovers_the_mixture),
  };
  return cmocka_run_group_tests(tests, nullptr, nullptr);
}
