// kmeans.cpp - greedy k-means++ seeding and Lloyd iterations with restarts, seam-safe for angle
// dimensions (the update moves a center by the mean wrapped difference, then wraps it).
// Seeds EM (em.cpp); see kmeans.hpp. Points are rows (N x D) so distances are vector ops.
#include "gmmrrt_learner/kmeans.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "gmmrrt/features.h"
#include "gmmrrt_learner/mixture.hpp"

namespace gmmrrt {
namespace learn {

bool KMeansOptions::IsValid(std::string* error) const {
  if (k < 1) { *error = "k must be >= 1"; return false; }
  if (restarts < 1) { *error = "restarts must be >= 1"; return false; }
  if (max_iterations < 1) { *error = "max_iterations must be >= 1"; return false; }
  return true;
}

// The candidates per k-means++ step (greedy k-means++).
static int SeedTrials(int k) { return 2 + static_cast<int>(std::log(static_cast<double>(k))); }

uint64_t KMeansRandomDraws(const KMeansOptions& options) {
  return static_cast<uint64_t>(options.restarts) *
         (1u + static_cast<uint64_t>(options.k - 1) * static_cast<uint64_t>(SeedTrials(options.k)));
}

double Uniform01(std::mt19937_64* rng) {
  return static_cast<double>((*rng)() >> 11) * (1.0 / 9007199254740992.0);
}

namespace {

// One angle difference per point, centre and iteration: the core's wrap, inline (features.h).
inline double Wrap(double v) { return gmmrrt_wrap_angle_inline(v); }

}  // namespace

void SquaredDistances(const Eigen::MatrixXd& points, const Eigen::VectorXd& center,
                      uint32_t angle_mask, Eigen::ArrayXd* d2) {
  const Eigen::Index n = points.rows();
  d2->resize(n);
  if (angle_mask == 0u) {  // one pass, no temporary (the same sums: 0 + a^2 = a^2 exactly)
    *d2 = (points.col(0).array() - center[0]).square();
    for (Eigen::Index c = 1; c < points.cols(); ++c) *d2 += (points.col(c).array() - center[c]).square();
    return;
  }
  d2->setZero();
  Eigen::ArrayXd diff(n);
  for (Eigen::Index c = 0; c < points.cols(); ++c) {
    diff = points.col(c).array() - center[c];
    if (c < 32 && ((angle_mask >> c) & 1u))
      for (Eigen::Index p = 0; p < n; ++p) diff[p] = Wrap(diff[p]);
    *d2 += diff.square();
  }
}

namespace {

Eigen::Index UniformIndex(Eigen::Index n, std::mt19937_64* rng) {
  return std::min<Eigen::Index>(static_cast<Eigen::Index>(Uniform01(rng) * static_cast<double>(n)), n - 1);
}

// Index drawn with probability proportional to weight (cumulative sums in cum, total > 0).
Eigen::Index DrawProportional(const Eigen::ArrayXd& cum, std::mt19937_64* rng) {
  const double u = Uniform01(rng) * cum[cum.size() - 1];
  const double* first = cum.data();
  const double* it = std::upper_bound(first, first + cum.size(), u);
  return std::min<Eigen::Index>(it - first, cum.size() - 1);
}

void SeedPlusPlus(const Eigen::MatrixXd& x, uint32_t mask, int k, std::mt19937_64* rng,
                  Eigen::MatrixXd* centers) {
  const Eigen::Index n = x.rows();
  centers->resize(x.cols(), k);
  centers->col(0) = x.row(UniformIndex(n, rng)).transpose();
  Eigen::ArrayXd closest, d2, best_d2, cum(n);
  SquaredDistances(x, centers->col(0), mask, &closest);
  const int trials = SeedTrials(k);
  for (int c = 1; c < k; ++c) {
    std::partial_sum(closest.data(), closest.data() + n, cum.data());
    double best_potential = std::numeric_limits<double>::infinity();
    Eigen::Index best = 0;
    for (int t = 0; t < trials; ++t) {
      const Eigen::Index cand = cum[n - 1] > 0.0 ? DrawProportional(cum, rng) : UniformIndex(n, rng);
      SquaredDistances(x, x.row(cand).transpose(), mask, &d2);
      const double potential = closest.min(d2).sum();
      if (potential < best_potential) {
        best_potential = potential;
        best = cand;
        best_d2 = d2;
      }
    }
    centers->col(c) = x.row(best).transpose();
    closest = closest.min(best_d2);
  }
}

// Assigns every point to its nearest center (ties: the lower index); returns the inertia.
// Compiled twice on x86-64, for the baseline and for AVX2 (4 distances per instruction instead
// of 2), chosen when the program loads: the same operations lane by lane (no FMA), so the same
// labels and bits; it was a tenth of the benchmark fit's time, in the candidates' Lloyd steps.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__linux__)
__attribute__((target_clones("avx2", "default")))
#endif
double Assign(const Eigen::MatrixXd& x, uint32_t mask, const Eigen::MatrixXd& centers,
              Eigen::ArrayXi* labels, Eigen::ArrayXd* best) {
  const Eigen::Index n = x.rows();
  if (x.cols() == 2 && (mask == 0u || mask == 2u)) {
    // D = 2, plain or with the angle on dimension 1 (the benchmark's and the planner's (d, theta)
    // features): one pass over the points per center, no temporaries; the same distances and
    // ties (strict <: the lower index wins) as below.
    const bool angle = mask == 2u;
    labels->resize(n);
    best->resize(n);
    const double* x0 = x.col(0).data();
    const double* x1 = x.col(1).data();
    int* lab = labels->data();
    double* bst = best->data();
    {
      const double c0 = centers(0, 0), c1 = centers(1, 0);
      for (Eigen::Index p = 0; p < n; ++p) {
        const double a = x0[p] - c0, b = angle ? Wrap(x1[p] - c1) : x1[p] - c1;
        bst[p] = a * a + b * b;
        lab[p] = 0;
      }
    }
    for (Eigen::Index c = 1; c < centers.cols(); ++c) {
      const double c0 = centers(0, c), c1 = centers(1, c);
      const int ci = static_cast<int>(c);
      for (Eigen::Index p = 0; p < n; ++p) {
        const double a = x0[p] - c0, b = angle ? Wrap(x1[p] - c1) : x1[p] - c1;
        const double d = a * a + b * b;
        const bool closer = d < bst[p];
        bst[p] = closer ? d : bst[p];
        lab[p] = closer ? ci : lab[p];
      }
    }
    return best->sum();
  }
  Eigen::ArrayXd d2;
  SquaredDistances(x, centers.col(0), mask, best);
  labels->setZero(n);
  for (Eigen::Index c = 1; c < centers.cols(); ++c) {
    SquaredDistances(x, centers.col(c), mask, &d2);
    const auto closer = d2 < *best;
    *labels = closer.select(static_cast<int>(c), *labels);
    *best = closer.select(d2, *best);
  }
  return best->sum();
}

// Moves the centers to their clusters' means; returns the summed squared center shift.
double Update(const Eigen::MatrixXd& x, uint32_t mask, const Eigen::ArrayXi& labels,
              const Eigen::ArrayXd& best, Eigen::MatrixXd* centers) {
  const Eigen::Index k = centers->cols(), n = x.rows();
  Eigen::MatrixXd shift = Eigen::MatrixXd::Zero(x.cols(), k);
  Eigen::VectorXd count = Eigen::VectorXd::Zero(k);
  // Each cluster's sums in point order, as one += per point would give them; but a run of points
  // with the same label (most of them: EM's callers order the points spatially) adds into a
  // register, not through memory, whose store-to-load round trip per point was most of k-means'
  // own time. The same additions in the same order: the same bits.
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    const bool angle = c < 32 && ((mask >> c) & 1u);
    const double* xc = x.col(c).data();
    for (Eigen::Index p = 0; p < n;) {
      const int l = labels[p];
      const double center = (*centers)(c, l);
      double acc = shift(c, l);
      const Eigen::Index run_start = p;
      if (angle) {
        do {
          acc += Wrap(xc[p] - center);
          ++p;
        } while (p < n && labels[p] == l);
      } else {  // no call in this loop: acc stays in a register (with one, GCC kept it on the stack)
        do {
          acc += xc[p] - center;
          ++p;
        } while (p < n && labels[p] == l);
      }
      shift(c, l) = acc;
      if (c == 0) count[l] += static_cast<double>(p - run_start);  // integers: exact in any grouping
    }
  }
  std::vector<bool> taken(n, false);
  Eigen::MatrixXd previous = *centers;
  for (Eigen::Index c = 0; c < k; ++c) {
    if (count[c] > 0.0) {
      centers->col(c) += shift.col(c) / count[c];
    } else {
      // An empty cluster takes the point farthest from its center (deterministic).
      Eigen::Index far = 0;
      double far_d2 = -1.0;
      for (Eigen::Index p = 0; p < n; ++p)
        if (!taken[p] && best[p] > far_d2) { far_d2 = best[p]; far = p; }
      taken[far] = true;
      centers->col(c) = x.row(far).transpose();
    }
  }
  WrapAngleRows(mask, centers);
  Eigen::MatrixXd moved = *centers - previous;
  WrapAngleRows(mask, &moved);
  return moved.squaredNorm();
}

}  // namespace

Status KMeans(const Eigen::MatrixXd& points, uint32_t angle_mask, const KMeansOptions& options,
              std::mt19937_64* rng, KMeansResult* result) {
  std::string why;
  if (!options.IsValid(&why)) return Status::Error(StatusCode::kInvalidArgument, "k-means: " + why);
  if (points.rows() < options.k)
    return Status::Error(StatusCode::kNotEnoughData,
                         "k-means: " + std::to_string(points.rows()) + " points for " +
                             std::to_string(options.k) + " clusters");
  // scikit-learn's tolerance: 1e-4 of the mean per-dimension variance.
  const Eigen::RowVectorXd mean = points.colwise().mean();
  const double shift_tol = 1e-4 * (points.rowwise() - mean).array().square().colwise().mean().mean();
  result->inertia = std::numeric_limits<double>::infinity();
  Eigen::MatrixXd centers;
  Eigen::ArrayXi labels, previous;
  Eigen::ArrayXd best;
  for (int r = 0; r < options.restarts; ++r) {
    SeedPlusPlus(points, angle_mask, options.k, rng, &centers);
    double inertia = Assign(points, angle_mask, centers, &labels, &best);
    int it = 0;
    while (it < options.max_iterations) {
      ++it;
      previous = labels;
      const double shift = Update(points, angle_mask, labels, best, &centers);
      inertia = Assign(points, angle_mask, centers, &labels, &best);
      if ((labels == previous).all() || shift <= shift_tol) break;
    }
    if (inertia < result->inertia) {
      result->inertia = inertia;
      result->centers = centers;
      result->labels.assign(labels.data(), labels.data() + labels.size());
      result->iterations = it;
    }
  }
  return Status::Ok();
}

}  // namespace learn
}  // namespace gmmrrt
