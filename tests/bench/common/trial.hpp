/*
 * trial.hpp - one benchmark trial's record, shared by the OMPL and the gmmrrt runners of
 * gmmrrt-bench-ompl, and its JSON form (one object per line, read by tools/bench.py).
 *
 * The benchmark problem (docs/benchmarks.md): [-10,10]^2, a disc of radius 2 at the origin, start
 * (-5,0), goal (5,0), a point robot; path length, or path length plus the paper's task
 * cost (Sect. 4) integrated along the path.
 */
#ifndef GMMRRT_BENCH_TRIAL_HPP
#define GMMRRT_BENCH_TRIAL_HPP

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace gmmrrt_bench {

/* A point of the best-cost-versus-time curve of one run. */
struct CostPoint {
    double time_ms;     /* since the start of the timed planning */
    int64_t iterations; /* samples drawn so far */
    double cost;        /* best cost so far */
};

struct TrialResult {
    std::string planner;           /* "ompl_rrtstar" or "gmmrrt_rrtstar" */
    std::string objective;         /* "length" or "task" */
    int trial = 0;
    uint64_t seed = 0;
    double setup_ms = 0;           /* untimed preparation (OMPL setup(); our set_problem) */
    double time_ms = 0;            /* timed planning, wall clock */
    double cpu_ms = 0;             /* CPU time of the planning thread over the same span: on a shared
                                      machine, iterations per CPU-second is the steadier rate */
    int64_t iterations = 0;        /* samples drawn, as OMPL counts them */
    int64_t nodes = 0;             /* tree size at the end */
    double first_solution_ms = -1; /* -1: no solution */
    int64_t first_solution_iteration = -1;
    double final_cost = -1;        /* -1: no solution */
    std::string status;            /* planner's own final status, for the record */
    std::vector<CostPoint> history;
};

/* CPU time of the calling thread, ms (CLOCK_THREAD_CPUTIME_ID). */
double thread_cpu_ms();

/* Writes r as one JSON object on one line (no trailing newline). Non-finite numbers become null. */
void write_trial_json(std::ostream &out, const TrialResult &r);

} // namespace gmmrrt_bench

#endif
