"""bench.stats: the benchmark harness's arithmetic on hand-made trial records.

Oracles are computed by hand in each test from the records it builds: medians that keep
"never" as infinity, best cost read off a curve, time to a cost, paired ratios, the social
summary's converged cost, and the target judgement (met / not met / not run).
"""
import json
import math

import pytest

from gmmrrt_tools.bench.planner import summarize_ompl, summarize_social
from gmmrrt_tools.bench.report import evaluate_targets
from gmmrrt_tools.bench.stats import INF, clean, cost_at, median, quantile, ratio, time_to_cost

CURVE = [[0.5, 10, 20.0], [2.0, 40, 15.0], [9.0, 200, 12.0], [50.0, 900, 11.0]]


def test_median_counts_never_as_the_largest_value():
    assert median([3.0, 1.0, 2.0]) == 2.0
    assert median([1.0, INF, INF]) == INF
    assert median([1.0, 2.0, INF]) == 2.0
    assert math.isnan(median([]))


def test_quantile_is_nearest_rank():
    vals = [float(v) for v in range(1, 11)]
    assert quantile(vals, 0.9) == 9.0
    assert quantile(vals, 1.0) == 10.0
    assert quantile([5.0], 0.5) == 5.0


def test_cost_at_reads_the_best_cost_so_far():
    assert cost_at(CURVE, 0.1) == INF
    assert cost_at(CURVE, 0.5) == 20.0
    assert cost_at(CURVE, 8.99) == 15.0
    assert cost_at(CURVE, 1e9) == 11.0


def test_time_to_cost_is_the_first_time_at_or_below():
    assert time_to_cost(CURVE, 15.0) == 2.0
    assert time_to_cost(CURVE, 14.9) == 9.0
    assert time_to_cost(CURVE, 10.0) == INF


def test_ratio_refuses_missing_or_zero_peers():
    assert ratio(6.0, 3.0) == 2.0
    assert ratio(1.0, 0.0) is None
    assert ratio(INF, 1.0) is None
    assert ratio(None, 1.0) is None


def test_clean_makes_strict_json():
    text = json.dumps(clean({"a": INF, "b": [math.nan, 1.5], "c": {"d": -INF}}), allow_nan=False)
    assert json.loads(text) == {"a": None, "b": [None, 1.5], "c": {"d": None}}


def _trial(planner, trial, iterations, time_ms, history, first=None, cpu_ms=None):
    first = history[0][0] if first is None and history else first
    return {"planner": planner, "objective": "length", "trial": trial, "seed": trial, "setup_ms": 0.1,
            "time_ms": time_ms, "cpu_ms": cpu_ms, "iterations": iterations, "nodes": iterations // 2,
            "first_solution_ms": -1 if first is None else first,
            "first_solution_iteration": -1 if first is None else 1,
            "final_cost": history[-1][2] if history else -1, "status": "ok", "history": history}


def test_ompl_summary_ratios_and_reference_cost():
    # OMPL: 1000 and 3000 iterations in 1 s; ours 10x each. OMPL's 1 s costs 12 and 14 -> median 13.
    o = [_trial("ompl_rrtstar", 0, 1000, 1000.0, [[5.0, 10, 20.0], [500.0, 500, 12.0]], cpu_ms=500.0),
         _trial("ompl_rrtstar", 1, 3000, 1000.0, [[7.0, 10, 20.0], [600.0, 500, 14.0]], cpu_ms=500.0)]
    g = [_trial("gmmrrt_rrtstar", 0, 10000, 1000.0, [[0.5, 5, 19.0], [4.0, 50, 12.5], [40.0, 500, 11.0]],
                cpu_ms=250.0),
         _trial("gmmrrt_rrtstar", 1, 30000, 1000.0, [[1.5, 5, 19.0], [8.0, 50, 13.0]], cpu_ms=250.0)]
    s = summarize_ompl(o + g, 1000.0)
    po, pg = s["planners"]["ompl_rrtstar"], s["planners"]["gmmrrt_rrtstar"]
    assert po["iterations_per_s_median"] == pytest.approx(2000.0)
    assert pg["iterations_per_s_median"] == pytest.approx(20000.0)
    assert s["ratios"]["iterations_per_s"] == pytest.approx(10.0)
    assert s["ratios"]["iterations_per_s_paired_median"] == pytest.approx(10.0)
    # per CPU-second: OMPL 2000 and 6000 -> 4000; ours 40000 and 120000 -> 80000
    assert po["iterations_per_cpu_s_median"] == pytest.approx(4000.0)
    assert s["ratios"]["iterations_per_cpu_s"] == pytest.approx(20.0)
    assert pg["cpu_share_median"] == pytest.approx(0.25)
    assert po["first_solution_ms_median"] == pytest.approx(6.0)
    assert pg["first_solution_ms_median"] == pytest.approx(1.0)
    assert po["cost_at_ms_median"]["10"] == 20.0
    assert pg["cost_at_ms_median"]["10"] == pytest.approx((12.5 + 13.0) / 2)
    ref = s["ompl_reference"]
    assert ref["ompl_median_cost"] == pytest.approx(13.0)
    # ours reach 13: trial 0 at 4 ms (12.5), trial 1 at 8 ms (13.0) -> median 6 ms; 1000 / 6
    assert ref["ours_median_time_to_that_cost_ms"] == pytest.approx(6.0)
    assert ref["speedup"] == pytest.approx(1000.0 / 6.0)
    assert ref["ours_reached"] == 2


def test_ompl_summary_extra_pairs():
    # OMPL default 1000 it/s, reaching 13 at 1 s; OMPL informed 2000 it/s, reaching 11 at 1 s;
    # ours plain 5000 it/s reaching 13 at 100 ms; ours 10000 it/s reaching 11 at 10 ms.
    o = [_trial("ompl_rrtstar", 0, 1000, 1000.0, [[500.0, 500, 13.0]])]
    oi = [_trial("ompl_rrtstar_informed", 0, 2000, 1000.0, [[500.0, 500, 11.0]])]
    gp = [_trial("gmmrrt_rrtstar_plain", 0, 5000, 1000.0, [[100.0, 500, 13.0]])]
    g = [_trial("gmmrrt_rrtstar", 0, 10000, 1000.0, [[1.0, 5, 13.0], [10.0, 50, 11.0]])]
    s = summarize_ompl(o + oi + gp + g, 1000.0)
    assert s["ratios"]["iterations_per_s"] == pytest.approx(10.0)
    assert s["ompl_reference"]["speedup"] == pytest.approx(1000.0)
    plain = s["pairs"]["plain_vs_ompl"]
    assert plain["ratios"]["iterations_per_s"] == pytest.approx(5.0)
    assert plain["reference"]["speedup"] == pytest.approx(10.0)
    inf = s["pairs"]["ours_vs_ompl_informed"]
    assert inf["ratios"]["iterations_per_s"] == pytest.approx(5.0)
    assert inf["reference"]["ompl_median_cost"] == pytest.approx(11.0)
    assert inf["reference"]["speedup"] == pytest.approx(100.0)
    # without the extra planners there are no pairs
    assert "pairs" not in summarize_ompl(o + g, 1000.0)


def test_ompl_summary_without_solutions_reports_never():
    o = [_trial("ompl_rrtstar", 0, 100, 50.0, [], first=None)]
    g = [_trial("gmmrrt_rrtstar", 0, 1000, 50.0, [], first=None)]
    s = summarize_ompl(o + g, 50.0)
    assert s["planners"]["ompl_rrtstar"]["first_solution_ms_median"] == INF
    assert s["planners"]["ompl_rrtstar"]["solved"] == 0
    assert s["ompl_reference"]["speedup"] is None
    assert s["ompl_reference"]["ours_reached"] == 0


def test_social_summary_converged_cost_and_within_one_percent():
    rs = [_trial("gmmrrt_gmm_rrtstar", 0, 1000, 100.0, [[0.4, 3, 12.0], [30.0, 300, 10.05]]),
          _trial("gmmrrt_gmm_rrtstar", 1, 1000, 100.0, [[0.8, 3, 11.0], [60.0, 600, 10.0]]),
          _trial("gmmrrt_gmm_rrtstar", 2, 1000, 100.0, [[2.0, 3, 10.5]])]
    s = summarize_social(rs, 100.0)
    assert s["first_solution_ms_median"] == pytest.approx(0.8)
    assert s["converged_cost"] == pytest.approx(10.0)
    # within 1.01 * 10 = 10.1: trial 0 at 30 ms, trial 1 at 60 ms, trial 2 never -> median 60
    assert s["within_1pct_ms_median"] == pytest.approx(60.0)
    assert s["within_1pct_reached"] == 2
    # own final: 30, 60 and 2 ms -> median 30
    assert s["within_1pct_of_own_final_ms_median"] == pytest.approx(30.0)
    assert s["speedup_vs_paper"] == pytest.approx(1500.0 / 0.8)


def test_targets_are_met_not_met_or_not_run():
    res = {"ompl": {"length": {"ratios": {"iterations_per_s": 31.0},
                               "ompl_reference": {"time_ms": 1000.0, "speedup": 29.0, "ours_reached": 3}}},
           "memory": {"bytes_per_node": 44.0, "alloc_counter_works": True,
                      "rrtstar_disc": {"set_problem_allocs": 0, "run_allocs": 0},
                      "gmm_rrtstar_avoid": {"set_problem_allocs": 0, "run_allocs": 1}},
           "learner": {"fit": {"speedup": 25.0, "log_likelihood_gap": -0.01, "n": 10, "k": 2}}}
    by = {t["name"].split(" (")[0].split(":")[0]: t["status"] for t in evaluate_targets(res)}
    assert by["iterations/s vs OMPL RRTstar"] == "met"
    assert by["time to OMPL's 1,000 ms cost"] == "not met"
    assert by["bytes per node"] == "met"
    assert by["allocations during planning"] == "not met"
    assert by["learner fit vs scikit-learn"] == "not met"  # fast, but a worse log-likelihood
    assert by["social avoid"] == "not run"
    assert by["BIC sweep K=1..30 vs scikit-learn"] == "not run"


def test_same_iteration_targets_judge_both_of_our_settings():
    si = {"n": 200000, "k": 19, "em_iterations": 16,
          "speedup_vs_armadillo_2_cpu": 21.0, "speedup_vs_armadillo_2": 19.0, "log_likelihood_gap_vs_armadillo_2": 0.4,
          "second_core_ours": 1.8, "speedup_vs_sklearn_1_cpu": 61.0, "speedup_vs_sklearn_1": 60.5,
          "log_likelihood_gap_vs_sklearn": -0.002,
          "speedup_vs_armadillo_2_cpu_one_start": 19.0, "speedup_vs_armadillo_2_one_start": 18.0,
          "log_likelihood_gap_vs_armadillo_2_one_start": 0.4, "second_core_ours_one_start": 1.5,
          "speedup_vs_sklearn_1_cpu_one_start": 70.0, "speedup_vs_sklearn_1_one_start": 70.0,
          "log_likelihood_gap_vs_sklearn_one_start": 0.0, "second_core_armadillo": 1.1}
    rows = [t for t in evaluate_targets({"learner": {"same_iterations": si}}) if "EM iterations" in t["name"]]
    defaults = [t["status"] for t in rows if "defaults" in t["name"]]
    one = [t["status"] for t in rows if "like-for-like" in t["name"]]
    # Armadillo (CPU time, LL better), second core, scikit-learn (fast enough but a worse LL).
    assert defaults == ["met", "met", "not met"]
    assert one == ["not met", "not met", "met"]
    # The rows say which statistic they compare: medians over the same seeds on every side.
    assert all("medians over 25 seeds each side (seeds 1-25)" in t["name"]
               for t in evaluate_targets({"learner": {"same_iterations": dict(si, seeds=list(range(1, 26)))}})
               if "EM iterations" in t["name"])
    skipped = evaluate_targets({"learner": {"same_iterations": {"skipped": "no Armadillo"}}})
    assert {t["status"] for t in skipped if "EM iterations" in t["name"]} == {"not run"}
