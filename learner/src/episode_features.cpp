// episode_features.cpp - episodes to (d, theta) or (s, x', y') feature points through
// features.h (paper Sect. 3), selection by task / homotopy / split. See episode_features.hpp.
#include "gmmrrt_learner/episode_features.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "gmmrrt/features.h"

namespace gmmrrt {
namespace learn {

const char* KindName(int kind) {
  switch (kind) {
    case GMMRRT_MODEL_KIND_FEATURES: return "features";
    case GMMRRT_MODEL_KIND_XY: return "xy";
    case GMMRRT_MODEL_KIND_GENERIC: return "generic";
    default: return "unknown";
  }
}

Status SelectEpisodes(const std::vector<Episode>& all, const EpisodeFilter& filter,
                      std::vector<const Episode*>* chosen) {
  chosen->clear();
  for (const Episode& e : all) {
    if (e.task != filter.task) continue;
    if (filter.homotopy != GMMRRT_HOMOTOPY_ALL && e.homotopy != filter.homotopy) continue;
    if (filter.split_by_episode) {
      auto it = filter.split_by_episode->find(e.id);
      if (it == filter.split_by_episode->end())
        return Status::Error(StatusCode::kBadInput, "episode '" + e.id + "' has no row in the index");
      if (it->second != filter.split) continue;
    }
    chosen->push_back(&e);
  }
  if (chosen->empty()) {
    std::string what = std::string("no episode of task ") + TaskName(filter.task) + ", homotopy " +
                       HomotopyName(filter.homotopy);
    if (filter.split_by_episode) what += ", split " + filter.split;
    return Status::Error(StatusCode::kNotEnoughData, what + " in the input (" + std::to_string(all.size()) +
                                                         " episodes read)");
  }
  return Status::Ok();
}

Status EpisodeFeatures(const std::vector<const Episode*>& episodes, int kind, Eigen::MatrixXd* points,
                       uint32_t* angle_mask) {
  if (kind != GMMRRT_MODEL_KIND_FEATURES && kind != GMMRRT_MODEL_KIND_XY)
    return Status::Error(StatusCode::kInvalidArgument, "episodes give features or xy points only");
  size_t n = 0;
  for (const Episode* e : episodes) n += e->samples.size();
  const int d = kind == GMMRRT_MODEL_KIND_FEATURES ? 2 : 3;
  points->resize(d, static_cast<Eigen::Index>(n));
  *angle_mask = kind == GMMRRT_MODEL_KIND_FEATURES ? (1u << 1) : 0u;
  Eigen::Index col = 0;
  for (const Episode* e : episodes) {
    const size_t m = e->samples.size();
    for (size_t i = 0; i < m; ++i) {
      const PoseSample& p = e->samples[i];
      if (!std::isfinite(p.robot_x) || !std::isfinite(p.robot_y) || !std::isfinite(p.person_x) ||
          !std::isfinite(p.person_y) || !std::isfinite(p.person_yaw))
        return Status::Error(StatusCode::kBadInput,
                             "episode '" + e->id + "' sample " + std::to_string(i) + " is not finite");
      const gmmrrt_pose_t person = {p.person_x, p.person_y, p.person_yaw};
      if (kind == GMMRRT_MODEL_KIND_FEATURES) {
        gmmrrt_features_from_xy(&person, p.robot_x, p.robot_y, &(*points)(0, col), &(*points)(1, col));
      } else {
        (*points)(0, col) = m > 1 ? static_cast<double>(i) / static_cast<double>(m - 1) : 0.0;
        gmmrrt_world_to_person(&person, p.robot_x, p.robot_y, &(*points)(1, col), &(*points)(2, col));
      }
      ++col;
    }
  }
  return Status::Ok();
}

void SortComponentsByProgress(Mixture* m) {
  std::vector<int> order(m->k());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [m](int a, int b) { return m->means(0, a) < m->means(0, b); });
  Mixture sorted = *m;
  for (int i = 0; i < m->k(); ++i) {
    sorted.weights[i] = m->weights[order[i]];
    sorted.means.col(i) = m->means.col(order[i]);
    sorted.chol[i] = m->chol[order[i]];
  }
  *m = std::move(sorted);
}

}  // namespace learn
}  // namespace gmmrrt
