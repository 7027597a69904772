/*
 * ompl_log.hpp - an OMPL-format benchmark log of both planners, so Planner Arena
 * (plannerarena.org, ompl_benchmark_statistics.py) can plot them side by side. Our planner
 * is wrapped as an ompl::base::Planner; ompl::tools::Benchmark runs each planner in turn
 * (not interleaved: the interleaved figures are the JSON trials of gmmrrt-bench-ompl).
 */
#ifndef GMMRRT_BENCH_OMPL_LOG_HPP
#define GMMRRT_BENCH_OMPL_LOG_HPP

#include <cstdint>
#include <string>

#include "problem.hpp"

namespace gmmrrt_bench {

/* Runs ompl::tools::Benchmark (runs per planner, time_ms each) and saves its log to path.
 * False with *err when the log cannot be written. */
bool write_ompl_benchmark_log(const std::string &path, const std::string &objective, const TaskSettings *task,
                              double time_ms, unsigned runs, int32_t max_nodes, uint64_t seed, std::string *err);

} // namespace gmmrrt_bench

#endif
