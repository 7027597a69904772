/*
 * gmmrrt_runner.hpp - the benchmark problem (problem.hpp) solved by our planner through
 * planner.h, configured like OMPL's RRTstar defaults (problem.hpp) so that both planners
 * search alike: uniform sampling, same range, goal bias, motion-check resolution and
 * rewiring constant.
 */
#ifndef GMMRRT_BENCH_GMMRRT_RUNNER_HPP
#define GMMRRT_BENCH_GMMRRT_RUNNER_HPP

#include <cstdint>
#include <string>
#include <vector>

#include "gmmrrt/config.h"
#include "gmmrrt/planner.h"
#include "problem.hpp"
#include "trial.hpp"

namespace gmmrrt_bench {

/* The configuration used for `objective` ("length": plain RRT*; "task": GMM-RRT* with
 * gmm_bias 0, so it samples uniformly like OMPL and differs only by the cost). */
gmmrrt_planner_config_t gmmrrt_bench_config(const std::string &objective, const TaskSettings *task,
                                            int32_t max_nodes, uint64_t seed);

/* The problem for `objective`: a circle obstacle ("length") or a person ("task"). */
gmmrrt_problem_t gmmrrt_bench_problem(const std::string &objective, const TaskSettings *task);

/* One timed run for time_ms, the planner block allocated before timing starts. The run is
 * cut into ~100 geometrically spaced slices (anytime calls to gmmrrt_planner_run) to read the
 * best cost over time; the cost history then gives each improvement's iteration, whose time
 * is interpolated between slices. With plain, informed sampling is off (planner
 * "gmmrrt_rrtstar_plain": configured like OMPL's default RRTstar, k-nearest and uniform
 * sampling only). Returns false with *err on a setup error. */
bool run_gmmrrt_trial(const std::string &objective, const TaskSettings *task, double time_ms, int trial,
                      uint64_t seed, int32_t max_nodes, std::vector<unsigned char> *block, TrialResult *out,
                      std::string *err, bool plain = false);

} // namespace gmmrrt_bench

#endif
