// kmeans.cpp - greedy k-means++ seeding and Lloyd iterations with restarts, seam-safe for angle
// dimensions (the update moves a center by the mean wrapped difference, then wraps it).
// Seeds EM (em.cpp); see kmeans.hpp.
#include "gmmrrt_learner/kmeans.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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

double Uniform01(std::mt19937_64* rng) {
  return static_cast<double>((*rng)() >> 11) * (1.0 / 9007199254740992.0);
}

void SquaredDistances(const Eigen::MatrixXd& points, const Eigen::VectorXd& center,
                      uint32_t angle_mask, Eigen::VectorXd* d2) {
  Eigen::MatrixXd diff = points.colwise() - center;
  WrapAngleRows(angle_mask, &diff);
  *d2 = diff.colwise().squaredNorm().transpose();
}

namespace {

// Index drawn with probability proportional to weight (cumulative sums in cum, total > 0).
Eigen::Index DrawProportional(const Eigen::VectorXd& cum, std::mt19937_64* rng) {
  const double u = Uniform01(rng) * cum[cum.size() - 1];
  const double* first = cum.data();
  const double* it = std::upper_bound(first, first + cum.size(), u);
  return std::min<Eigen::Index>(it - first, cum.size() - 1);
}

void SeedPlusPlus(const Eigen::MatrixXd& x, uint32_t mask, int k, std::mt19937_64* rng,
                  Eigen::MatrixXd* centers) {
  const Eigen::Index n = x.cols();
  centers->resize(x.rows(), k);
  const Eigen::Index first = std::min<Eigen::Index>(
      static_cast<Eigen::Index>(Uniform01(rng) * static_cast<double>(n)), n - 1);
  centers->col(0) = x.col(first);
  Eigen::VectorXd closest, d2, best_d2, cum(n);
  SquaredDistances(x, centers->col(0), mask, &closest);
  const int trials = 2 + static_cast<int>(std::log(static_cast<double>(k)));
  for (int c = 1; c < k; ++c) {
    std::partial_sum(closest.data(), closest.data() + n, cum.data());
    double best_potential = std::numeric_limits<double>::infinity();
    Eigen::Index best = 0;
    for (int t = 0; t < trials; ++t) {
      const Eigen::Index cand =
          cum[n - 1] > 0.0 ? DrawProportional(cum, rng)
                           : std::min<Eigen::Index>(
                                 static_cast<Eigen::Index>(Uniform01(rng) * static_cast<double>(n)), n - 1);
      SquaredDistances(x, x.col(cand), mask, &d2);
      const double potential = closest.cwiseMin(d2).sum();
      if (potential < best_potential) {
        best_potential = potential;
        best = cand;
        best_d2 = d2;
      }
    }
    centers->col(c) = x.col(best);
    closest = closest.cwiseMin(best_d2);
  }
}

// Assigns every point to its nearest center; returns the inertia.
double Assign(const Eigen::MatrixXd& x, uint32_t mask, const Eigen::MatrixXd& centers,
              std::vector<int>* labels, Eigen::VectorXd* best) {
  const Eigen::Index n = x.cols();
  best->setConstant(n, std::numeric_limits<double>::infinity());
  labels->assign(n, 0);
  Eigen::VectorXd d2;
  for (Eigen::Index c = 0; c < centers.cols(); ++c) {
    SquaredDistances(x, centers.col(c), mask, &d2);
    for (Eigen::Index p = 0; p < n; ++p) {
      if (d2[p] < (*best)[p]) {
        (*best)[p] = d2[p];
        (*labels)[p] = static_cast<int>(c);
      }
    }
  }
  return best->sum();
}

void Update(const Eigen::MatrixXd& x, uint32_t mask, const std::vector<int>& labels,
            const Eigen::VectorXd& best, Eigen::MatrixXd* centers) {
  const Eigen::Index k = centers->cols();
  Eigen::MatrixXd shift = Eigen::MatrixXd::Zero(x.rows(), k);
  Eigen::VectorXd count = Eigen::VectorXd::Zero(k);
  Eigen::VectorXd diff(x.rows());
  for (Eigen::Index p = 0; p < x.cols(); ++p) {
    const int c = labels[p];
    diff = x.col(p) - centers->col(c);
    for (Eigen::Index j = 0; j < x.rows(); ++j)
      if ((mask >> j) & 1u) diff[j] = gmmrrt_wrap_angle(diff[j]);
    shift.col(c) += diff;
    count[c] += 1.0;
  }
  std::vector<bool> taken(x.cols(), false);
  for (Eigen::Index c = 0; c < k; ++c) {
    if (count[c] > 0.0) {
      centers->col(c) += shift.col(c) / count[c];
    } else {
      // An empty cluster takes the point farthest from its center (deterministic).
      Eigen::Index far = 0;
      double far_d2 = -1.0;
      for (Eigen::Index p = 0; p < x.cols(); ++p)
        if (!taken[p] && best[p] > far_d2) { far_d2 = best[p]; far = p; }
      taken[far] = true;
      centers->col(c) = x.col(far);
    }
  }
  Eigen::MatrixXd wrapped = *centers;
  WrapAngleRows(mask, &wrapped);
  *centers = wrapped;
}

}  // namespace

Status KMeans(const Eigen::MatrixXd& points, uint32_t angle_mask, const KMeansOptions& options,
              std::mt19937_64* rng, KMeansResult* result) {
  std::string why;
  if (!options.IsValid(&why)) return Status::Error(StatusCode::kInvalidArgument, "k-means: " + why);
  if (points.cols() < options.k)
    return Status::Error(StatusCode::kNotEnoughData,
                         "k-means: " + std::to_string(points.cols()) + " points for " +
                             std::to_string(options.k) + " clusters");
  result->inertia = std::numeric_limits<double>::infinity();
  Eigen::MatrixXd centers;
  std::vector<int> labels;
  Eigen::VectorXd best;
  for (int r = 0; r < options.restarts; ++r) {
    SeedPlusPlus(points, angle_mask, options.k, rng, &centers);
    double inertia = Assign(points, angle_mask, centers, &labels, &best);
    int it = 0;
    while (it < options.max_iterations) {
      ++it;
      const std::vector<int> previous = labels;
      Update(points, angle_mask, labels, best, &centers);
      inertia = Assign(points, angle_mask, centers, &labels, &best);
      if (labels == previous) break;
    }
    if (inertia < result->inertia) {
      result->inertia = inertia;
      result->centers = centers;
      result->labels = labels;
      result->iterations = it;
    }
  }
  return Status::Ok();
}

}  // namespace learn
}  // namespace gmmrrt
