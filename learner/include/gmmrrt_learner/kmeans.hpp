// kmeans.hpp - k-means++ seeding (greedy, 2 + ln K local trials, Arthur & Vassilvitskii 2007)
// and Lloyd iterations, with several restarts of which the lowest inertia is kept: it seeds EM,
// whose result depends on its start, so the best of several starts is kept. Angle dimensions use
// the wrapped difference, so a cluster across the theta = +-pi seam is one cluster.
#ifndef GMMRRT_LEARNER_KMEANS_HPP
#define GMMRRT_LEARNER_KMEANS_HPP

#include <Eigen/Dense>
#include <cstdint>
#include <random>
#include <vector>

#include "gmmrrt_learner/status.hpp"

namespace gmmrrt {
namespace learn {

struct KMeansOptions {
  int k = 1;                // clusters, >= 1, <= number of points
  int restarts = 4;         // independent seedings; the lowest final inertia is kept
  int max_iterations = 100; // Lloyd iterations per restart; a restart also stops when the
                            // squared center shift sums to <= 1e-4 x the mean data variance
                            // (scikit-learn's rule) or no label changes
  int threads = 1;          // threads for the seeding, assignment and update passes, >= 1; the
                            // result is the same bits for any value
  bool prune = true;        // skip the centers that box bounds rule out, and the groups of
                            // points that bounds carried across Lloyd passes rule out
                            // (kmeans.cpp); false computes every distance: the same bits (tests
                            // compare the two)
  bool IsValid(std::string* error) const;
};

struct KMeansResult {
  Eigen::MatrixXd centers;  // D x K; angle rows in (-pi, pi]
  std::vector<int> labels;  // N, cluster of each point
  double inertia = 0.0;     // sum of squared (wrapped) distances to the assigned centers
  int iterations = 0;       // Lloyd iterations of the kept restart
};

// Squared distances of every row of points (N x D) to center (D; angle dimensions wrapped)
// into *d2 (N).
void SquaredDistances(const Eigen::MatrixXd& points, const Eigen::VectorXd& center,
                      uint32_t angle_mask, Eigen::ArrayXd* d2);

// Clusters the ROWS of points (N x D, finite, angle columns in (-pi, pi]); rows keep each
// dimension contiguous so that distances vectorise. rng is advanced deterministically. Faster
// when consecutive points lie close together (FitMixture's spatial order for D = 2): the
// seeding and the assignment skip centers by the bounding boxes of 64 consecutive points, and
// the Lloyd passes skip such groups by distance bounds carried from pass to pass, without
// changing a bit of the result (kmeans.cpp). Allocates O(N) once per call.
// kInvalidArgument for bad options or K > N.
Status KMeans(const Eigen::MatrixXd& points, uint32_t angle_mask, const KMeansOptions& options,
              std::mt19937_64* rng, KMeansResult* result);

// How many numbers KMeans draws from rng: restarts x (1 + (k - 1) x (2 + floor(ln k))), one per
// k-means++ draw (the first centre, then each candidate centre); Lloyd draws none. A caller that
// runs several KMeans at once gives each a copy of rng advanced (discard) by this much per earlier
// one, and gets the same centres as from running them in order.
uint64_t KMeansRandomDraws(const KMeansOptions& options);

// Uniform double in [0, 1) from 53 random bits: the same on every platform, unlike
// std::uniform_real_distribution.
double Uniform01(std::mt19937_64* rng);

}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_KMEANS_HPP
