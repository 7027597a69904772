// background.hpp - the data of a task model's background (model.h, "background section"):
// where the demonstrators would have been had they not reacted to the person.
//
// Each episode is replaced by the straight line from its first to its last robot position,
// sampled at as many evenly spaced points as the episode has (the same weight per episode as
// the task model's data), with the same person. The line is the path of least effort between
// the same endpoints, the one a walker takes past someone they ignore; its features relative
// to the person are therefore the density of "being there anyway". The background cost
// (config.h GMMRRT_TASK_COST_BACKGROUND) charges a point by how much more the background than
// the demonstrations goes there, so the cost bends a path only where the demonstrations bent
// theirs (docs/planner.md, "The background cost").
#ifndef GMMRRT_LEARNER_BACKGROUND_HPP
#define GMMRRT_LEARNER_BACKGROUND_HPP

#include <vector>

#include "gmmrrt_learner/demo_io.hpp"

namespace gmmrrt {
namespace learn {

// The straight-line twin of each episode, in order: same id, task, homotopy, times and person;
// robot sample i at start + i / (n - 1) (end - start) with the segment's heading (NaN for an
// episode whose ends coincide); an episode of one sample stays at its start.
std::vector<Episode> StraightLineEpisodes(const std::vector<const Episode*>& episodes);

}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_BACKGROUND_HPP
