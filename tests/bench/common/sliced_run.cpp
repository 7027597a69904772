/*
 * sliced_run.cpp - sliced timing of our planner (sliced_run.hpp).
 */
#include "sliced_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

namespace gmmrrt_bench {

using Clock = std::chrono::steady_clock;

static double ms_since(Clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/* Time (ms) at which `iteration` was reached, by linear interpolation between slices. */
static double time_of_iteration(const std::vector<CostPoint> &slices, int64_t iteration)
{
    double t_prev = 0.0;
    int64_t it_prev = 0;
    for (const CostPoint &s : slices) {
        if (s.iterations >= iteration) {
            if (s.iterations == it_prev)
                return s.time_ms;
            const double frac =
                static_cast<double>(iteration - it_prev) / static_cast<double>(s.iterations - it_prev);
            return t_prev + frac * (s.time_ms - t_prev);
        }
        t_prev = s.time_ms;
        it_prev = s.iterations;
    }
    return slices.empty() ? 0.0 : slices.back().time_ms;
}

void run_sliced(gmmrrt_planner_t *p, double time_ms, int32_t history_capacity, TrialResult *r)
{
    std::vector<CostPoint> slices;
    gmmrrt_plan_stats_t stats{};
    gmmrrt_status_t st = GMMRRT_NO_PATH_YET;
    const double cpu0 = thread_cpu_ms();
    const Clock::time_point t0 = Clock::now();
    double end_ms = std::min(0.02, time_ms);
    for (;;) {
        const double now = ms_since(t0);
        if (now < end_ms) {
            gmmrrt_budget_t budget{};
            budget.time_ms = end_ms - now;
            const gmmrrt_status_t slice = gmmrrt_planner_run(p, &budget, &stats);
            slices.push_back({ms_since(t0), stats.iterations, stats.best_cost});
            /* TIMEOUT: this slice's budget was gone before its first iteration (a short slice
             * and a preemption or page fault); the run goes on. It used to end the trial, and a
             * run without a path yet then counted as never solved. */
            if (slice != GMMRRT_TIMEOUT) {
                st = slice;
                if (st != GMMRRT_OK && st != GMMRRT_NO_PATH_YET)
                    break; /* pool full (or an error): the run ends here */
            }
        }
        if (end_ms >= time_ms)
            break;
        end_ms = std::min(end_ms * 1.1, time_ms);
    }
    r->time_ms = ms_since(t0);
    r->cpu_ms = thread_cpu_ms() - cpu0;
    r->status = gmmrrt_status_str(st);
    r->iterations = stats.iterations;
    r->nodes = stats.nodes;
    r->first_solution_ms = stats.first_solution_ms;
    r->first_solution_iteration = stats.first_solution_iteration;
    r->final_cost = std::isfinite(stats.best_cost) ? stats.best_cost : -1.0;

    const int32_t cap = std::max(history_capacity, 1);
    std::vector<int64_t> its(static_cast<size_t>(cap));
    std::vector<double> costs(static_cast<size_t>(cap));
    const int32_t n = gmmrrt_planner_cost_history(p, its.data(), costs.data(), cap);
    r->history.clear();
    for (int32_t i = 0; i < n; ++i)
        r->history.push_back({time_of_iteration(slices, its[i]), its[i], costs[i]});
    for (const CostPoint &s : slices)
        if (std::isfinite(s.cost))
            r->history.push_back(s);
    std::sort(r->history.begin(), r->history.end(),
              [](const CostPoint &a, const CostPoint &b) { return a.iterations < b.iterations; });
}

} // namespace gmmrrt_bench
