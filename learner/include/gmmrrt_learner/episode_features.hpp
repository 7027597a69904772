// episode_features.hpp - demonstrations (demo_io.hpp episodes) to the feature points a mixture
// is fitted on (paper Sect. 3), through the one C definition of the features (features.h):
//   kind features (D = 2): (d [m], theta [rad, wrapped angle]) of the robot in the person's frame;
//   kind xy       (D = 3): (s, x' [m], y' [m]) with s = sample index / (n - 1) in [0, 1], the
//                  normalised progress along the episode (index, not arc length: the samples are
//                  evenly timed, so s is normalised time), and (x', y') the robot in the person's
//                  frame. The GMM-RRT baseline samples its components in order of mean s.
// Also the selection of episodes by task, homotopy and index split.
#ifndef GMMRRT_LEARNER_EPISODE_FEATURES_HPP
#define GMMRRT_LEARNER_EPISODE_FEATURES_HPP

#include <Eigen/Dense>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "gmmrrt/model.h"
#include "gmmrrt_learner/demo_io.hpp"
#include "gmmrrt_learner/labels.hpp"
#include "gmmrrt_learner/mixture.hpp"
#include "gmmrrt_learner/status.hpp"

namespace gmmrrt {
namespace learn {

// ParseTask, ParseHomotopy, TaskName and HomotopyName: labels.hpp.
const char* KindName(int kind);          // "features", "xy", "generic" or "unknown"

struct EpisodeFilter {
  int task = GMMRRT_TASK_AVOID;           // episodes of this task only
  int homotopy = GMMRRT_HOMOTOPY_ALL;     // ALL keeps every homotopy
  // When non-null, only episodes whose split (from the index) equals `split`; an episode with
  // no index row is an error. Not owned.
  const std::map<std::string, std::string>* split_by_episode = nullptr;
  std::string split;
};

// Pointers into `all` (which must outlive them) of the episodes that pass the filter.
// kBadInput when an episode is missing from the index; kNotEnoughData when none pass.
Status SelectEpisodes(const std::vector<Episode>& all, const EpisodeFilter& filter,
                      std::vector<const Episode*>* chosen);

// Feature points (D x N, N = all samples of the episodes) of kind GMMRRT_MODEL_KIND_FEATURES
// or GMMRRT_MODEL_KIND_XY, and their angle mask (bit 1 for theta; none for xy).
// kBadInput for a non-finite sample (naming episode and sample), kInvalidArgument for another kind.
Status EpisodeFeatures(const std::vector<const Episode*>& episodes, int kind, Eigen::MatrixXd* points,
                       uint32_t* angle_mask);

// Sorts the components of an xy mixture by mean s (row 0), ascending; ties keep their order.
void SortComponentsByProgress(Mixture* m);

}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_EPISODE_FEATURES_HPP
