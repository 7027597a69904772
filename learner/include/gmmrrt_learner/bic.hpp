// bic.hpp - choosing K by the Bayesian information criterion (Schwarz 1978): fit K = A..B with
// the same options and seed, keep the K of lowest BIC = -2 ln L + p ln N. The paper chose
// k = 19 by hand (Sect. 5.1); `gmmrrt-learn fit --k auto` runs this sweep and prints the table.
#ifndef GMMRRT_LEARNER_BIC_HPP
#define GMMRRT_LEARNER_BIC_HPP

#include <Eigen/Dense>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gmmrrt_learner/em.hpp"
#include "gmmrrt_learner/mixture.hpp"
#include "gmmrrt_learner/status.hpp"

namespace gmmrrt {
namespace learn {

struct BicRow {
  int k = 0;                       // requested K
  int k_final = 0;                 // after dropped components
  double mean_log_likelihood = 0;  // per point
  double bic = 0;
  int iterations = 0;
  bool converged = false;
  int fresh_starts = 0;     // k-means++ candidates screened
  int split_starts = 0;     // split starts of the K - 1 fit screened
};

struct BicSweepResult {
  std::vector<BicRow> rows;
  int best_k = 0;        // requested K of the lowest BIC
  Mixture best;          // its mixture
  FitSummary best_summary;
  std::string note;      // why the sweep stopped early, if it did
};

// Default of SweepBic's stop_after_rises: the sweep ends once this many consecutive K have a
// BIC above the lowest so far. Past the generating K, each extra component costs
// (1 + D + D(D+1)/2) ln N in BIC and gains little likelihood, so BIC climbs steadily; three K in a
// row above the minimum is that climb, not noise from a local optimum. It makes a sweep over
// 1..30 of data with K = 6 fit K = 1..9 instead of thirty mixtures.
constexpr int kBicStopAfterRises = 3;

// Default of SweepBic's split_starts: how many split moves of the K - 1 fit join the k-means++
// candidates of K (split_components.hpp). Each costs screen_iterations EM steps on the
// screening sample. Evidence for the value: docs/learner.md, "BIC sweep".
constexpr int kBicSplitStarts = 4;

// Default of SweepBic's fresh_starts: the k-means++ candidates of each K that also has split
// starts of the K - 1 fit (options.restarts stays the count at K = k_min and whenever there are
// no split starts). The splits start next to a converged K - 1 optimum; the fresh candidates
// only guard against a basin the chain of splits carries along, and two do that as well as
// eight on the benchmark's mixtures (same K and BIC on all six generating-K cases, seeds 1-4)
// for about half the sweep's CPU time. Evidence and its cost on real trajectories:
// docs/learner.md, "BIC sweep".
constexpr int kBicFreshStarts = 2;

// Fits K = k_min..k_max (1 <= k_min <= k_max <= GMMRRT_MAX_K; options.k is ignored), in order,
// and stops early once stop_after_rises consecutive K have a BIC above the lowest so far
// (0: fit the whole range); note says where and why. A K with too few points for it ends the
// sweep early (note says so) unless it is k_min, which is an error. Other fit errors are
// returned as they are. on_row (may be empty) is called after each K. Each K > k_min screens,
// beside options.restarts k-means++ starts, up to split_starts splits of the K - 1 fit (0:
// fresh starts only): the sweep is then only as good as the best of both, not of EM's luck.
// A K that has split starts screens min(options.restarts, fresh_starts) k-means++ candidates,
// any other K options.restarts (fresh_starts >= 1, else kInvalidArgument); each row says what
// it screened.
Status SweepBic(const Eigen::MatrixXd& points, uint32_t angle_mask, const FitOptions& options,
                int k_min, int k_max, BicSweepResult* result,
                const std::function<void(const BicRow&)>& on_row = nullptr,
                int stop_after_rises = kBicStopAfterRises, int split_starts = kBicSplitStarts,
                int fresh_starts = kBicFreshStarts);

// The rows as a fixed-width text table (header, one line per K, the chosen K marked with *).
std::string FormatBicTable(const BicSweepResult& result);

}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_BIC_HPP
