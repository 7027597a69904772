/*
 * gmmrrt_runner.cpp - our RRT* (planner.h; paper Sect. 4) on the benchmark problem. Timed from
 * the first gmmrrt_planner_run() call; set_problem (collision world build) is timed apart as
 * setup, like OMPL's setup().
 */
#include "gmmrrt_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "gmmrrt/planner.h"
#include "sliced_run.hpp"

namespace gmmrrt_bench {

using Clock = std::chrono::steady_clock;

static double ms_since(Clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

gmmrrt_planner_config_t gmmrrt_bench_config(const std::string &objective, const TaskSettings *task,
                                            int32_t max_nodes, uint64_t seed)
{
    gmmrrt_planner_config_t cfg;
    gmmrrt_planner_config_default(&cfg);
    const bool is_task = objective == "task";
    cfg.planner = is_task ? GMMRRT_PLANNER_GMM_RRT_STAR : GMMRRT_PLANNER_RRT_STAR;
    cfg.seed = seed;
    cfg.max_nodes = max_nodes;
    cfg.history_capacity = std::max(cfg.history_capacity, 1 << 16);
    cfg.robot_radius_m = 0.0; /* point robot */
    cfg.person_radius_m = kDiscRadius;
    cfg.edge_resolution_m = ompl_default_resolution();
    cfg.step_m = ompl_default_range();
    cfg.goal_bias = kOmplGoalBias;
    cfg.gmm_bias = 0.0; /* uniform sampling, as OMPL */
    cfg.rewire_gamma = ompl_rewire_gamma();
    cfg.w_length = is_task ? task->w_length : 1.0;
    cfg.w_task = is_task ? task->w_task : 0.0;
    if (is_task)
        cfg.delta = task->delta;
    cfg.person_influence_m = 2.0 * max_extent();
    /* The clearance grid must cover the whole square at the configured resolution. */
    const double cells_per_side = std::ceil((kBoundHi - kBoundLo) / cfg.grid_resolution_m) + 2.0;
    cfg.grid_max_cells = std::max(cfg.grid_max_cells, static_cast<int32_t>(cells_per_side * cells_per_side));
    return cfg;
}

gmmrrt_problem_t gmmrrt_bench_problem(const std::string &objective, const TaskSettings *task)
{
    gmmrrt_problem_t pb{};
    pb.start_x = kStartX;
    pb.start_y = kStartY;
    pb.goal_x = kGoalX;
    pb.goal_y = kGoalY;
    pb.goal_tolerance_m = kGoalTolerance;
    pb.target_person = -1;
    pb.obstacles.bounds = {kBoundLo, kBoundLo, kBoundHi, kBoundHi};
    if (objective == "task") {
        pb.task = GMMRRT_TASK_AVOID;
        pb.model = task->model;
        pb.obstacles.num_people = 1;
        pb.obstacles.people[0] = task->person;
    } else {
        pb.task = GMMRRT_TASK_NONE;
        pb.model = nullptr;
        pb.obstacles.num_circles = 1;
        pb.obstacles.circles[0] = {0.0, 0.0, kDiscRadius};
    }
    return pb;
}

bool run_gmmrrt_trial(const std::string &objective, const TaskSettings *task, double time_ms, int trial,
                      uint64_t seed, int32_t max_nodes, std::vector<unsigned char> *block, TrialResult *out,
                      std::string *err, bool plain)
{
    TrialResult r;
    r.planner = plain ? "gmmrrt_rrtstar_plain" : "gmmrrt_rrtstar";
    r.objective = objective;
    r.trial = trial;
    r.seed = seed;

    gmmrrt_planner_config_t cfg = gmmrrt_bench_config(objective, task, max_nodes, seed);
    if (plain)
        cfg.informed_sampling = 0;
    const size_t need = gmmrrt_planner_mem_size(&cfg);
    if (need == 0) {
        *err = "gmmrrt_planner_mem_size rejected the benchmark configuration";
        return false;
    }
    if (block->size() < need + 8)
        block->assign(need + 8, 0); /* outside the timing; +8 to align */
    void *mem = block->data();
    size_t size = block->size();
    void *aligned = std::align(8, need, mem, size);

    gmmrrt_planner_t *p = nullptr;
    gmmrrt_status_t st = gmmrrt_planner_init(&p, aligned, size, &cfg);
    if (st != GMMRRT_OK) {
        *err = std::string("gmmrrt_planner_init: ") + gmmrrt_status_str(st);
        return false;
    }
    const gmmrrt_problem_t pb = gmmrrt_bench_problem(objective, task);
    const Clock::time_point t_setup = Clock::now();
    st = gmmrrt_planner_set_problem(p, &pb);
    r.setup_ms = ms_since(t_setup);
    if (st != GMMRRT_OK) {
        *err = std::string("gmmrrt_planner_set_problem: ") + gmmrrt_status_str(st);
        return false;
    }

    run_sliced(p, time_ms, cfg.history_capacity, &r);
    *out = r;
    return true;
}

} // namespace gmmrrt_bench
