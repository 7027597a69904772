/*
 * bench_all_main.cpp - gmmrrt-bench-all: our RRT* against every OMPL 1.5 planner of the
 * comparison (RRTConnect, RRTstar, InformedRRTstar, SORRTstar, RRTsharp, RRTXstatic, LBTRRT,
 * BITstar, ABITstar, AITstar, FMT) on the 2-D point-robot problems of tests/data/bench_problems
 * (path length), with set-up counted on both sides and every motion checked exactly on both
 * sides (OMPL gets an exact motion validator for circles and boxes, so its costs mean what ours
 * mean; a returned path is re-checked here and counted only when it is exactly free).
 *
 * For each problem, planner and trial, one fresh run per budget (1, 10, 100, 1000 ms by
 * default): the best cost at a moment is the cost a run of that budget returns; the first
 * solution time is set-up plus the time to the first solution (OMPL's intermediate-solution
 * callback where the planner calls it, else the solve's duration when it returned early with a
 * solution, else unknown: "-"), median over every run of every budget. Set-up: OMPL from the space's construction to the end of
 * setup(); ours from init to the end of set_problem. Every run starts with the CPU's caches
 * evicted (evict_caches), so that every planner's first path is timed from the same state.
 *
 * With --model FILE (a features avoid model), also the social avoid scene of gmmrrt-bench-ompl
 * (problem.hpp: a person of radius 2 m at the origin facing the start, (-5, 0) -> (5, 0), cost
 * the integral of 1 + c(f) along the path, OMPL through GmmTaskCostObjective): every planner that
 * accepts that objective (those that throw are reported as such), ours as GMM-RRT* with uniform
 * sampling (bias 0). Both sides' cost is the same function of the path each returns: OMPL's
 * objective (its trapezoid rule at its motion-check resolution) on OMPL's path and on ours (our
 * planner searches with its own midpoint rule; recheck_our_path evaluates the returned path).
 *
 * With --approach-model FILE (a features approach model), also AP, the social approach scene of
 * gmmrrt-bench-social (bounds [-6,6] x [-5,5], a person at the origin facing +x, start (-4, 0.5)
 * behind them, goal (1.2, 0) in front of them; the person a disc of 0.55 m = the default person
 * radius 0.25 m plus robot radius 0.3 m around a point robot), task cost as S with the person as
 * the target (GMMRRT_TASK_APPROACH), OMPL through the same GmmTaskCostObjective.
 *
 * With --map FILE.yaml (map_server format, docs/world.md), also MAP: the map's whole extent,
 * start (-9, -2), goal (8, 4) (the floor plan of logs/maps/), a robot disc of 0.3 m, path length.
 * Ours reads the map through its raster layer (the distance field, conservative by up to about a
 * cell); OMPL gets raster_exact.hpp's exact disc-against-blocked-squares state and motion
 * validators over the same raster, and every returned path of both sides is re-checked with
 * them. The blocked cells mean the same on both sides; OMPL's free space is the larger one. The
 * map is loaded once before every run, outside both clocks, with its distance field (one transform
 * per map load, docs/world.md): a robot pays it when a map arrives, not per plan; OMPL's validators
 * read the same cells and need nothing built.
 *
 * With --arena DIR, one ompl::tools::Benchmark-format log per problem and budget,
 * DIR/<problem>_<budget>ms.log (arena_log.hpp), for Planner Arena.
 *
 * With --planners gmmrrt,ABITstar,... only those planners run, in that order (profiling one side,
 * or a quick two-planner comparison); by default all of them.
 *
 * Usage: gmmrrt-bench-all --problems DIR [--trials N] [--budgets 1,10,100,1000] [--json FILE]
 *        [--planners LIST] [--model FILE] [--approach-model FILE] [--map FILE.yaml] [--arena DIR]
 * Prints a markdown table per problem (medians over trials).
 */
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/fmt/FMT.h>
#include <ompl/geometric/planners/informedtrees/ABITstar.h>
#include <ompl/geometric/planners/informedtrees/AITstar.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/LBTRRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTXstatic.h>
#include <ompl/geometric/planners/rrt/RRTsharp.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/rrt/SORRTstar.h>
#include <ompl/util/Console.h>

#include "arena_log.hpp"
#include "gmmrrt/map_file.h"
#include "gmmrrt/raster.h"
#include "gmmrrt/planner.h"
#include "gmmrrt_runner.hpp"
#include "ompl_runner.hpp"
#include "problem.hpp"
#include "raster_exact.hpp"

namespace ob = ompl::base;
namespace og = ompl::geometric;
using Clock = std::chrono::steady_clock;

static double ms_since(Clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct Problem {
    std::string name;
    double xmin = 0, ymin = 0, xmax = 0, ymax = 0, sx = 0, sy = 0, gx = 0, gy = 0;
    std::vector<std::array<double, 3>> circles;
    std::vector<std::array<double, 5>> boxes; /* cx, cy, w, h, yaw */
    /* The map scene: a raster whose blocked cells hold a robot disc of robot_radius off. */
    const gmmrrt_raster_t *raster = nullptr;
    double robot_radius = 0.0;
    /* The social scenes: the task (AVOID, APPROACH with person 0 the target) and its settings;
     * the person is also circles[0] (its disc around a point robot). */
    gmmrrt_task_t task = GMMRRT_TASK_NONE;
    const gmmrrt_bench::TaskSettings *task_settings = nullptr;
};

static bool read_problem(const std::string &path, Problem *p)
{
    std::ifstream in(path);
    if (!in)
        return false;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream ls(line);
        std::string key;
        ls >> key;
        if (key == "name")
            ls >> p->name;
        else if (key == "bounds")
            ls >> p->xmin >> p->ymin >> p->xmax >> p->ymax;
        else if (key == "start")
            ls >> p->sx >> p->sy;
        else if (key == "goal")
            ls >> p->gx >> p->gy;
        else if (key == "circle") {
            std::array<double, 3> c{};
            ls >> c[0] >> c[1] >> c[2];
            p->circles.push_back(c);
        } else if (key == "box") {
            std::array<double, 5> b{};
            ls >> b[0] >> b[1] >> b[2] >> b[3] >> b[4];
            p->boxes.push_back(b);
        }
    }
    return !p->name.empty();
}

/* Exact geometry of a point robot among closed circles and boxes. */
static bool point_free(const Problem &p, double x, double y)
{
    if (p.raster && !gmmrrt_bench::raster_disc_free(*p.raster, p.robot_radius, x, y))
        return false;
    for (const auto &c : p.circles)
        if ((x - c[0]) * (x - c[0]) + (y - c[1]) * (y - c[1]) <= c[2] * c[2])
            return false;
    for (const auto &b : p.boxes) {
        const double dx = x - b[0], dy = y - b[1], cs = std::cos(b[4]), sn = std::sin(b[4]);
        if (std::fabs(dx * cs + dy * sn) <= 0.5 * b[2] && std::fabs(-dx * sn + dy * cs) <= 0.5 * b[3])
            return false;
    }
    return x >= p.xmin && x <= p.xmax && y >= p.ymin && y <= p.ymax;
}

static bool segment_free(const Problem &p, double x0, double y0, double x1, double y1)
{
    if (p.raster && !gmmrrt_bench::raster_motion_free(*p.raster, p.robot_radius, x0, y0, x1, y1))
        return false;
    const double vx = x1 - x0, vy = y1 - y0, l2 = vx * vx + vy * vy;
    for (const auto &c : p.circles) {
        double t = l2 > 0 ? ((c[0] - x0) * vx + (c[1] - y0) * vy) / l2 : 0.0;
        t = std::min(1.0, std::max(0.0, t));
        const double ex = x0 + t * vx - c[0], ey = y0 + t * vy - c[1];
        if (ex * ex + ey * ey <= c[2] * c[2])
            return false;
    }
    for (const auto &b : p.boxes) { /* Liang-Barsky clip in the box frame */
        const double cs = std::cos(b[4]), sn = std::sin(b[4]);
        const double ax = (x0 - b[0]) * cs + (y0 - b[1]) * sn, ay = -(x0 - b[0]) * sn + (y0 - b[1]) * cs;
        const double dx = vx * cs + vy * sn, dy = -vx * sn + vy * cs;
        double t0 = 0.0, t1 = 1.0;
        bool hit = true;
        const double pp[4] = {-dx, dx, -dy, dy};
        const double qq[4] = {ax + 0.5 * b[2], 0.5 * b[2] - ax, ay + 0.5 * b[3], 0.5 * b[3] - ay};
        for (int k = 0; k < 4 && hit; ++k) {
            if (pp[k] == 0.0) {
                if (qq[k] < 0.0)
                    hit = false;
            } else {
                const double r = qq[k] / pp[k];
                if (pp[k] < 0.0)
                    t0 = std::max(t0, r);
                else
                    t1 = std::min(t1, r);
                if (t0 > t1)
                    hit = false;
            }
        }
        if (hit)
            return false;
    }
    return point_free(p, x0, y0) && point_free(p, x1, y1);
}

class ExactValidity : public ob::StateValidityChecker {
public:
    ExactValidity(const ob::SpaceInformationPtr &si, const Problem &p) : StateValidityChecker(si), p_(p) {}
    bool isValid(const ob::State *s) const override
    {
        const auto *v = s->as<ob::RealVectorStateSpace::StateType>();
        return point_free(p_, v->values[0], v->values[1]);
    }

private:
    const Problem &p_;
};

class ExactMotion : public ob::MotionValidator {
public:
    ExactMotion(const ob::SpaceInformationPtr &si, const Problem &p) : MotionValidator(si), p_(p) {}
    bool checkMotion(const ob::State *a, const ob::State *b) const override
    {
        const auto *u = a->as<ob::RealVectorStateSpace::StateType>(), *v = b->as<ob::RealVectorStateSpace::StateType>();
        if (segment_free(p_, u->values[0], u->values[1], v->values[0], v->values[1])) {
            ++valid_;
            return true;
        }
        ++invalid_;
        return false;
    }
    bool checkMotion(const ob::State *a, const ob::State *b, std::pair<ob::State *, double> &last) const override
    {
        if (checkMotion(a, b))
            return true;
        /* The last valid state: bisect for the first blocked point (OMPL's contract). */
        const auto *u = a->as<ob::RealVectorStateSpace::StateType>(), *v = b->as<ob::RealVectorStateSpace::StateType>();
        double lo = 0.0, hi = 1.0;
        for (int k = 0; k < 40; ++k) {
            const double mid = 0.5 * (lo + hi);
            const double x = u->values[0] + mid * (v->values[0] - u->values[0]);
            const double y = u->values[1] + mid * (v->values[1] - u->values[1]);
            if (segment_free(p_, u->values[0], u->values[1], x, y))
                lo = mid;
            else
                hi = mid;
        }
        if (last.first)
            si_->getStateSpace()->interpolate(a, b, lo, last.first);
        last.second = lo;
        return false;
    }

private:
    const Problem &p_;
};

struct Run {
    double setup_ms = 0, first_ms = NAN, solve_ms = NAN, cost = INFINITY;
};

static std::shared_ptr<ob::Planner> make_planner(const std::string &name, const ob::SpaceInformationPtr &si)
{
    if (name == "RRTConnect") return std::make_shared<og::RRTConnect>(si);
    if (name == "RRTstar") return std::make_shared<og::RRTstar>(si);
    if (name == "InformedRRTstar") return std::make_shared<og::InformedRRTstar>(si);
    if (name == "SORRTstar") return std::make_shared<og::SORRTstar>(si);
    if (name == "RRTsharp") return std::make_shared<og::RRTsharp>(si);
    if (name == "RRTXstatic") return std::make_shared<og::RRTXstatic>(si);
    if (name == "LBTRRT") return std::make_shared<og::LBTRRT>(si);
    if (name == "BITstar") return std::make_shared<og::BITstar>(si);
    if (name == "ABITstar") return std::make_shared<og::ABITstar>(si);
    if (name == "AITstar") return std::make_shared<og::AITstar>(si);
    if (name == "FMT") return std::make_shared<og::FMT>(si);
    return nullptr;
}

static double path_cost_if_free(const Problem &p, const std::vector<std::array<double, 2>> &pts, double gx, double gy)
{
    if (pts.size() < 2)
        return INFINITY;
    if (std::hypot(pts.back()[0] - gx, pts.back()[1] - gy) > 1e-6)
        return INFINITY;
    double len = 0.0;
    for (size_t i = 1; i < pts.size(); ++i) {
        if (!segment_free(p, pts[i - 1][0], pts[i - 1][1], pts[i][0], pts[i][1]))
            return INFINITY;
        len += std::hypot(pts[i][0] - pts[i - 1][0], pts[i][1] - pts[i - 1][1]);
    }
    return len;
}

static Run run_ompl(const Problem &p, const std::string &name, double budget_ms,
                    const gmmrrt_bench::TaskSettings *task = nullptr)
{
    Run r;
    const Clock::time_point t_setup = Clock::now();
    auto space = std::make_shared<ob::RealVectorStateSpace>(2);
    ob::RealVectorBounds bounds(2);
    bounds.setLow(0, p.xmin);
    bounds.setLow(1, p.ymin);
    bounds.setHigh(0, p.xmax);
    bounds.setHigh(1, p.ymax);
    space->setBounds(bounds);
    auto si = std::make_shared<ob::SpaceInformation>(space);
    si->setStateValidityChecker(std::make_shared<ExactValidity>(si, p));
    si->setMotionValidator(std::make_shared<ExactMotion>(si, p));
    si->setup();
    auto pdef = std::make_shared<ob::ProblemDefinition>(si);
    ob::ScopedState<> start(space), goal(space);
    start[0] = p.sx;
    start[1] = p.sy;
    goal[0] = p.gx;
    goal[1] = p.gy;
    pdef->setStartAndGoalStates(start, goal, 1e-6);
    ob::OptimizationObjectivePtr obj = task ? gmmrrt_bench::make_objective(si, "task", task)
                                            : std::make_shared<ob::PathLengthOptimizationObjective>(si);
    obj->setCostThreshold(ob::Cost(0.0)); /* never "good enough": run the whole budget */
    pdef->setOptimizationObjective(obj);
    auto planner = make_planner(name, si);
    planner->setProblemDefinition(pdef);
    planner->setup();
    Clock::time_point t0;
    pdef->setIntermediateSolutionCallback([&](const ob::Planner *, const std::vector<const ob::State *> &, const ob::Cost) {
        if (std::isnan(r.first_ms))
            r.first_ms = ms_since(t0);
    });
    r.setup_ms = ms_since(t_setup);
    t0 = Clock::now();
    const ob::PlannerStatus st = planner->solve(ob::timedPlannerTerminationCondition(budget_ms / 1000.0));
    const double solve_ms = ms_since(t0);
    r.solve_ms = solve_ms;
    if (st == ob::PlannerStatus::EXACT_SOLUTION && pdef->getSolutionPath()) {
        auto *path = pdef->getSolutionPath()->as<og::PathGeometric>();
        std::vector<std::array<double, 2>> pts;
        for (const ob::State *s : path->getStates()) {
            const auto *v = s->as<ob::RealVectorStateSpace::StateType>();
            pts.push_back({v->values[0], v->values[1]});
        }
        r.cost = path_cost_if_free(p, pts, p.gx, p.gy);
        if (task && std::isfinite(r.cost))
            r.cost = path->cost(obj).value();
        if (std::isnan(r.first_ms) && solve_ms < 0.9 * budget_ms)
            r.first_ms = solve_ms; /* a planner that stops at its solution */
    }
    if (!std::isnan(r.first_ms))
        r.first_ms += r.setup_ms;
    return r;
}

/* Our returned path (gmmrrt_planner_best_path: the best tree path resampled at the waypoint
 * spacing, start and goal included) re-checked exactly like OMPL's, segment by segment
 * (path_cost_if_free): INFINITY when any segment is not free. Its cost: for path length the
 * planner's own best cost (the tree path's length); for a task cost OMPL's objective
 * (GmmTaskCostObjective, its trapezoid rule at its motion-check resolution) evaluated on this
 * path, so that both sides' costs are the same function of the path each returns. Runs after
 * the clocks stop. */
static double recheck_our_path(const Problem &p, const gmmrrt_planner_t *pl, double best_cost)
{
    gmmrrt_path_t path;
    if (gmmrrt_planner_best_path(pl, &path) != GMMRRT_OK)
        return INFINITY;
    std::vector<std::array<double, 2>> pts;
    for (int32_t k = 0; k < path.num_points; ++k)
        pts.push_back({path.x[k], path.y[k]});
    if (!std::isfinite(path_cost_if_free(p, pts, p.gx, p.gy)))
        return INFINITY;
    if (!p.task_settings)
        return best_cost;
    auto space = std::make_shared<ob::RealVectorStateSpace>(2);
    ob::RealVectorBounds bounds(2);
    bounds.setLow(0, p.xmin);
    bounds.setLow(1, p.ymin);
    bounds.setHigh(0, p.xmax);
    bounds.setHigh(1, p.ymax);
    space->setBounds(bounds);
    auto si = std::make_shared<ob::SpaceInformation>(space);
    si->setStateValidityChecker(std::make_shared<ExactValidity>(si, p));
    si->setup();
    const ob::OptimizationObjectivePtr obj = gmmrrt_bench::make_objective(si, "task", p.task_settings);
    og::PathGeometric g(si);
    ob::ScopedState<> s(space);
    for (const auto &q : pts) {
        s[0] = q[0];
        s[1] = q[1];
        g.append(s.get());
    }
    return g.cost(obj).value();
}

static Run run_ours(const Problem &p, double budget_ms, uint64_t seed, std::vector<unsigned char> *block)
{
    Run r;
    gmmrrt_planner_config_t cfg;
    gmmrrt_planner_config_default(&cfg);
    cfg.planner = GMMRRT_PLANNER_RRT_STAR;
    cfg.seed = seed;
    cfg.robot_radius_m = p.robot_radius;
    cfg.history_capacity = 1 << 16;
    /* OMPL RRTstar's defaults on this space (as gmmrrt-bench-ompl, problem.hpp): range and
     * motion-check resolution from the space's extent, goal bias 0.05, uniform sampling. */
    const double extent = std::hypot(p.xmax - p.xmin, p.ymax - p.ymin);
    cfg.step_m = 0.2 * extent;
    cfg.edge_resolution_m = 0.01 * extent;
    cfg.goal_bias = 0.05;
    cfg.gmm_bias = 0.0;
    /* The clearance grid must cover the whole bounds at its resolution. */
    const double cells = (std::ceil((p.xmax - p.xmin) / cfg.grid_resolution_m) + 2.0) *
                         (std::ceil((p.ymax - p.ymin) / cfg.grid_resolution_m) + 2.0);
    cfg.grid_max_cells = std::max(cfg.grid_max_cells, static_cast<int32_t>(cells));
    const size_t size = gmmrrt_planner_mem_size(&cfg);
    if (block->size() < size + 8)
        block->assign(size + 8, 0); /* allocated once, outside the clocks */
    void *mem = reinterpret_cast<void *>((reinterpret_cast<uintptr_t>(block->data()) + 7u) & ~uintptr_t(7));
    gmmrrt_problem_t pr{};
    pr.start_x = p.sx;
    pr.start_y = p.sy;
    pr.goal_x = p.gx;
    pr.goal_y = p.gy;
    pr.goal_tolerance_m = 1e-6;
    pr.task = GMMRRT_TASK_NONE;
    pr.target_person = -1;
    pr.obstacles.bounds = {p.xmin, p.ymin, p.xmax, p.ymax};
    for (const auto &c : p.circles)
        pr.obstacles.circles[pr.obstacles.num_circles++] = {c[0], c[1], c[2]};
    for (const auto &b : p.boxes)
        pr.obstacles.boxes[pr.obstacles.num_boxes++] = {b[0], b[1], b[2], b[3], b[4]};
    pr.obstacles.raster = p.raster;
    const Clock::time_point t_setup = Clock::now();
    gmmrrt_planner_t *pl = nullptr;
    if (gmmrrt_planner_init(&pl, mem, size, &cfg) != GMMRRT_OK || gmmrrt_planner_set_problem(pl, &pr) != GMMRRT_OK)
        return r;
    r.setup_ms = ms_since(t_setup);
    gmmrrt_budget_t budget{budget_ms, 0, 0.0, 0};
    gmmrrt_plan_stats_t st;
    const Clock::time_point t_run = Clock::now();
    gmmrrt_planner_run(pl, &budget, &st);
    r.solve_ms = ms_since(t_run);
    if (st.first_solution_ms >= 0.0)
        r.first_ms = r.setup_ms + st.first_solution_ms;
    if (std::isfinite(st.best_cost))
        r.cost = recheck_our_path(p, pl, st.best_cost);
    return r;
}

/* GMM-RRT* with uniform sampling on a social scene (S or AP): gmmrrt_bench_config's settings
 * (OMPL RRTstar's defaults, problem.hpp) taken from this scene's bounds, the person a disc of the
 * scene's circle radius. For S this is exactly gmmrrt_bench_config / gmmrrt_bench_problem. */
static Run run_ours_task(const Problem &p, double budget_ms, uint64_t seed, std::vector<unsigned char> *block)
{
    Run r;
    const gmmrrt_bench::TaskSettings &task = *p.task_settings;
    gmmrrt_planner_config_t cfg = gmmrrt_bench::gmmrrt_bench_config("task", &task, 2000000, seed);
    const double extent = std::hypot(p.xmax - p.xmin, p.ymax - p.ymin);
    cfg.step_m = 0.2 * extent;
    cfg.edge_resolution_m = 0.01 * extent;
    cfg.rewire_gamma = 1.1 * 2.0 * std::sqrt(1.5) * std::sqrt((p.xmax - p.xmin) * (p.ymax - p.ymin) / M_PI);
    cfg.person_influence_m = 2.0 * extent;
    cfg.person_radius_m = p.circles.at(0)[2];
    const size_t size = gmmrrt_planner_mem_size(&cfg);
    if (block->size() < size + 8)
        block->assign(size + 8, 0);
    void *mem = reinterpret_cast<void *>((reinterpret_cast<uintptr_t>(block->data()) + 7u) & ~uintptr_t(7));
    gmmrrt_problem_t pr{};
    pr.start_x = p.sx;
    pr.start_y = p.sy;
    pr.goal_x = p.gx;
    pr.goal_y = p.gy;
    pr.goal_tolerance_m = gmmrrt_bench::kGoalTolerance;
    pr.task = p.task;
    pr.target_person = p.task == GMMRRT_TASK_APPROACH ? 0 : -1;
    pr.model = task.model;
    pr.obstacles.bounds = {p.xmin, p.ymin, p.xmax, p.ymax};
    pr.obstacles.num_people = 1;
    pr.obstacles.people[0] = task.person;
    const Clock::time_point t_setup = Clock::now();
    gmmrrt_planner_t *pl = nullptr;
    if (gmmrrt_planner_init(&pl, mem, size, &cfg) != GMMRRT_OK || gmmrrt_planner_set_problem(pl, &pr) != GMMRRT_OK)
        return r;
    r.setup_ms = ms_since(t_setup);
    gmmrrt_budget_t budget{budget_ms, 0, 0.0, 0};
    gmmrrt_plan_stats_t st;
    const Clock::time_point t_run = Clock::now();
    gmmrrt_planner_run(pl, &budget, &st);
    r.solve_ms = ms_since(t_run);
    if (st.first_solution_ms >= 0.0)
        r.first_ms = r.setup_ms + st.first_solution_ms;
    if (std::isfinite(st.best_cost))
        r.cost = recheck_our_path(p, pl, st.best_cost);
    return r;
}

/* Every run of every planner starts from the same state of the CPU's caches and TLBs: before
 * each run (outside both clocks) this writes one byte per cache line of a 128 MiB buffer, four
 * times the last-level cache of the machines of docs/benchmarks.md (32 MiB; a CPU with a larger
 * one would keep part of each side's lines). Without it the first-path times compared
 * different states: a planner that stops at its first path (RRTConnect) ran each time right
 * after a run of its own of some microseconds, its code and data still cached, while an anytime
 * planner (ours, RRTstar, ...) started after one of its own runs of up to a second that had
 * evicted them. Each planner keeps its own sequence of runs (its allocator's state stays its own). */
static volatile unsigned char evict_sink; /* the writes' checksum: keeps them */

static void evict_caches()
{
    static std::vector<unsigned char> buffer(size_t(128) << 20, 1);
    unsigned char sum = 0;
    for (size_t i = 0; i < buffer.size(); i += 64)
        sum = static_cast<unsigned char>(sum + ++buffer[i]);
    evict_sink = sum;
}

static double median(std::vector<double> v)
{
    v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return std::isnan(x); }), v.end());
    if (v.empty())
        return NAN;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

static std::string fmt(double v, const char *f = "%.3f")
{
    if (std::isnan(v))
        return "-";
    if (std::isinf(v))
        return "none";
    char b[64];
    std::snprintf(b, sizeof b, f, v);
    return b;
}

int main(int argc, char **argv)
{
    std::string dir = "tests/data/bench_problems", json, model_path, approach_path, map_path, arena_dir;
    int trials = 3;
    std::vector<double> budgets = {1, 10, 100, 1000};
    std::vector<std::string> only, chosen;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--problems" && i + 1 < argc)
            dir = argv[++i];
        else if (a == "--trials" && i + 1 < argc)
            trials = std::atoi(argv[++i]);
        else if (a == "--budgets" && i + 1 < argc) {
            budgets.clear();
            std::stringstream ss(argv[++i]);
            std::string t;
            while (std::getline(ss, t, ','))
                budgets.push_back(std::atof(t.c_str()));
        } else if (a == "--only" && i + 1 < argc)
            only.push_back(argv[++i]);
        else if (a == "--planners" && i + 1 < argc) {
            std::stringstream ss(argv[++i]);
            std::string t;
            while (std::getline(ss, t, ','))
                chosen.push_back(t);
        }
        else if (a == "--json" && i + 1 < argc)
            json = argv[++i];
        else if (a == "--model" && i + 1 < argc)
            model_path = argv[++i];
        else if (a == "--approach-model" && i + 1 < argc)
            approach_path = argv[++i];
        else if (a == "--map" && i + 1 < argc)
            map_path = argv[++i];
        else if (a == "--arena" && i + 1 < argc)
            arena_dir = argv[++i];
        else {
            std::fprintf(stderr, "usage: gmmrrt-bench-all [--problems DIR] [--trials N] [--budgets 1,10,100,1000] "
                                 "[--only PROBLEM] [--planners gmmrrt,RRTConnect,...] [--json FILE] [--model FILE] "
                                 "[--approach-model FILE] [--map FILE.yaml] [--arena DIR]\n");
            return 2;
        }
    }
    if (trials < 1 || budgets.empty()) {
        std::fprintf(stderr, "gmmrrt-bench-all: --trials must be >= 1 and --budgets not empty\n");
        return 2;
    }
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    const std::vector<std::string> all_planners = {"gmmrrt",    "RRTConnect", "RRTstar", "InformedRRTstar",
                                                   "SORRTstar", "RRTsharp",   "RRTXstatic", "LBTRRT",
                                                   "BITstar",   "ABITstar",   "AITstar", "FMT"};
    std::vector<std::string> planners = all_planners;
    if (!chosen.empty()) {
        for (const std::string &name : chosen)
            if (std::find(all_planners.begin(), all_planners.end(), name) == all_planners.end()) {
                std::fprintf(stderr, "gmmrrt-bench-all: --planners: unknown planner '%s'\n", name.c_str());
                return 2;
            }
        planners = chosen; /* in the order given */
    }
    std::FILE *jf = json.empty() ? nullptr : std::fopen(json.c_str(), "w");
    std::vector<unsigned char> block;
    static gmmrrt_model_t model;
    gmmrrt_bench::TaskSettings task;
    if (!model_path.empty()) {
        std::string err;
        if (!gmmrrt_bench::load_model_file(model_path, &model, &err)) {
            std::fprintf(stderr, "gmmrrt-bench-all: --model: %s\n", err.c_str());
            return 1;
        }
        task.model = &model;
    }
    static gmmrrt_model_t approach_model;
    gmmrrt_bench::TaskSettings approach;
    approach.person = {0.0, 0.0, 0.0}; /* facing +x; the robot comes from behind */
    if (!approach_path.empty()) {
        std::string err;
        if (!gmmrrt_bench::load_model_file(approach_path, &approach_model, &err)) {
            std::fprintf(stderr, "gmmrrt-bench-all: --approach-model: %s\n", err.c_str());
            return 1;
        }
        approach.model = &approach_model;
    }
    /* The map: at most 2^20 cells (9 MiB of raster); a larger one is refused with its sizes. */
    static gmmrrt_raster_t raster;
    std::vector<unsigned char> raster_mem;
    if (!map_path.empty()) {
        const int32_t max_cells = 1 << 20, max_side = 4096;
        raster_mem.assign(gmmrrt_raster_mem_size(max_cells, max_side) + 8, 0);
        void *mem = reinterpret_cast<void *>((reinterpret_cast<uintptr_t>(raster_mem.data()) + 7u) & ~uintptr_t(7));
        char err[512] = "";
        if (gmmrrt_raster_init(&raster, mem, raster_mem.size() - 8, max_cells, max_side) != GMMRRT_OK ||
            gmmrrt_map_load_file(map_path.c_str(), 1, &raster, err, sizeof err) != GMMRRT_OK) {
            std::fprintf(stderr, "gmmrrt-bench-all: --map: %s\n", err[0] ? err : "cannot set up the raster");
            return 1;
        }
        if (raster.origin_yaw != 0.0) {
            std::fprintf(stderr, "gmmrrt-bench-all: --map %s: the scene's bounds are the map's extent, which needs "
                                 "origin yaw 0 (it is %g)\n", map_path.c_str(), raster.origin_yaw);
            return 1;
        }
    }
    std::vector<std::string> files = {"problem_A.txt", "problem_B.txt", "problem_C.txt"};
    if (task.model)
        files.push_back("social");
    if (approach.model)
        files.push_back("approach");
    if (!map_path.empty())
        files.push_back("map");
    const unsigned first_seed = 1;
    for (const std::string &file : files) {
        Problem p;
        const bool social = file == "social" || file == "approach";
        if (file == "approach") {
            p.name = "AP";
            p.xmin = -6.0, p.ymin = -5.0, p.xmax = 6.0, p.ymax = 5.0;
            p.sx = -4.0, p.sy = 0.5, p.gx = 1.2, p.gy = 0.0;
            p.circles.push_back({0.0, 0.0, 0.25 + 0.3});
            p.task = GMMRRT_TASK_APPROACH;
            p.task_settings = &approach;
        } else if (file == "map") {
            p.name = "MAP";
            p.raster = &raster;
            p.robot_radius = 0.3;
            p.xmin = raster.origin_x, p.ymin = raster.origin_y;
            p.xmax = raster.origin_x + raster.width * raster.resolution_m;
            p.ymax = raster.origin_y + raster.height * raster.resolution_m;
            p.sx = -9.0, p.sy = -2.0, p.gx = 8.0, p.gy = 4.0;
            if (!point_free(p, p.sx, p.sy) || !point_free(p, p.gx, p.gy)) {
                std::fprintf(stderr, "gmmrrt-bench-all: --map %s: start (-9, -2) or goal (8, 4) is not free for a "
                                     "0.3 m disc\n", map_path.c_str());
                return 1;
            }
        } else if (social) {
            p.name = "S";
            p.xmin = p.ymin = gmmrrt_bench::kBoundLo;
            p.xmax = p.ymax = gmmrrt_bench::kBoundHi;
            p.sx = gmmrrt_bench::kStartX;
            p.sy = gmmrrt_bench::kStartY;
            p.gx = gmmrrt_bench::kGoalX;
            p.gy = gmmrrt_bench::kGoalY;
            p.circles.push_back({0.0, 0.0, gmmrrt_bench::kDiscRadius});
            p.task = GMMRRT_TASK_AVOID;
            p.task_settings = &task;
        } else if (!read_problem(dir + "/" + file, &p)) {
            std::fprintf(stderr, "gmmrrt-bench-all: cannot read %s/%s\n", dir.c_str(), file.c_str());
            return 1;
        }
        if (!only.empty() && std::find(only.begin(), only.end(), p.name) == only.end())
            continue;
        std::printf("\n### Problem %s (%s, %d trials)\n\n| planner | set-up ms | first path incl. set-up ms |", p.name.c_str(),
                    file == "social" ? "social avoid, task cost"
                    : file == "approach" ? "social approach, task cost"
                    : file == "map" ? "floor plan, robot radius 0.3 m, path length" : file.c_str(),
                    trials);
        for (double b : budgets)
            std::printf(" cost @ %g ms |", b);
        std::printf("\n|---|---|---|");
        for (size_t k = 0; k < budgets.size(); ++k)
            std::printf("---|");
        std::printf("\n");
        const Clock::time_point t_problem = Clock::now();
        std::vector<std::vector<gmmrrt_bench::ArenaPlanner>> arena(budgets.size());
        for (const std::string &name : planners) {
            for (auto &per_budget : arena)
                per_budget.push_back({name, {}});
            std::vector<double> setup, first;
            std::vector<std::vector<double>> cost(budgets.size());
            for (int t = 0; t < trials; ++t)
                for (size_t k = 0; k < budgets.size(); ++k) {
                    Run r;
                    evict_caches();
                    try {
                        r = name == "gmmrrt" ? (social ? run_ours_task(p, budgets[k], first_seed + (uint64_t)t, &block)
                                                       : run_ours(p, budgets[k], first_seed + (uint64_t)t, &block))
                                             : run_ompl(p, name, budgets[k], p.task_settings);
                    } catch (const std::exception &e) { /* a planner that refuses the objective */
                        r = Run{};
                        r.setup_ms = NAN;
                        if (t == 0 && k == 0)
                            std::fprintf(stderr, "gmmrrt-bench-all: %s on %s: %s\n", name.c_str(), p.name.c_str(),
                                         e.what());
                    }
                    setup.push_back(r.setup_ms);
                    first.push_back(r.first_ms); /* every run times its first solution */
                    cost[k].push_back(r.cost);
                    arena[k].back().runs.push_back({r.setup_ms, r.first_ms, r.solve_ms, r.cost});
                    if (jf)
                        std::fprintf(jf,
                                     "{\"problem\": \"%s\", \"planner\": \"%s\", \"trial\": %d, \"budget_ms\": %g, "
                                     "\"setup_ms\": %s, \"first_ms\": %s, \"cost\": %s}\n",
                                     p.name.c_str(), name.c_str(), t, budgets[k],
                                     std::isnan(r.setup_ms) ? "null" : fmt(r.setup_ms, "%.6f").c_str(),
                                     std::isnan(r.first_ms) ? "null" : fmt(r.first_ms, "%.6f").c_str(),
                                     std::isfinite(r.cost) ? fmt(r.cost, "%.6f").c_str() : "null");
                }
            std::printf("| %s | %s | %s |", name.c_str(), fmt(median(setup)).c_str(), fmt(median(first)).c_str());
            for (size_t k = 0; k < budgets.size(); ++k)
                std::printf(" %s |", fmt(median(cost[k]), "%.4f").c_str());
            std::printf("\n");
            std::fflush(stdout);
        }
        if (!arena_dir.empty()) {
            const double seconds = ms_since(t_problem) / 1000.0;
            std::string setup = "gmmrrt-bench-all problem " + p.name + " (" + file + "): bounds [" +
                                fmt(p.xmin, "%g") + ", " + fmt(p.xmax, "%g") + "] x [" + fmt(p.ymin, "%g") + ", " +
                                fmt(p.ymax, "%g") + "], start (" + fmt(p.sx, "%g") + ", " + fmt(p.sy, "%g") +
                                "), goal (" + fmt(p.gx, "%g") + ", " + fmt(p.gy, "%g") + "); " +
                                (social ? "task cost" : "path length") +
                                "; one fresh planner per run, set-up counted, motions checked exactly on both "
                                "sides; the budgets' runs are interleaved, so 'seconds spent' covers all budgets";
            for (size_t k = 0; k < budgets.size(); ++k) {
                std::string err;
                const std::string path = arena_dir + "/" + p.name + "_" + fmt(budgets[k], "%g") + "ms.log";
                if (!gmmrrt_bench::write_arena_log(path, p.name + "_" + fmt(budgets[k], "%g") + "ms",
                                                   setup, budgets[k], first_seed, seconds, arena[k], &err)) {
                    std::fprintf(stderr, "gmmrrt-bench-all: %s\n", err.c_str());
                    return 1;
                }
            }
        }
    }
    if (jf)
        std::fclose(jf);
    return 0;
}
