/*
 * ompl_runner.cpp - OMPL RRTstar (Karaman & Frazzoli 2011, OMPL 1.5) on the benchmark
 * problem, default planner settings. Time runs from the call to solve() (after setup());
 * the best-cost curve comes from the problem definition's intermediate-solution callback,
 * which RRTstar calls on every improvement; iterations are RRTstar::numIterations().
 */
#include "ompl_runner.hpp"

#include <chrono>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>

#include "gmmrrt/gmm.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace gmmrrt_bench {

using Clock = std::chrono::steady_clock;

static double ms_since(Clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

bool DiscValidityChecker::isValid(const ob::State *state) const
{
    const auto *s = state->as<ob::RealVectorStateSpace::StateType>();
    const double x = s->values[0], y = s->values[1];
    return x * x + y * y > kDiscRadius * kDiscRadius;
}

GmmTaskCostObjective::GmmTaskCostObjective(const ob::SpaceInformationPtr &si, const TaskSettings &task)
    : StateCostIntegralObjective(si, true), task_(task)
{
    description_ = "gmmrrt task cost (w_length + w_task c(f)) integral";
}

ob::Cost GmmTaskCostObjective::stateCost(const ob::State *state) const
{
    const auto *s = state->as<ob::RealVectorStateSpace::StateType>();
    double f[2];
    gmmrrt_features_from_xy(&task_.person, s->values[0], s->values[1], &f[0], &f[1]);
    return ob::Cost(task_.w_length + task_.w_task * gmmrrt_gmm_task_cost(task_.model, f, task_.delta));
}

ob::SpaceInformationPtr make_space_information()
{
    auto space = std::make_shared<ob::RealVectorStateSpace>(2);
    space->setBounds(kBoundLo, kBoundHi);
    auto si = std::make_shared<ob::SpaceInformation>(space);
    si->setStateValidityChecker(std::make_shared<DiscValidityChecker>(si));
    si->setup();
    return si;
}

ob::OptimizationObjectivePtr make_objective(const ob::SpaceInformationPtr &si, const std::string &objective,
                                            const TaskSettings *task)
{
    ob::OptimizationObjectivePtr obj;
    if (objective == "task")
        obj = std::make_shared<GmmTaskCostObjective>(si, *task);
    else
        obj = std::make_shared<ob::PathLengthOptimizationObjective>(si);
    obj->setCostThreshold(ob::Cost(0.0)); /* never "good enough": run the whole budget */
    return obj;
}

TrialResult run_ompl_trial(const std::string &objective, const TaskSettings *task, double time_ms, int trial,
                           bool informed)
{
    TrialResult r;
    r.planner = informed ? "ompl_rrtstar_informed" : "ompl_rrtstar";
    r.objective = objective;
    r.trial = trial;

    const Clock::time_point t_setup = Clock::now();
    ob::SpaceInformationPtr si = make_space_information();
    auto pdef = std::make_shared<ob::ProblemDefinition>(si);
    ob::ScopedState<> start(si->getStateSpace()), goal(si->getStateSpace());
    start[0] = kStartX;
    start[1] = kStartY;
    goal[0] = kGoalX;
    goal[1] = kGoalY;
    pdef->setStartAndGoalStates(start, goal, kGoalTolerance);
    pdef->setOptimizationObjective(make_objective(si, objective, task));
    auto planner = std::make_shared<og::RRTstar>(si);
    if (informed)
        planner->setInformedSampling(true);
    planner->setProblemDefinition(pdef);
    planner->setup();

    Clock::time_point t0;
    pdef->setIntermediateSolutionCallback(
        [&](const ob::Planner *, const std::vector<const ob::State *> &, const ob::Cost cost) {
            r.history.push_back({ms_since(t0), static_cast<int64_t>(planner->numIterations()), cost.value()});
        });
    r.setup_ms = ms_since(t_setup);

    const double cpu0 = thread_cpu_ms();
    t0 = Clock::now();
    const ob::PlannerStatus status = planner->solve(ob::timedPlannerTerminationCondition(time_ms / 1000.0));
    r.time_ms = ms_since(t0);
    r.cpu_ms = thread_cpu_ms() - cpu0;

    r.iterations = planner->numIterations();
    ob::PlannerData data(si);
    planner->getPlannerData(data);
    r.nodes = data.numVertices();
    r.status = status.asString();
    if (!r.history.empty()) {
        r.first_solution_ms = r.history.front().time_ms;
        r.first_solution_iteration = r.history.front().iterations;
    }
    if (pdef->hasExactSolution())
        r.final_cost = planner->bestCost().value();
    return r;
}

} // namespace gmmrrt_bench
