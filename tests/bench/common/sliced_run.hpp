/*
 * sliced_run.hpp - timing one run of our planner (planner.h) with its best-cost-versus-time
 * curve. The run is cut into geometrically spaced slices (0.02 ms x 1.1^k, ~100 per second of
 * budget; anytime calls to gmmrrt_planner_run) and the stats are read after each; the
 * planner's cost history then gives each improvement's iteration, whose time is interpolated
 * between the slices. The slices' own readings are kept too (exact times, and complete if
 * the history capacity ran out).
 */
#ifndef GMMRRT_BENCH_SLICED_RUN_HPP
#define GMMRRT_BENCH_SLICED_RUN_HPP

#include "gmmrrt/planner.h"
#include "trial.hpp"

namespace gmmrrt_bench {

/* Runs p (problem already set) for time_ms and fills time_ms, iterations, nodes,
 * first_solution_*, final_cost, status and history of *r. history_capacity is the
 * planner's configured history capacity. Stops early on GMMRRT_POOL_FULL or an error. */
void run_sliced(gmmrrt_planner_t *p, double time_ms, int32_t history_capacity, TrialResult *r);

} // namespace gmmrrt_bench

#endif
