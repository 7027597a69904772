/*
 * problem.hpp - the benchmark problem both planners solve, in one place:
 * [-10,10]^2, a disc of radius 2 at the origin, start (-5,0), goal (5,0), a point robot.
 *
 * Objective "length": path length. Objective "task": the paper's edge cost (Sect. 4),
 * the integral over the path of w_length + w_task c(f(x)), c(f) = delta / max(p(f), delta),
 * with f = (d, theta) of x relative to a person standing on the disc, facing the start
 * (yaw pi): the disc is then that person (person_radius_m = 2 in our planner).
 */
#ifndef GMMRRT_BENCH_PROBLEM_HPP
#define GMMRRT_BENCH_PROBLEM_HPP

#include <cmath>
#include <cstdint>
#include <string>

#include "gmmrrt/features.h"
#include "gmmrrt/model.h"

namespace gmmrrt_bench {

constexpr double kBoundLo = -10.0, kBoundHi = 10.0; /* m */
constexpr double kDiscRadius = 2.0;                 /* m, centred at the origin */
constexpr double kStartX = -5.0, kStartY = 0.0;     /* m */
constexpr double kGoalX = 5.0, kGoalY = 0.0;        /* m */
/* Both planners must reach the goal state itself (OMPL's GoalState default threshold is
 * machine epsilon; ours needs > 0): 1e-6 m is "exactly" for both. */
constexpr double kGoalTolerance = 1e-6;
/* Optimal path length around the disc: 2 sqrt(5^2 - 2^2) + 2 (pi - 2 acos(2/5)) = 10.8112 m. */

/* OMPL RRTstar's defaults on this space, reproduced in our configuration so both search
 * alike: range = 0.2 x max extent, goal bias 0.05, motion-check resolution = 0.01 x max
 * extent, rewiring radius constant r_rrg = 1.1 * 2 (1 + 1/2)^(1/2) (400 / pi)^(1/2). */
inline double max_extent() { return std::sqrt(2.0) * (kBoundHi - kBoundLo); }
inline double ompl_default_range() { return 0.2 * max_extent(); }
constexpr double kOmplGoalBias = 0.05;
inline double ompl_default_resolution() { return 0.01 * max_extent(); }
inline double ompl_rewire_gamma()
{
    const double measure = (kBoundHi - kBoundLo) * (kBoundHi - kBoundLo);
    return 1.1 * 2.0 * std::sqrt(1.5) * std::sqrt(measure / M_PI);
}

/* The task objective's settings (identical in both planners). */
struct TaskSettings {
    const gmmrrt_model_t *model = nullptr; /* FEATURES model (d, theta) */
    gmmrrt_pose_t person{0.0, 0.0, M_PI};  /* on the disc, facing the start */
    double delta = GMMRRT_MODEL_DEFAULT_DELTA;
    double w_length = 1.0;
    double w_task = 1.0;
};

/* Reads and validates a model file into *out; false with a message in *err. */
bool load_model_file(const std::string &path, gmmrrt_model_t *out, std::string *err);

} // namespace gmmrrt_bench

#endif
