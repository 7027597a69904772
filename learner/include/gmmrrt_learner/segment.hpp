// segment.hpp - cut continuous recordings (ROBOT_POSE and PEOPLE, no DEMO_INFO) into labelled
// demonstration episodes: the robot passing or approaching a person who stands still (paper
// Sect. 2 tasks, Sect. 5.1 demonstrations), so that a team learns from its own teleoperation
// logs without labelling them by hand. `gmmrrt-learn segment` writes the result as an episode
// CSV that `gmmrrt-learn fit` reads.
//
// Rules (defaults in SegmentOptions; docs/learner.md, "Raw recordings in"):
//  1. A person stands still while their speed, measured over speed_window_s, stays below
//     still_speed_mps, for at least min_still_s; the standing position is the median of the
//     track over that span and the facing its circular mean.
//  2. An encounter is a maximal stretch of ROBOT_POSE samples within radius_m of a standing
//     person while they stand, at least 3 samples, with at least min_path_m of robot travel.
//  3. Task: approach when the robot ends the encounter within approach_stop_m of the person,
//     stopped (speed over its last speed_window_s below still_speed_mps), without having gone
//     round them (|swept angle| < approach_max_swept_rad); otherwise avoid, and an avoid
//     encounter must go round the person, |swept angle| >= min_swept_rad
//     (gmmrrt_path_swept_angle), else it is a note ("not a pass") and left out.
//  4. Homotopy from the geometry (gmmrrt/path_side.h): avoid, the side passed
//     (gmmrrt_path_passing_side over the encounter); approach, frontal when the robot starts in
//     the person's front half-plane (|theta| < pi/2, gmmrrt_features_from_xy), else the side of
//     its last point.
#ifndef GMMRRT_LEARNER_SEGMENT_HPP
#define GMMRRT_LEARNER_SEGMENT_HPP

#include <cstdint>
#include <string>
#include <vector>

#include "gmmrrt_learner/demo_io.hpp"

namespace gmmrrt {
namespace learn {

struct SegmentOptions {
    double still_speed_mps = 0.3;  // a tracked standing person jitters by a few cm per sample
    double speed_window_s = 1.0;
    double min_still_s = 2.0;
    double radius_m = 3.0;  // UPO's avoid episodes start and end about 2.1-2.5 m from the person
    double min_path_m = 0.5;
    double approach_stop_m = 1.5;
    double approach_max_swept_rad = 1.5707963267948966;  // pi/2: ends near them without going round
    double min_swept_rad = 0.7853981633974483;  // pi/4: UPO passes start and end ~2 m out, 0.8-1.6 rad
};

struct SegmentedEpisode {
    Episode episode;  // id "<file stem>_seg<NNNN>", t_s from the encounter's start, robot_yaw NaN
    int32_t person_id;
};

// The episodes of one recording in time order (then by person id), and notes naming the file,
// the person and the time: a person who never stands still, an encounter that is not a pass.
struct SegmentResult {
    std::vector<SegmentedEpisode> episodes;
    std::vector<std::string> notes;
};

// Segments an already read recording; `path` names it in ids and notes.
SegmentResult SegmentRecording(const Recording& rec, const std::string& path, const SegmentOptions& options);

}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_SEGMENT_HPP
