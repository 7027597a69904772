// segment.cpp - continuous recordings -> labelled episodes; the rules are in segment.hpp.
#include "gmmrrt_learner/segment.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <tuple>
#include <utility>

#include "gmmrrt/features.h"
#include "gmmrrt/model.h"
#include "gmmrrt/path_side.h"

namespace gmmrrt {
namespace learn {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Speed [m/s] at each sample over the preceding window: from the first sample at most window_s
// earlier; when that is less than half a window back (the start of a track), over the following
// window instead. 0 where no time passes.
template <typename Sample>
std::vector<double> Speeds(const std::vector<Sample>& track, double window_s) {
    const size_t n = track.size();
    std::vector<double> speed(n, 0.0);
    for (size_t i = 0; i < n; ++i) {
        const double t = track[i].t_s;
        size_t j = static_cast<size_t>(
            std::lower_bound(track.begin(), track.end(), t - window_s,
                             [](const Sample& s, double v) { return s.t_s < v; }) - track.begin());
        j = std::min(j, i);
        if (t - track[j].t_s < 0.5 * window_s) {
            j = static_cast<size_t>(
                std::lower_bound(track.begin(), track.end(), t + window_s,
                                 [](const Sample& s, double v) { return s.t_s < v; }) - track.begin());
            j = std::min(j, n - 1);
        }
        const double dt = std::fabs(t - track[j].t_s);
        const double dist = std::hypot(track[i].x - track[j].x, track[i].y - track[j].y);
        speed[i] = dt > 0 ? dist / dt : 0.0;
    }
    return speed;
}

// [start, end) index ranges where mask holds.
std::vector<std::pair<size_t, size_t>> Runs(const std::vector<bool>& mask) {
    std::vector<std::pair<size_t, size_t>> out;
    size_t start = 0;
    bool open = false;
    for (size_t i = 0; i < mask.size(); ++i) {
        if (mask[i] && !open) {
            start = i;
            open = true;
        } else if (!mask[i] && open) {
            out.emplace_back(start, i);
            open = false;
        }
    }
    if (open)
        out.emplace_back(start, mask.size());
    return out;
}

// numpy's median: the middle value, or the mean of the two middle values.
double Median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

std::string Stem(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
    return base.substr(0, base.find('.'));
}

std::string Format(const char* fmt, double a, double b, double c) {
    char buf[160];
    std::snprintf(buf, sizeof buf, fmt, a, b, c);
    return buf;
}

}  // namespace

SegmentResult SegmentRecording(const Recording& rec, const std::string& path, const SegmentOptions& o) {
    SegmentResult res;
    const std::vector<double> robot_speed = Speeds(rec.robot, o.speed_window_s);
    struct Found {
        double t0;
        int32_t person_id;
        SegmentedEpisode ep;
    };
    std::vector<Found> found;
    for (const auto& entry : rec.people) {  // std::map: by person id
        const int32_t pid = entry.first;
        const std::vector<PersonSample>& track = entry.second;
        const std::vector<double> speed = Speeds(track, o.speed_window_s);
        std::vector<bool> still(track.size());
        for (size_t i = 0; i < track.size(); ++i)
            still[i] = speed[i] < o.still_speed_mps;
        std::vector<std::pair<size_t, size_t>> spans;
        for (const auto& r : Runs(still))
            if (track[r.second - 1].t_s - track[r.first].t_s >= o.min_still_s)
                spans.push_back(r);
        if (spans.empty()) {
            res.notes.push_back(path + ": person " + std::to_string(pid) +
                                Format(" never stands still for %g s (speed < %g m/s): no episode around them",
                                       o.min_still_s, o.still_speed_mps, 0.0));
            continue;
        }
        for (const auto& span : spans) {
            std::vector<double> xs, ys;
            double sin_sum = 0.0, cos_sum = 0.0;
            for (size_t i = span.first; i < span.second; ++i) {
                xs.push_back(track[i].x);
                ys.push_back(track[i].y);
                sin_sum += std::sin(track[i].yaw);
                cos_sum += std::cos(track[i].yaw);
            }
            const double n = static_cast<double>(xs.size());
            const gmmrrt_pose_t person = {Median(xs), Median(ys), std::atan2(sin_sum / n, cos_sum / n)};
            const double t_lo = track[span.first].t_s, t_hi = track[span.second - 1].t_s;
            std::vector<bool> inside(rec.robot.size());
            for (size_t i = 0; i < rec.robot.size(); ++i) {
                const RobotSample& r = rec.robot[i];
                inside[i] = r.t_s >= t_lo && r.t_s <= t_hi && std::hypot(r.x - person.x, r.y - person.y) < o.radius_m;
            }
            for (const auto& run : Runs(inside)) {
                const size_t r0 = run.first, r1 = run.second;
                if (r1 - r0 < 3)
                    continue;
                std::vector<double> xy;
                double travel = 0.0;
                for (size_t i = r0; i < r1; ++i) {
                    xy.push_back(rec.robot[i].x);
                    xy.push_back(rec.robot[i].y);
                    if (i > r0)
                        travel += std::hypot(rec.robot[i].x - rec.robot[i - 1].x, rec.robot[i].y - rec.robot[i - 1].y);
                }
                if (travel < o.min_path_m)
                    continue;
                const size_t count = r1 - r0;
                const RobotSample& first = rec.robot[r0];
                const RobotSample& last = rec.robot[r1 - 1];
                const double end_d = std::hypot(last.x - person.x, last.y - person.y);
                const double swept = gmmrrt_path_swept_angle(&person, xy.data(), count);
                int task, homotopy;
                if (end_d < o.approach_stop_m && robot_speed[r1 - 1] < o.still_speed_mps &&
                    std::fabs(swept) < o.approach_max_swept_rad) {
                    task = GMMRRT_TASK_APPROACH;
                    double d0, th0;
                    gmmrrt_features_from_xy(&person, first.x, first.y, &d0, &th0);
                    homotopy = std::fabs(th0) < kPi / 2
                                   ? GMMRRT_HOMOTOPY_FRONTAL
                                   : (gmmrrt_path_passing_side(&person, &xy[2 * (count - 1)], 1) > 0
                                          ? GMMRRT_HOMOTOPY_LEFT
                                          : GMMRRT_HOMOTOPY_RIGHT);
                } else {
                    if (std::fabs(swept) < o.min_swept_rad) {
                        res.notes.push_back(path + ": person " + std::to_string(pid) +
                                            Format(", t = %.1f..%.1f s: not a pass (swept angle %.2f rad): left out",
                                                   first.t_s, last.t_s, swept));
                        continue;
                    }
                    task = GMMRRT_TASK_AVOID;
                    homotopy = gmmrrt_path_passing_side(&person, xy.data(), count) > 0 ? GMMRRT_HOMOTOPY_LEFT
                                                                                       : GMMRRT_HOMOTOPY_RIGHT;
                }
                Found f;
                f.t0 = first.t_s;
                f.person_id = pid;
                f.ep.person_id = pid;
                f.ep.episode.task = task;
                f.ep.episode.homotopy = homotopy;
                for (size_t i = r0; i < r1; ++i) {
                    const RobotSample& r = rec.robot[i];
                    f.ep.episode.samples.push_back({r.t_s - first.t_s, r.x, r.y,
                                                    std::numeric_limits<double>::quiet_NaN(), person.x, person.y,
                                                    person.yaw});
                }
                found.push_back(std::move(f));
            }
        }
    }
    std::stable_sort(found.begin(), found.end(), [](const Found& a, const Found& b) {
        return std::tie(a.t0, a.person_id) < std::tie(b.t0, b.person_id);
    });
    const std::string stem = Stem(path);
    for (size_t n = 0; n < found.size(); ++n) {
        char num[24];
        std::snprintf(num, sizeof num, "%04zu", n);
        found[n].ep.episode.id = stem + "_seg" + num;
        res.episodes.push_back(std::move(found[n].ep));
    }
    return res;
}

}  // namespace learn
}  // namespace gmmrrt
