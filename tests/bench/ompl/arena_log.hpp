/*
 * arena_log.hpp - gmmrrt-bench-all's runs written as an ompl::tools::Benchmark log (the text
 * format of OMPL 1.5's Benchmark::saveResultsToStream), one log per problem and time budget, so
 * that ompl_benchmark_statistics.py turns them into a Planner Arena database. Written from the
 * benchmark's own runs (fresh planner per run, set-up counted, exact checks), not by
 * ompl::tools::Benchmark, which would time OMPL's set-up apart and could not run our planner on
 * these scenes.
 */
#ifndef GMMRRT_BENCH_ARENA_LOG_HPP
#define GMMRRT_BENCH_ARENA_LOG_HPP

#include <string>
#include <vector>

namespace gmmrrt_bench {

/* One run: milliseconds (NaN: unknown), cost (inf: no exactly free path). */
struct ArenaRun {
    double setup_ms, first_ms, solve_ms, cost;
};

struct ArenaPlanner {
    std::string name; /* written as geometric_<name> */
    std::vector<ArenaRun> runs;
};

/* Writes the log to path (replacing it); the experiment is named `experiment` (one word: the
 * parser keeps a line's last word), `setup` is the free text of the experiment's set-up block. Each run has the properties "best cost REAL",
 * "first solution time REAL" (s, set-up included), "setup time REAL" (s), "solved BOOLEAN"
 * (an exactly free path was returned) and "time REAL" (s, set-up plus solve); unknown values are
 * left empty (NULL in the database). False with *err when the file cannot be written. */
bool write_arena_log(const std::string &path, const std::string &experiment, const std::string &setup,
                     double budget_ms, unsigned seed, double total_seconds, const std::vector<ArenaPlanner> &planners,
                     std::string *err);

} // namespace gmmrrt_bench

#endif
