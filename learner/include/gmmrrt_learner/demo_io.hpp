// demo_io.hpp - readers of recorded demonstrations for the learner (paper Sect. 2 and 5.1: the
// models are learned from demonstrations of each task and homotopy).
//
// Two inputs give the same Episode list:
//  - a demonstration log: an LCM event log (as lcm-logger writes it) with channels
//    DEMO_INFO (gmmrrt demo_info_t, starts an episode), ROBOT_POSE (pose2d_t) and
//    PEOPLE (people_t); layout and pairing rule in docs/demonstrations.md;
//  - an episode CSV as in ../shared/data/real/README.md
//    (episode_id,task,homotopy,t,robot_x,robot_y,person_x,person_y,person_yaw).
//
// Errors are returned, never thrown: ReadResult.ok = false with a message naming the
// file and the event number (logs) or line number (CSV). Events that are bad on their
// own (undecodable payload, NaN/Inf, time going backwards) are skipped and each skip is
// recorded in ReadResult.warnings; a log whose structure is broken (bytes that are not an
// event, missing channel) is an error. A log whose last event is cut short (a recorder killed
// mid-write) is read up to its last complete event, with a warning naming the file and event.
#ifndef GMMRRT_LEARNER_DEMO_IO_HPP
#define GMMRRT_LEARNER_DEMO_IO_HPP

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace gmmrrt {
namespace learn {

// One sample of an episode. Positions in metres (world frame of the recording), angles in
// radians, t_s in seconds from the episode's start.
// robot_yaw: from ROBOT_POSE in a log; estimated from the motion in a CSV (the real CSVs
// have no robot heading, see EstimateHeadingsFromMotion), NaN when it cannot be estimated.
struct PoseSample {
    double t_s, robot_x, robot_y, robot_yaw, person_x, person_y, person_yaw;
};

// One demonstration. task: gmmrrt_task_t values, homotopy: gmmrrt_homotopy_t values
// (planner/include/gmmrrt/model.h; equal to demo_info_t's constants on the wire).
// id: the CSV's episode_id; for a log "<file stem>_<episode number, 4 digits>".
struct Episode {
    std::string id;
    int task;
    int homotopy;
    std::vector<PoseSample> samples;
};

struct ReadResult {
    bool ok = true;
    std::string error;                  // set when !ok: names the file and event / line
    std::vector<std::string> warnings;  // skipped events / rows, each naming file and place
};

// Largest |robot pose utime - person utime| [s] for pairing a ROBOT_POSE with the latest
// PEOPLE entry of the episode's person; poses without such a partner are skipped. Generous
// because the demonstrated person stands and a people_t message is 1.7 kB (small logs publish
// PEOPLE every few seconds); see docs/demonstrations.md.
constexpr double kMaxPersonAgeS = 5.0;

// Largest number of warnings kept; the last one then says how many more were dropped.
constexpr size_t kMaxWarnings = 100;

// Reads an episode CSV. On success appends the episodes, in file order, to *out; on
// failure leaves *out unchanged. Rows of one episode must be contiguous, with one
// task and homotopy and strictly increasing t. Errors: cannot open, bad header, wrong
// column count, a number that does not parse or is not finite, unknown task or
// homotopy string, time not increasing, a repeated episode.
ReadResult ReadEpisodeCsv(const std::string& path, std::vector<Episode>* out);

// Reads a demonstration log. On success appends its episodes (those with at least one
// sample, in log order) to *out; on failure leaves *out unchanged. Errors: cannot open,
// not an LCM log, corrupted event structure, no DEMO_INFO / ROBOT_POSE / PEOPLE event at
// all, no episode with samples (these name the cut too when the log was cut short). A cut
// last event is a warning, not an error.
ReadResult ReadDemoLog(const std::string& path, std::vector<Episode>* out);

// Writes episodes as an episode CSV (the format ReadEpisodeCsv reads; robot_yaw is not part of
// it and is dropped; numbers with 17 significant digits, so they read back exactly). The file
// appears whole or not at all (a temporary file beside it, synced, renamed). Errors: no
// episodes, an id that is empty or holds a comma, a task / homotopy without a CSV label
// (homotopy "all"), a non-finite number, a file that cannot be written.
ReadResult WriteEpisodeCsv(const std::string& path, const std::vector<Episode>& episodes);

// A continuous recording (no DEMO_INFO needed: what the segmenter cuts into episodes). Times in
// seconds from the first valid ROBOT_POSE or PEOPLE message's utime.
struct RobotSample {
    double t_s, x, y;
};
struct PersonSample {
    double t_s, x, y, yaw;  // PEOPLE's message utime, the person's position and facing
};
struct Recording {
    std::vector<RobotSample> robot;                       // ROBOT_POSE, utime strictly increasing
    std::map<int32_t, std::vector<PersonSample>> people;  // by person id, PEOPLE order
};

// Reads a continuous recording with the same framing checks and validating decoders as
// ReadDemoLog. On success replaces *out; on failure leaves it unchanged. Errors: cannot open,
// not a regular file, not an LCM log, corrupted event structure, no ROBOT_POSE, no PEOPLE with
// a person. Warnings: invalid messages, time not advancing, a cut last event.
ReadResult ReadRecording(const std::string& path, Recording* out);

// Either of the above, chosen by content: the LCM log sync word 0xEDA1DA01 at the start
// means a log, anything else is read as an episode CSV.
ReadResult ReadEpisodes(const std::string& path, std::vector<Episode>* out);

// Reads an index CSV with (at least) the columns episode_id and split (e.g.
// ../shared/data/real/upo_avoid_index.csv) into *split_by_episode (replaced on success,
// unchanged on failure). Errors: missing column, wrong column count, empty id or split,
// an id listed twice.
ReadResult ReadSplitIndex(const std::string& path, std::map<std::string, std::string>* split_by_episode);

// Fills robot_yaw of each sample from the direction of motion (central difference of
// neighbouring positions that are at least min_step_m apart; the ends use one-sided
// differences). Samples where the robot never moved get NaN.
void EstimateHeadingsFromMotion(std::vector<PoseSample>* samples, double min_step_m = 0.01);

}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_DEMO_IO_HPP
