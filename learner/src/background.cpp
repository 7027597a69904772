// background.cpp - straight-line twins of demonstrations, the data of the background model
// (background.hpp).
#include "gmmrrt_learner/background.hpp"

#include <cmath>
#include <limits>

namespace gmmrrt {
namespace learn {

std::vector<Episode> StraightLineEpisodes(const std::vector<const Episode*>& episodes) {
  std::vector<Episode> out;
  out.reserve(episodes.size());
  for (const Episode* e : episodes) {
    Episode line = *e;
    const size_t n = line.samples.size();
    if (n > 0) {
      const PoseSample& a = e->samples.front();
      const PoseSample& b = e->samples.back();
      const double dx = b.robot_x - a.robot_x, dy = b.robot_y - a.robot_y;
      const double yaw = (dx != 0.0 || dy != 0.0) ? std::atan2(dy, dx) : std::numeric_limits<double>::quiet_NaN();
      for (size_t i = 0; i < n; ++i) {
        const double u = n > 1 ? static_cast<double>(i) / static_cast<double>(n - 1) : 0.0;
        line.samples[i].robot_x = a.robot_x + u * dx;
        line.samples[i].robot_y = a.robot_y + u * dy;
        line.samples[i].robot_yaw = yaw;
      }
    }
    out.push_back(std::move(line));
  }
  return out;
}

}  // namespace learn
}  // namespace gmmrrt
