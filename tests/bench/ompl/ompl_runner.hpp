/*
 * ompl_runner.hpp - the benchmark problem (problem.hpp) solved by OMPL's RRTstar with its
 * default settings; the task objective is an ompl::base::StateCostIntegralObjective whose
 * state cost calls our C task cost (gmm.h), so both planners integrate the same function.
 */
#ifndef GMMRRT_BENCH_OMPL_RUNNER_HPP
#define GMMRRT_BENCH_OMPL_RUNNER_HPP

#include <memory>
#include <string>

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/objectives/StateCostIntegralObjective.h>

#include "problem.hpp"
#include "trial.hpp"

namespace gmmrrt_bench {

/* Validity: the point robot is outside the disc. Bounds are the state space's. */
class DiscValidityChecker : public ompl::base::StateValidityChecker {
public:
    explicit DiscValidityChecker(const ompl::base::SpaceInformationPtr &si) : StateValidityChecker(si) {}
    bool isValid(const ompl::base::State *state) const override;
};

/* State cost w_length + w_task c(f(x)) integrated along motions at the motion-check
 * resolution (trapezoid rule, StateCostIntegralObjective with interpolation on). */
class GmmTaskCostObjective : public ompl::base::StateCostIntegralObjective {
public:
    GmmTaskCostObjective(const ompl::base::SpaceInformationPtr &si, const TaskSettings &task);
    ompl::base::Cost stateCost(const ompl::base::State *s) const override;

private:
    TaskSettings task_;
};

/* The space information of the problem (bounds, validity checker), set up. */
ompl::base::SpaceInformationPtr make_space_information();

/* The objective for "length" or "task" (task must be non-NULL for "task"). */
ompl::base::OptimizationObjectivePtr make_objective(const ompl::base::SpaceInformationPtr &si,
                                                    const std::string &objective, const TaskSettings *task);

/* One timed run of OMPL RRTstar (fresh planner, default settings) for time_ms; with
 * informed, RRTstar's informed sampling switched on (planner "ompl_rrtstar_informed";
 * path-length objective only). */
TrialResult run_ompl_trial(const std::string &objective, const TaskSettings *task, double time_ms, int trial,
                           bool informed = false);

} // namespace gmmrrt_bench

#endif
