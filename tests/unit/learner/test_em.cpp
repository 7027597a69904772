// test_em.cpp - learner.em: k-means++ and EM on synthetic mixtures (recovered means and
// weights), monotone log-likelihood, determinism (also across thread counts), SQUAREM against
// plain EM, degenerate components, the +-pi seam, BIC
// choosing the generating K, bad input, and the Eigen density against the C gmm.h density.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <set>

#include "gmmrrt/gmm.h"
#include "gmmrrt_learner/bic.hpp"
#include "gmmrrt_learner/em.hpp"
#include "gmmrrt_learner/kmeans.hpp"
#include "gmmrrt_learner/mixture.hpp"
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
using test_support::Blob;
using test_support::Diag;
using test_support::Vec;

namespace {

std::vector<Blob> ThreeBlobs() {
  Eigen::MatrixXd tilted(2, 2);
  tilted << 0.5, 0.0, 0.3, 0.2;
  return {{Vec({0.0, 0.0}), Diag({0.4, 0.4}), 1500},
          {Vec({6.0, 1.0}), tilted, 900},
          {Vec({2.0, 7.0}), Diag({0.3, 0.6}), 600}};
}

// Index of the component whose mean is nearest to target.
int Nearest(const Mixture& m, const Eigen::VectorXd& target) {
  int best = 0;
  for (int i = 1; i < m.k(); ++i)
    if ((m.means.col(i) - target).norm() < (m.means.col(best) - target).norm()) best = i;
  return best;
}

FitOptions Quiet(int k, uint64_t seed) {
  FitOptions o;
  o.k = k;
  o.seed = seed;
  return o;
}

void test_kmeans_finds_separated_centers(void** state) {
  (void)state;
  const auto blobs = ThreeBlobs();
  const Eigen::MatrixXd x = test_support::Sample(blobs, 0, 7);
  KMeansOptions o;
  o.k = 3;
  std::mt19937_64 rng(3);
  KMeansResult r;
  const Eigen::MatrixXd rows = x.transpose();
  assert_true(KMeans(rows, 0, o, &rng, &r).ok());
  for (const Blob& b : blobs) {
    double nearest = 1e9;
    for (int c = 0; c < 3; ++c) nearest = std::min(nearest, (r.centers.col(c) - b.mean).norm());
    assert_true(nearest < 0.15);
  }
}

// FitMixture runs its candidates side by side, each k-means on a copy of the RNG advanced by
// KMeansRandomDraws per earlier candidate: that count must be what KMeans really draws.
void test_kmeans_draws_what_kmeans_random_draws_says(void** state) {
  (void)state;
  const Eigen::MatrixXd rows = test_support::Sample(ThreeBlobs(), 0, 5).transpose();
  for (int k : {1, 2, 3, 7, 19, 40}) {
    for (int restarts : {1, 3}) {
      for (uint32_t mask : {0u, 2u}) {
        KMeansOptions o;
        o.k = k;
        o.restarts = restarts;
        std::mt19937_64 rng(11), skipped(11);
        KMeansResult r;
        assert_true(KMeans(rows, mask, o, &rng, &r).ok());
        skipped.discard(KMeansRandomDraws(o));
        assert_true(rng == skipped);
      }
    }
  }
}

// Data for the pruned k-means passes: rows (N x D) in strips of 0.25 along dimension 0, each
// strip in order of dimension 1, so consecutive points are close (as FitMixture's spatial order
// makes them) and the 64-point boxes are small, which is where centers get skipped.
Eigen::MatrixXd StripOrdered(const Eigen::MatrixXd& x) {
  std::vector<Eigen::Index> idx(static_cast<size_t>(x.cols()));
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<Eigen::Index>(i);
  std::sort(idx.begin(), idx.end(), [&x](Eigen::Index a, Eigen::Index b) {
    const double sa = std::floor(4.0 * x(0, a)), sb = std::floor(4.0 * x(0, b));
    return sa < sb || (sa == sb && (x(1, a) < x(1, b) || (x(1, a) == x(1, b) && a < b)));
  });
  Eigen::MatrixXd rows(x.cols(), x.rows());
  for (size_t i = 0; i < idx.size(); ++i) rows.row(static_cast<Eigen::Index>(i)) = x.col(idx[i]).transpose();
  return rows;
}

// The k-means test cases: overlapping blobs in D = 2 and D = 3, a lattice (equidistant points:
// ties between centers), blobs across the +-pi seam of an angle on dimension 1, and the D = 2
// blobs moved far from the origin (1e6: the differences lose 20 bits to the coordinates, which
// the bounds carried across Lloyd passes must allow for).
struct KMeansCase {
  Eigen::MatrixXd rows;
  uint32_t mask;
  int k;
};

std::vector<KMeansCase> KMeansCases() {
  std::vector<KMeansCase> cases;
  std::vector<Blob> blobs2, blobs3, seam;
  for (int b = 0; b < 6; ++b) {
    blobs2.push_back({Vec({1.5 * (b % 3), 2.0 * (b / 3)}), Diag({0.5 + 0.1 * b, 0.6}), 4000});
    blobs3.push_back({Vec({1.5 * (b % 3), 2.0 * (b / 3), 0.5 * b}), Diag({0.5, 0.6, 0.4}), 3000});
  }
  seam = {{Vec({1.0, 3.0}), Diag({0.3, 0.25}), 6000},
          {Vec({2.0, -3.0}), Diag({0.3, 0.25}), 6000},
          {Vec({1.5, 0.0}), Diag({0.4, 0.5}), 6000}};
  cases.push_back({StripOrdered(test_support::Sample(blobs2, 0, 31)), 0u, 9});
  cases.push_back({test_support::Sample(blobs3, 0, 32).transpose(), 0u, 7});
  Eigen::MatrixXd lattice(2, 41 * 41);
  for (int i = 0; i < 41; ++i)
    for (int j = 0; j < 41; ++j) lattice.col(41 * i + j) << i, j;
  cases.push_back({lattice.transpose(), 0u, 4});
  cases.push_back({StripOrdered(test_support::Sample(seam, 2u, 33)), 2u, 5});
  Eigen::MatrixXd far = StripOrdered(test_support::Sample(blobs2, 0, 34));
  far.array() += 1e6;
  cases.push_back({far, 0u, 9});
  return cases;
}

// The assignment step skips centers by box bounds: its labels and distances must be those of a
// scan over every center (ties to the lower index), and the inertia their sum (k-means adds the
// distances per group of points and then the groups, this test in one run: the two orders
// differ by at most about N ulps of the sum, N <= 24 000, hence the relative 1e-11).
void test_kmeans_pruned_assignment_equals_a_full_scan(void** state) {
  (void)state;
  for (const KMeansCase& c : KMeansCases()) {
    KMeansOptions o;
    o.k = c.k;
    o.restarts = 1;
    std::mt19937_64 rng(5);
    KMeansResult r;
    assert_true(KMeans(c.rows, c.mask, o, &rng, &r).ok());
    Eigen::ArrayXd best, d2;
    SquaredDistances(c.rows, r.centers.col(0), c.mask, &best);
    std::vector<int> labels(static_cast<size_t>(c.rows.rows()), 0);
    for (int j = 1; j < c.k; ++j) {
      SquaredDistances(c.rows, r.centers.col(j), c.mask, &d2);
      for (Eigen::Index p = 0; p < c.rows.rows(); ++p)
        if (d2[p] < best[p]) {
          best[p] = d2[p];
          labels[static_cast<size_t>(p)] = j;
        }
    }
    assert_true(labels == r.labels);
    assert_true(std::fabs(best.sum() - r.inertia) <= 1e-11 * best.sum());
  }
}

// Pruning (the seeding's and the assignment's) changes no bit, and neither does the number of
// threads: centers, labels and inertia are the same for pruned or full passes on 1, 2 or 3
// threads (N up to 24 000: several tasks of 8192 points).
void test_kmeans_is_the_same_pruned_or_not_on_any_thread_count(void** state) {
  (void)state;
  for (const KMeansCase& c : KMeansCases()) {
    for (int iterations : {1, 100}) {  // one Lloyd step: the centers still show the seeding's picks
    KMeansResult ref;
    bool have_ref = false;
    for (bool prune : {false, true})
      for (int threads : {1, 2, 3}) {
        KMeansOptions o;
        o.k = c.k;
        o.restarts = 2;
        o.max_iterations = iterations;
        o.prune = prune;
        o.threads = threads;
        std::mt19937_64 rng(9);
        KMeansResult r;
        assert_true(KMeans(c.rows, c.mask, o, &rng, &r).ok());
        if (!have_ref) {
          ref = r;
          have_ref = true;
          continue;
        }
        assert_true(r.centers == ref.centers);
        assert_true(r.labels == ref.labels);
        assert_true(r.inertia == ref.inertia);
        assert_int_equal(r.iterations, ref.iterations);
      }
    }
  }
}

void test_em_recovers_means_and_weights(void** state) {
  (void)state;
  const auto blobs = ThreeBlobs();
  const Eigen::MatrixXd x = test_support::Sample(blobs, 0, 11);
  Mixture m;
  FitSummary s;
  assert_true(FitMixture(x, 0, Quiet(3, 1), &m, &s).ok());
  assert_int_equal(m.k(), 3);
  assert_true(s.converged);
  const double n = static_cast<double>(x.cols());
  for (const Blob& b : blobs) {
    const int i = Nearest(m, b.mean);
    assert_true((m.means.col(i) - b.mean).norm() < 0.1);
    assert_true(std::fabs(m.weights[i] - b.count / n) < 0.02);
    const Eigen::MatrixXd cov = m.chol[i] * m.chol[i].transpose();
    const Eigen::MatrixXd truth = b.chol * b.chol.transpose();
    assert_true((cov - truth).cwiseAbs().maxCoeff() < 0.05);
  }
  // The summary's final value is the mixture's mean log-likelihood.
  assert_true(std::fabs(MeanLogLikelihood(m, x) - s.final_mean_log_likelihood) < 1e-12);
}

// The stages' times: each spent (positive: every stage has work here, the candidates screened
// for one step), none counted twice (together within the call's own time), on a fit that screens
// its candidates on a sample and on one that does not.
void test_stage_times_add_up_within_the_call(void** state) {
  (void)state;
  const Eigen::MatrixXd x = test_support::Sample(ThreeBlobs(), 0, 11);
  for (int64_t screen_points : {int64_t{0}, int64_t{500}}) {
    FitOptions o = Quiet(3, 1);
    o.screen_points = screen_points;
    o.screen_iterations = 1;  // so the kept candidate has steps left for the converge stage
    Mixture m;
    FitSummary s;
    const auto t0 = std::chrono::steady_clock::now();
    assert_true(FitMixture(x, 0, o, &m, &s).ok());
    const double call = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    assert_true(s.prepare_seconds > 0.0 && s.candidates_seconds > 0.0 && s.converge_seconds > 0.0);
    assert_true(s.prepare_seconds + s.candidates_seconds + s.converge_seconds <= call);
    assert_true(s.BriefReport().find(" seconds: prepare=") != std::string::npos);
  }
}

void test_em_log_likelihood_never_decreases(void** state) {
  (void)state;
  // Overlapping blobs so that EM needs many steps.
  std::vector<Blob> blobs = {{Vec({0.0, 0.0}), Diag({1.0, 1.0}), 800},
                             {Vec({1.5, 0.5}), Diag({0.7, 1.2}), 800},
                             {Vec({-1.0, 2.0}), Diag({0.5, 0.5}), 400}};
  const Eigen::MatrixXd x = test_support::Sample(blobs, 0, 5);
  FitOptions o = Quiet(3, 2);
  o.restarts = 1;
  o.tolerance = 1e-10;
  Mixture m;
  FitSummary s;
  assert_true(FitMixture(x, 0, o, &m, &s).ok());
  assert_true(s.reseed_iterations.empty());
  assert_true(s.log_likelihood.size() > 5);
  for (size_t t = 1; t < s.log_likelihood.size(); ++t)
    assert_true(s.log_likelihood[t] >= s.log_likelihood[t - 1] - 1e-12);
}

// Overlapping components, each large enough that the E-step is cut into several tasks (8192
// points for D = 2, 8192 for the general path): the thread count must not change a bit. The
// passes before EM (checks, copies, spatial order, data moments, k-means, the hard assignment's
// sums) run in tasks of 8192 points too; the last dimension is also taken as an angle, with
// components across the seam, so the circular mean and the wrapped differences are covered.
void test_any_thread_count_gives_the_same_bits(void** state) {
  (void)state;
  for (int d : {2, 3})
  for (uint32_t mask : {0u, 1u << (d - 1)}) {
    std::vector<Blob> blobs;
    for (int b = 0; b < 4; ++b) {
      Eigen::VectorXd mu = Eigen::VectorXd::Zero(d);
      mu[0] = 1.2 * b;
      mu[d - 1] = mask ? 2.8 + 0.5 * (b % 2) : 0.5 * (b % 2);  // angle: about the seam at pi
      blobs.push_back({mu, Eigen::MatrixXd::Identity(d, d) * (0.6 + 0.1 * b), 6000});
    }
    const Eigen::MatrixXd x = test_support::Sample(blobs, mask, 21);
    // 8 candidates run side by side, one thread each; 1 candidate runs its k-means and EM on
    // all the threads. The candidates on all points, and on a sample of 5000 of the 24 000
    // (drawn in tasks of 8192 points).
    for (int64_t screen_points : {int64_t{0}, int64_t{5000}})
    for (int restarts : {8, 1}) {
    Mixture ref;
    FitSummary sref;
    for (int threads : {1, 2, 3, 5}) {
      FitOptions o = Quiet(4, 8);
      o.restarts = restarts;
      o.threads = threads;
      o.max_iterations = 40;
      o.screen_points = screen_points;
      Mixture m;
      FitSummary s;
      assert_true(FitMixture(x, mask, o, &m, &s).ok());
      assert_int_equal(s.threads, threads);
      if (threads == 1) {
        ref = m;
        sref = s;
        continue;
      }
      assert_int_equal(m.k(), ref.k());
      assert_true(m.weights == ref.weights);
      assert_true(m.means == ref.means);
      for (int i = 0; i < m.k(); ++i) assert_true(m.chol[i] == ref.chol[i]);
      assert_true(s.log_likelihood == sref.log_likelihood);
    }
    }
  }
}

// --max-iter N is N EM steps however the candidates were screened: on all points (whose
// screening steps are the fit's first ones) and on a sample (the kept candidate then continues
// on all points, at least a quarter of the cap), with plain EM and SQUAREM (each E-step counts,
// refused extrapolations too).
void test_iteration_cap_is_exact(void** state) {
  (void)state;
  std::vector<Blob> blobs = {{Vec({0.0, 0.0}), Diag({1.0, 1.0}), 3000},
                             {Vec({1.5, 0.5}), Diag({0.7, 1.2}), 3000},
                             {Vec({-1.0, 2.0}), Diag({0.5, 0.5}), 2000}};
  const Eigen::MatrixXd x = test_support::Sample(blobs, 0, 6);
  for (int screen_points : {0, 2000})
    for (int restarts : {1, 3})
      for (bool accelerate : {false, true})
        for (int cap : {0, 1, 5, 16, 25}) {
          FitOptions o = Quiet(3, 4);
          o.restarts = restarts;
          o.screen_points = screen_points;
          o.accelerate = accelerate;
          o.tolerance = 1e-300;  // no step converges: the cap stops the fit
          o.max_iterations = cap;
          Mixture m;
          FitSummary s;
          assert_true(FitMixture(x, 0, o, &m, &s).ok());
          assert_false(s.converged);
          if (!accelerate) {
            assert_int_equal(s.iterations, cap);
            if (screen_points == 0) assert_int_equal(s.log_likelihood.size(), cap + 1);
            // On a sample, a quarter of the cap (at least one step) is left to all points.
            const int on_all = cap == 0 ? 0 : cap == 1 ? 1 : cap == 5 ? 1 : cap == 16 ? 4 : 6;
            if (screen_points > 0) assert_int_equal(s.log_likelihood.size(), on_all + 1);
          } else {
            assert_true(s.iterations <= cap);
            // Every E-step counts, the refused extrapolations' included: on all points the
            // history plus the refused steps is the cap exactly.
            if (screen_points == 0)
              assert_int_equal(static_cast<int>(s.log_likelihood.size()) - 1 + s.extrapolations_refused, cap);
          }
        }
}

// SQUAREM on overlapping components (where plain EM crawls): at least plain EM's likelihood
// (less 1e-4 nats/point: both stop at a tolerance, not at the optimum itself), in fewer than
// half the E-steps, and the recorded log-likelihood never decreases.
void test_squarem_reaches_plain_em_likelihood_in_fewer_steps(void** state) {
  (void)state;
  std::vector<Blob> blobs;
  for (int b = 0; b < 6; ++b) {
    Eigen::MatrixXd l(2, 2);
    l << 0.8, 0.0, 0.3 * (b % 3 - 1), 0.5 + 0.1 * b;
    blobs.push_back({Vec({1.0 * b, 0.6 * (b % 2)}), l, 1500});
  }
  const Eigen::MatrixXd x = test_support::Sample(blobs, 0, 17);
  FitSummary plain, fast;
  Mixture mp, mf;
  FitOptions o = Quiet(6, 4);
  o.restarts = 1;
  o.tolerance = 1e-7;
  o.max_iterations = 20000;
  o.accelerate = false;
  assert_true(FitMixture(x, 0, o, &mp, &plain).ok());
  o.accelerate = true;
  assert_true(FitMixture(x, 0, o, &mf, &fast).ok());
  print_message("plain: %d iterations, %.9f; squarem: %d iterations, %.9f (%d refused)\n", plain.iterations,
                plain.final_mean_log_likelihood, fast.iterations, fast.final_mean_log_likelihood,
                fast.extrapolations_refused);
  assert_true(plain.converged && fast.converged);
  assert_true(fast.final_mean_log_likelihood > plain.final_mean_log_likelihood - 1e-4);
  assert_true(fast.iterations * 2 < plain.iterations);
  for (size_t t = 1; t < fast.log_likelihood.size(); ++t)
    assert_true(fast.log_likelihood[t] >= fast.log_likelihood[t - 1] - 1e-12);
}

void test_same_seed_gives_the_same_mixture(void** state) {
  (void)state;
  const Eigen::MatrixXd x = test_support::Sample(ThreeBlobs(), 0, 13);
  Mixture a, b;
  FitSummary sa, sb;
  assert_true(FitMixture(x, 0, Quiet(4, 99), &a, &sa).ok());
  assert_true(FitMixture(x, 0, Quiet(4, 99), &b, &sb).ok());
  assert_int_equal(a.k(), b.k());
  assert_true(a.weights == b.weights);
  assert_true(a.means == b.means);
  for (int i = 0; i < a.k(); ++i) assert_true(a.chol[i] == b.chol[i]);
  assert_true(sa.log_likelihood == sb.log_likelihood);
}

void test_degenerate_components_are_reseeded_or_dropped(void** state) {
  (void)state;
  // 300 points on only 3 distinct values: K = 5 must collapse, the fit must still succeed.
  Eigen::MatrixXd x(1, 300);
  for (int i = 0; i < 300; ++i) x(0, i) = (i % 3) * 10.0 + (i % 2) * 1e-3;
  std::vector<std::string> warnings;
  FitOptions o = Quiet(5, 1);
  o.warn = [&warnings](const std::string& w) { warnings.push_back(w); };
  Mixture m;
  FitSummary s;
  assert_true(FitMixture(x, 0, o, &m, &s).ok());
  assert_true(s.reseeds + s.dropped > 0);
  assert_false(warnings.empty());
  assert_int_equal(static_cast<int>(warnings.size()), static_cast<int>(s.warnings.size()));
  assert_true(ValidateMixture(m).ok());
  assert_int_equal(m.k(), s.k_final);
  assert_true(std::isfinite(s.final_mean_log_likelihood));
}

void test_cluster_across_the_seam_is_one_component(void** state) {
  (void)state;
  // (d, theta): a cluster behind the person (theta = pi, sd 0.25: half its points are near -pi)
  // and one in front; K = 2 must give one component at the back, one at the front.
  const uint32_t mask = 1u << 1;
  std::vector<Blob> blobs = {{Vec({1.5, M_PI}), Diag({0.2, 0.25}), 1200},
                             {Vec({2.5, 0.0}), Diag({0.3, 0.3}), 800}};
  const Eigen::MatrixXd x = test_support::Sample(blobs, mask, 21);
  int plus = 0, minus = 0;
  for (int i = 0; i < 1200; ++i) (x(1, i) > 0 ? plus : minus)++;
  assert_true(plus > 400 && minus > 400);  // the data really straddles the seam
  Mixture m;
  FitSummary s;
  assert_true(FitMixture(x, mask, Quiet(2, 4), &m, &s).ok());
  assert_int_equal(m.k(), 2);
  const int back = std::fabs(m.means(1, 0)) > std::fabs(m.means(1, 1)) ? 0 : 1;
  assert_true(std::fabs(gmmrrt_wrap_angle(m.means(1, back) - M_PI)) < 0.05);
  assert_true(std::fabs(m.weights[back] - 0.6) < 0.02);
  const Eigen::MatrixXd cov = m.chol[back] * m.chol[back].transpose();
  assert_true(std::fabs(std::sqrt(cov(1, 1)) - 0.25) < 0.03);  // not a 2 pi wide smear
  assert_true(m.means(1, back) > -M_PI && m.means(1, back) <= M_PI);
}

// 1 400 points of four separated Gaussians (the sweep tests' generating K = 4).
static Eigen::MatrixXd FourSeparatedBlobs() {
  std::vector<Blob> blobs = {{Vec({0.0, 0.0}), Diag({0.5, 0.5}), 400},
                             {Vec({5.0, 0.0}), Diag({0.5, 0.8}), 400},
                             {Vec({0.0, 5.0}), Diag({0.7, 0.4}), 300},
                             {Vec({5.0, 5.0}), Diag({0.4, 0.4}), 300}};
  return test_support::Sample(blobs, 0, 8);
}

void test_bic_picks_the_generating_k(void** state) {
  (void)state;
  const Eigen::MatrixXd x = FourSeparatedBlobs();
  BicSweepResult r;
  assert_true(SweepBic(x, 0, Quiet(1, 1), 1, 8, &r, nullptr, 0).ok());  // the whole range
  assert_int_equal(static_cast<int>(r.rows.size()), 8);
  assert_int_equal(r.best_k, 4);
  assert_int_equal(r.best.k(), 4);
  assert_true(FormatBicTable(r).find("  *") != std::string::npos);
  assert_true(r.note.empty());
  // The default stops once BIC has stayed above its minimum for kBicStopAfterRises K: the same
  // choice and rows, the sweep ended at K = 4 + 3 with a note.
  BicSweepResult early;
  assert_true(SweepBic(x, 0, Quiet(1, 1), 1, 8, &early).ok());
  assert_int_equal(early.best_k, 4);
  assert_int_equal(static_cast<int>(early.rows.size()), 4 + kBicStopAfterRises);
  for (size_t i = 0; i < early.rows.size(); ++i) assert_true(early.rows[i].bic == r.rows[i].bic);
  assert_true(early.note.find("K = 7") != std::string::npos);
  assert_int_equal(static_cast<int>(SweepBic(x, 0, Quiet(1, 1), 1, 8, &early, nullptr, -1).code),
                   static_cast<int>(StatusCode::kInvalidArgument));
}

// Each K after the first screens fresh_starts k-means++ candidates beside its split starts
// (min(K - 1, split_starts) of them), the first K options.restarts; without split starts every
// K screens options.restarts. Counted from the candidates the progress callback reports, and
// checked against what each row says it screened.
void test_sweep_screens_fewer_fresh_starts_beside_the_splits(void** state) {
  (void)state;
  const Eigen::MatrixXd x = FourSeparatedBlobs();
  auto sweep = [&x](int split_starts, int fresh_starts, BicSweepResult* r, std::vector<int>* seen_per_k) {
    std::set<int> seen;
    seen_per_k->clear();
    FitOptions o = Quiet(1, 1);
    assert_int_equal(o.restarts, 8);
    o.progress = [&seen](int restart, int, double) { seen.insert(restart); };
    return SweepBic(x, 0, o, 1, 7, r, [&](const BicRow&) {
      seen_per_k->push_back(static_cast<int>(seen.size()));
      seen.clear();
    }, 0, split_starts, fresh_starts);
  };
  BicSweepResult r;
  std::vector<int> seen;
  assert_true(sweep(4, 2, &r, &seen).ok());
  assert_int_equal(static_cast<int>(r.rows.size()), 7);
  for (int k = 1; k <= 7; ++k) {
    const int splits = k == 1 ? 0 : std::min(k - 1, 4), fresh = k == 1 ? 8 : 2;
    assert_int_equal(r.rows[k - 1].split_starts, splits);
    assert_int_equal(r.rows[k - 1].fresh_starts, fresh);
    assert_int_equal(seen[k - 1], fresh + splits);
  }
  assert_true(sweep(4, 100, &r, &seen).ok());  // never more than options.restarts
  for (int k = 2; k <= 7; ++k) assert_int_equal(seen[k - 1], 8 + std::min(k - 1, 4));
  assert_true(sweep(0, 2, &r, &seen).ok());  // no warm starts: every K screens all
  for (int c : seen) assert_int_equal(c, 8);
  assert_int_equal(static_cast<int>(sweep(4, 0, &r, &seen).code), static_cast<int>(StatusCode::kInvalidArgument));
}

// The sweep with its fewer fresh starts gives the same rows, bit for bit, on 1 and 2 threads
// (the fresh candidates run side by side with 2; see em.hpp on determinism).
void test_sweep_is_the_same_on_any_thread_count(void** state) {
  (void)state;
  std::vector<Blob> blobs = {{Vec({0.0, 0.0}), Diag({0.6, 0.6}), 500},
                             {Vec({2.0, 0.0}), Diag({0.6, 0.9}), 500},
                             {Vec({1.0, 2.0}), Diag({0.8, 0.5}), 400}};
  const Eigen::MatrixXd x = test_support::Sample(blobs, 0, 11);
  BicSweepResult r[2];
  for (int t = 0; t < 2; ++t) {
    FitOptions o = Quiet(1, 5);
    o.threads = t + 1;
    assert_true(SweepBic(x, 0, o, 1, 6, &r[t], nullptr, 0).ok());
  }
  assert_int_equal(static_cast<int>(r[0].rows.size()), 6);
  assert_int_equal(static_cast<int>(r[1].rows.size()), 6);
  for (size_t i = 0; i < r[0].rows.size(); ++i) {
    assert_true(r[0].rows[i].bic == r[1].rows[i].bic);
    assert_int_equal(r[0].rows[i].iterations, r[1].rows[i].iterations);
  }
  assert_int_equal(r[0].rows[1].fresh_starts, kBicFreshStarts);
  assert_int_equal(r[0].best_k, r[1].best_k);
}

void test_bad_input_is_rejected(void** state) {
  (void)state;
  Mixture m;
  FitSummary s;
  Eigen::MatrixXd empty(2, 0);
  assert_int_equal(static_cast<int>(FitMixture(empty, 0, Quiet(1, 1), &m, &s).code),
                   static_cast<int>(StatusCode::kNotEnoughData));
  Eigen::MatrixXd few = Eigen::MatrixXd::Random(2, 10);
  assert_int_equal(static_cast<int>(FitMixture(few, 0, Quiet(4, 1), &m, &s).code),
                   static_cast<int>(StatusCode::kNotEnoughData));
  Eigen::MatrixXd nan = Eigen::MatrixXd::Random(2, 100);
  nan(1, 50) = std::nan("");
  const Status st = FitMixture(nan, 0, Quiet(2, 1), &m, &s);
  assert_int_equal(static_cast<int>(st.code), static_cast<int>(StatusCode::kBadInput));
  assert_true(st.message.find("point 50, dimension 1 is not finite") != std::string::npos);
  // The check runs in tasks of 8192 points on the threads: the first bad value in the points'
  // order is named whichever task finds one first.
  Eigen::MatrixXd nans = Eigen::MatrixXd::Random(2, 30000);
  nans(0, 25000) = std::nan("");
  nans(1, 9000) = INFINITY;
  nans(0, 9001) = std::nan("");
  for (int threads : {1, 2, 3}) {
    FitOptions o = Quiet(2, 1);
    o.threads = threads;
    const Status bad_st = FitMixture(nans, 0, o, &m, &s);
    assert_int_equal(static_cast<int>(bad_st.code), static_cast<int>(StatusCode::kBadInput));
    assert_true(bad_st.message.find("point 9000, dimension 1 is not finite") != std::string::npos);
  }
  // A finite value so large that squared distances overflow (one point at 1e200 crashed the fit):
  // refused by name, whatever the thread count; 1e150 itself is taken.
  Eigen::MatrixXd huge = Eigen::MatrixXd::Random(2, 20000);
  huge(0, 12345) = 1e200;
  for (int threads : {1, 2}) {
    FitOptions o = Quiet(3, 1);
    o.threads = threads;
    const Status huge_st = FitMixture(huge, 0, o, &m, &s);
    assert_int_equal(static_cast<int>(huge_st.code), static_cast<int>(StatusCode::kBadInput));
    assert_true(huge_st.message.find("point 12345, dimension 0 is 1e+200") != std::string::npos);
  }
  huge(0, 12345) = -1e150;  // at the limit: not refused by it (the fit itself may still fail)
  const Status edge = FitMixture(huge, 0, Quiet(3, 1), &m, &s);
  assert_true(edge.message.find("rescale") == std::string::npos);
  Eigen::MatrixXd constant = Eigen::MatrixXd::Random(2, 100);
  constant.row(0).setConstant(3.0);
  assert_int_equal(static_cast<int>(FitMixture(constant, 0, Quiet(2, 1), &m, &s).code),
                   static_cast<int>(StatusCode::kBadInput));
  FitOptions bad = Quiet(0, 1);
  std::string why;
  assert_false(bad.IsValid(&why));
  assert_true(why.find("k") != std::string::npos);
  assert_int_equal(static_cast<int>(FitMixture(few, 0, bad, &m, &s).code),
                   static_cast<int>(StatusCode::kInvalidArgument));
}

void test_eigen_density_equals_the_c_density(void** state) {
  (void)state;
  // A random 3-D mixture with one angle dimension, evaluated by both implementations.
  std::mt19937_64 rng(17);
  std::normal_distribution<double> normal(0.0, 1.0);
  Mixture m;
  m.dim = 3;
  m.angle_mask = 1u << 2;
  const int k = 6;
  m.weights.resize(k);
  m.means.resize(3, k);
  m.chol.assign(k, Eigen::MatrixXd::Zero(3, 3));
  for (int i = 0; i < k; ++i) {
    m.weights[i] = 0.5 + std::fabs(normal(rng));
    for (int j = 0; j < 3; ++j) m.means(j, i) = 2.0 * normal(rng);
    m.means(2, i) = gmmrrt_wrap_angle(m.means(2, i) + (i == 0 ? M_PI : 0.0));
    for (int r = 0; r < 3; ++r) {
      m.chol[i](r, r) = 0.2 + 0.5 * std::fabs(normal(rng));
      for (int c = 0; c < r; ++c) m.chol[i](r, c) = 0.2 * normal(rng);
    }
  }
  m.weights /= m.weights.sum();
  gmmrrt_model_t model;
  assert_true(MixtureToModel(m, GMMRRT_MODEL_KIND_GENERIC, GMMRRT_TASK_NONE, GMMRRT_HOMOTOPY_ALL, 0.001, &model).ok());
  char err[128];
  assert_int_equal(gmmrrt_model_prepare(&model, err, sizeof err), GMMRRT_OK);
  Eigen::MatrixXd pts(3, 500);
  for (int c = 0; c < 500; ++c)
    for (int j = 0; j < 3; ++j) pts(j, c) = 3.0 * normal(rng);
  pts(2, 0) = M_PI;
  pts(2, 1) = -M_PI + 1e-12;
  Eigen::VectorXd ll;
  LogDensity(m, pts, &ll);
  for (int c = 0; c < 500; ++c) {
    const double expected = gmmrrt_gmm_log_density(&model, pts.col(c).data());
    assert_true(std::fabs(ll[c] - expected) <= 1e-9 * std::max(1.0, std::fabs(expected)));
  }
  // And back: the model's stored fields give the same mixture.
  const Mixture back = MixtureFromModel(model);
  assert_true(back.means == m.means && back.weights == m.weights);
}

}  // namespace

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_kmeans_finds_separated_centers),
      cmocka_unit_test(test_kmeans_draws_what_kmeans_random_draws_says),
      cmocka_unit_test(test_kmeans_pruned_assignment_equals_a_full_scan),
      cmocka_unit_test(test_kmeans_is_the_same_pruned_or_not_on_any_thread_count),
      cmocka_unit_test(test_em_recovers_means_and_weights),
      cmocka_unit_test(test_stage_times_add_up_within_the_call),
      cmocka_unit_test(test_em_log_likelihood_never_decreases),
      cmocka_unit_test(test_same_seed_gives_the_same_mixture),
      cmocka_unit_test(test_any_thread_count_gives_the_same_bits),
      cmocka_unit_test(test_squarem_reaches_plain_em_likelihood_in_fewer_steps),
      cmocka_unit_test(test_iteration_cap_is_exact),
      cmocka_unit_test(test_degenerate_components_are_reseeded_or_dropped),
      cmocka_unit_test(test_cluster_across_the_seam_is_one_component),
      cmocka_unit_test(test_bic_picks_the_generating_k),
      cmocka_unit_test(test_sweep_screens_fewer_fresh_starts_beside_the_splits),
      cmocka_unit_test(test_sweep_is_the_same_on_any_thread_count),
      cmocka_unit_test(test_bad_input_is_rejected),
      cmocka_unit_test(test_eigen_density_equals_the_c_density),
  };
  return cmocka_run_group_tests(tests, nullptr, nullptr);
}
