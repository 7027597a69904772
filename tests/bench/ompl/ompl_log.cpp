/*
 * ompl_log.cpp - our planner behind ompl::base::Planner, and an ompl::tools::Benchmark run
 * of it next to OMPL's RRTstar (ompl_log.hpp). The wrapper plans in 1 ms anytime slices
 * until OMPL's termination condition holds, and reports "iterations INTEGER" and
 * "best cost REAL" as progress properties, as RRTstar does.
 */
#include "ompl_log.hpp"

#include <atomic>
#include <cmath>
#include <memory>
#include <vector>

#include <ompl/base/Planner.h>
#include <ompl/base/PlannerData.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/tools/benchmark/Benchmark.h>

#include "gmmrrt/planner.h"
#include "gmmrrt_runner.hpp"
#include "ompl_runner.hpp"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace gmmrrt_bench {

namespace {

class GmmrrtOmplPlanner : public ob::Planner {
public:
    GmmrrtOmplPlanner(const ob::SpaceInformationPtr &si, std::string objective, const TaskSettings *task,
                      int32_t max_nodes, uint64_t seed)
        : Planner(si, "gmmrrt_rrtstar"), objective_(std::move(objective)), task_(task), max_nodes_(max_nodes),
          seed_(seed)
    {
        specs_.optimizingPaths = true;
        specs_.approximateSolutions = false;
        addPlannerProgressProperty("iterations INTEGER", [this] { return std::to_string(iterations_.load()); });
        addPlannerProgressProperty("best cost REAL", [this] { return std::to_string(best_cost_.load()); });
    }

    ob::PlannerStatus solve(const ob::PlannerTerminationCondition &ptc) override
    {
        checkValidity();
        const gmmrrt_planner_config_t cfg = gmmrrt_bench_config(objective_, task_, max_nodes_, seed_++);
        const size_t need = gmmrrt_planner_mem_size(&cfg);
        if (need == 0)
            return ob::PlannerStatus::CRASH;
        if (block_.size() < need + 8)
            block_.assign(need + 8, 0);
        void *mem = block_.data();
        size_t size = block_.size();
        void *aligned = std::align(8, need, mem, size);
        if (gmmrrt_planner_init(&planner_, aligned, size, &cfg) != GMMRRT_OK)
            return ob::PlannerStatus::CRASH;
        const gmmrrt_problem_t pb = gmmrrt_bench_problem(objective_, task_);
        if (gmmrrt_planner_set_problem(planner_, &pb) != GMMRRT_OK)
            return ob::PlannerStatus::INVALID_START;
        iterations_ = 0;
        best_cost_ = std::nan("");
        gmmrrt_plan_stats_t stats{};
        gmmrrt_status_t st = GMMRRT_NO_PATH_YET;
        while (!ptc) {
            gmmrrt_budget_t budget{};
            budget.time_ms = 1.0;
            st = gmmrrt_planner_run(planner_, &budget, &stats);
            iterations_ = stats.iterations;
            if (std::isfinite(stats.best_cost))
                best_cost_ = stats.best_cost;
            if (st != GMMRRT_OK && st != GMMRRT_NO_PATH_YET)
                break;
        }
        if (!std::isfinite(stats.best_cost))
            return ob::PlannerStatus::TIMEOUT;
        gmmrrt_path_t path;
        if (gmmrrt_planner_best_path(planner_, &path) != GMMRRT_OK || path.num_points < 2)
            return ob::PlannerStatus::TIMEOUT;
        auto geometric = std::make_shared<og::PathGeometric>(si_);
        ob::ScopedState<> s(si_->getStateSpace());
        for (int32_t i = 0; i < path.num_points; ++i) {
            s[0] = path.x[i];
            s[1] = path.y[i];
            geometric->append(s.get());
        }
        ob::PlannerSolution solution(geometric);
        solution.setPlannerName(getName());
        solution.setOptimized(pdef_->getOptimizationObjective(), ob::Cost(stats.best_cost), false);
        pdef_->addSolutionPath(solution);
        return ob::PlannerStatus::EXACT_SOLUTION;
    }

    void clear() override
    {
        Planner::clear();
        planner_ = nullptr;
    }

    void getPlannerData(ob::PlannerData &data) const override
    {
        Planner::getPlannerData(data);
        if (!planner_)
            return;
        ob::ScopedState<> s(si_->getStateSpace()), parent(si_->getStateSpace());
        const int32_t n = gmmrrt_planner_node_count(planner_);
        for (int32_t i = 0; i < n; ++i) {
            double x, y, px, py, cost;
            int32_t pi;
            if (gmmrrt_planner_node(planner_, i, &x, &y, &pi, &cost) != GMMRRT_OK)
                continue;
            s[0] = x;
            s[1] = y;
            if (pi < 0) {
                data.addStartVertex(ob::PlannerDataVertex(s.get(), i));
                continue;
            }
            int32_t unused;
            double unused_cost;
            if (gmmrrt_planner_node(planner_, pi, &px, &py, &unused, &unused_cost) != GMMRRT_OK)
                continue;
            parent[0] = px;
            parent[1] = py;
            data.addEdge(ob::PlannerDataVertex(parent.get(), pi), ob::PlannerDataVertex(s.get(), i));
        }
    }

private:
    std::string objective_;
    const TaskSettings *task_;
    int32_t max_nodes_;
    uint64_t seed_;
    std::vector<unsigned char> block_;
    gmmrrt_planner_t *planner_ = nullptr;
    std::atomic<long long> iterations_{0};
    std::atomic<double> best_cost_{0.0};
};

} // namespace

bool write_ompl_benchmark_log(const std::string &path, const std::string &objective, const TaskSettings *task,
                              double time_ms, unsigned runs, int32_t max_nodes, uint64_t seed, std::string *err)
{
    ob::SpaceInformationPtr si = make_space_information();
    og::SimpleSetup ss(si);
    ob::ScopedState<> start(si->getStateSpace()), goal(si->getStateSpace());
    start[0] = kStartX;
    start[1] = kStartY;
    goal[0] = kGoalX;
    goal[1] = kGoalY;
    ss.setStartAndGoalStates(start, goal, kGoalTolerance);
    ss.setOptimizationObjective(make_objective(si, objective, task));

    ompl::tools::Benchmark b(ss, "gmmrrt vs OMPL RRTstar: disc r=2, " + objective + " objective");
    b.addExperimentParameter("objective", "STRING", objective);
    b.addPlanner(std::make_shared<og::RRTstar>(si));
    b.addPlanner(std::make_shared<GmmrrtOmplPlanner>(si, objective, task, max_nodes, seed));
    ompl::tools::Benchmark::Request req;
    req.maxTime = time_ms / 1000.0;
    req.maxMem = 100000.0;
    req.runCount = runs;
    req.displayProgress = false;
    req.simplify = false;
    req.saveConsoleOutput = false; /* else OMPL leaves ompl_<host>_<date>.console in the working directory */
    b.benchmark(req);
    if (!b.saveResultsToFile(path.c_str())) {
        *err = "cannot write the OMPL benchmark log '" + path + "'";
        return false;
    }
    return true;
}

} // namespace gmmrrt_bench
