"""bench.stats: the benchmark harness's arithmetic on hand-made trial records.

Oracles are computed by hand in each test from the records it builds: medians that keep
"never" as infinity, best cost read off a curve, time to a cost, paired ratios, the social
summary's converged cost, the all-planner comparison's medians (each budget over its own
run's trials, first paths from the first-path budget only) and the tables and target rows
written from them, and the target judgement (met / not met / not run).
"""
import json
import math
from pathlib import Path

import pytest

from gmmrrt_tools.bench.planner import BenchError, summarize_all_planners, summarize_ompl, summarize_social
from gmmrrt_tools.bench.learner import pair_span_ms, stage_medians
from gmmrrt_tools.bench.merge_sections import merge
from gmmrrt_tools.bench.report import _planner_targets_summary, evaluate_targets, second_core_stages, write_markdown
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


def test_the_pair_of_fits_is_timed_from_the_first_start_to_the_last_end():
    together = [{"fit_start_monotonic_s": 10.0, "fit_end_monotonic_s": 10.080},
                {"fit_start_monotonic_s": 10.001, "fit_end_monotonic_s": 10.075}]
    span, overlap = pair_span_ms(together)
    assert span == pytest.approx(80.0) and overlap == pytest.approx(74.0)
    # Staggered fits that never ran at once: their span counts both, and no overlap.
    apart = [{"fit_start_monotonic_s": 1.0, "fit_end_monotonic_s": 1.05},
             {"fit_start_monotonic_s": 1.06, "fit_end_monotonic_s": 1.11}]
    span, overlap = pair_span_ms(apart)
    assert span == pytest.approx(110.0) and overlap == 0.0


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
    # The second-core rows show the machine's own second-CPU gain beside ours, or say it is missing.
    core_rows = [t for t in evaluate_targets({"learner": {"same_iterations": dict(si, second_core_machine=1.234)}})
                 if "second core" in t["name"]]
    assert len(core_rows) == 2 and all("two 1-thread one-start fits at once: 1.23x" in t["value_text"] for t in core_rows)
    assert all("two 1-thread one-start fits at once: -" in t["value_text"] for t in rows if "second core" in t["name"])
    skipped = evaluate_targets({"learner": {"same_iterations": {"skipped": "no Armadillo"}}})
    assert {t["status"] for t in skipped if "EM iterations" in t["name"]} == {"not run"}


def test_the_fit_stages_are_medians_per_stage_and_their_second_core_ratios():
    runs = [{"stages_ms": {"prepare": p, "candidates": c, "converge": v}}
            for p, c, v in ((8.0, 40.0, 12.0), (9.0, 30.0, 10.0), (7.0, 50.0, 11.0))]
    assert stage_medians(runs) == {"prepare": 8.0, "candidates": 40.0, "converge": 11.0}
    # A run from a bench binary that did not time its stages: no median rather than a wrong one.
    assert stage_medians(runs + [{"stages_ms": {"prepare": None}}])["prepare"] is None
    si = {"ours_1": {"stages_ms_median": {"prepare": 8.0, "candidates": 40.0, "converge": 11.0}},
          "ours_2": {"stages_ms_median": {"prepare": 5.0, "candidates": 20.0, "converge": 5.5}},
          "ours_one_1": {"stages_ms_median": {"prepare": 8.0, "candidates": 50.0, "converge": 0.01}},
          "ours_one_2": {"stages_ms_median": {"prepare": 4.0, "candidates": 26.0, "converge": 0.01}}}
    lines = second_core_stages(si)
    assert lines[0] == ("- ours (defaults), the fit's stages, medians on 1 -> 2 threads: prepare 8.0 ms -> 5.0 ms "
                        "(1.60x); candidates 40.0 ms -> 20.0 ms (2.00x); converge 11.0 ms -> 5.5 ms (2.00x)")
    # A stage that takes no time (one start does its EM steps among the candidates) has no ratio.
    assert lines[1].endswith("candidates 50.0 ms -> 26.0 ms (1.92x); converge under 0.05 ms")
    assert second_core_stages({"ours_1": {}, "ours_2": {}}) == []


# ------------------------------------------------------------------ all planners (gmmrrt-bench-all)
def _all_rec(planner, budget, trial, cost, first, setup, problem="MAP"):
    return {"problem": problem, "planner": planner, "trial": trial, "budget_ms": budget, "setup_ms": setup,
            "first_ms": first, "cost": cost}


def _all_planner_records():
    """A seeded run (15 trials at 1, 10, 100 ms) and a long run (3 trials at 1000 ms), as the two
    runs of run_all_planners write them. Ours has no path at 1 ms in trials 0 and 1 (seeds 1 and 2):
    the first three seeds alone would give a median of 'none' at 1 ms, the 15 give 10.9."""
    recs = []
    for t in range(15):
        for b in (1.0, 10.0, 100.0):
            ours_cost = (None if t < 2 else 10.0 + 0.1 * t) if b == 1.0 else 10.0 - 0.01 * t
            # First paths and set-up at 1 and 10 ms are far off: only the 100 ms runs may count.
            first, setup = (0.01 * (t + 1), 0.001 * (t + 1)) if b == 100.0 else (5.0, 1.0)
            recs.append(_all_rec("gmmrrt", b, t, ours_cost, first, setup))
            # RRTConnect finds a path in trial 14 without reporting when (left out of its median).
            recs.append(_all_rec("RRTConnect", b, t, 11.0 if b == 1.0 else 9.95,
                                 (None if t == 14 else 0.1 * (t + 1)) if b == 100.0 else 7.0, 0.1))
    for t, (ours, peer) in enumerate(((10.5, 10.8), (10.4, 10.7), (10.6, 10.9))):
        recs.append(_all_rec("gmmrrt", 1000.0, t, ours, 9.0, 1.0))
        recs.append(_all_rec("RRTConnect", 1000.0, t, peer, 9.0, 1.0))
    return recs


def test_all_planner_costs_are_medians_over_each_budgets_own_trials():
    pr = summarize_all_planners(_all_planner_records())["MAP"]
    c = pr["cost"]
    assert {b: e["trials"] for b, e in c.items()} == {"1": 15, "10": 15, "100": 15, "1000": 3}
    # 1 ms: ours 13 paths 10.2..11.4 and two 'none' (largest): the 8th of 15 is 10.9; RRTConnect 11.0.
    assert c["1"]["ours"] == pytest.approx(10.9)
    assert c["1"]["best_ompl"] == 11.0 and c["1"]["best_ompl_planner"] == "RRTConnect"
    assert c["1"]["met"] is True
    # 10 ms: ours 10.00..9.86, median 9.93 (trial 7); RRTConnect 9.95: met.
    assert c["10"]["ours"] == pytest.approx(9.93) and c["10"]["met"] is True
    # 1000 ms: the long run's three trials, 10.5 against 10.8.
    assert c["1000"]["ours"] == pytest.approx(10.5) and c["1000"]["best_ompl"] == pytest.approx(10.8)


def test_all_planner_first_paths_come_from_the_first_path_budget_only():
    pr = summarize_all_planners(_all_planner_records())["MAP"]
    assert pr["first_trials"] == 15
    assert pr["first_ms"] == pytest.approx(0.08)  # 0.01..0.15, the 8th
    # RRTConnect: trials 0..13 report 0.1..1.4 (trial 14 a path, no time): median (0.7 + 0.8) / 2
    assert pr["fastest_ompl"] == "RRTConnect"
    assert pr["fastest_ompl_first_ms"] == pytest.approx(0.75)
    assert pr["first_ratio"] == pytest.approx(0.08 / 0.75)
    rows = {r["planner"]: r for r in pr["table"]}
    assert [r["planner"] for r in pr["table"]] == ["gmmrrt", "RRTConnect"]  # the program's order
    assert rows["gmmrrt"]["setup_ms"] == pytest.approx(0.008)
    assert rows["gmmrrt"]["first_ms"] == pr["first_ms"]
    assert rows["gmmrrt"]["cost"]["1"] == pr["cost"]["1"]["ours"]


def test_all_planner_runs_without_a_path_count_as_never():
    """A planner with a path in one run of fifteen has no median first path (the other fourteen
    count as never), so it cannot be the fastest on that one lucky run; and a budget where neither
    side has a path is not a met target."""
    recs = _all_planner_records()
    for t in range(15):
        for b in (1.0, 10.0, 100.0):
            lucky = t == 0 and b == 100.0
            recs.append(_all_rec("ABITstar", b, t, 9.0 if lucky else None, 0.001 if lucky else None, 0.1))
    for t in range(3):
        recs.append(_all_rec("ABITstar", 1000.0, t, None, None, 0.1))
    pr = summarize_all_planners(recs)["MAP"]
    assert pr["first_ms_by_planner"]["ABITstar"] is None  # never, in 14 of 15
    assert pr["fastest_ompl"] == "RRTConnect"
    none = [_all_rec(p, b, t, None, None, 0.1) for p in ("gmmrrt", "RRTConnect") for b in (1.0, 10.0, 100.0)
            for t in range(15)]
    c = summarize_all_planners(none)["MAP"]["cost"]["1"]
    assert c["met"] is False


def test_all_planner_summary_refuses_two_runs_on_one_budget_and_uneven_trials():
    recs = _all_planner_records()
    with pytest.raises(BenchError, match="budget 1000 ms, trial 0: the runs' budgets must be disjoint"):
        summarize_all_planners(recs + [_all_rec("gmmrrt", 1000.0, 0, 10.0, 1.0, 1.0)])
    with pytest.raises(BenchError, match="budget 1000 ms: the planners ran different numbers of trials"):
        summarize_all_planners(recs + [_all_rec("gmmrrt", 1000.0, 3, 10.0, 1.0, 1.0)])


def test_all_planner_targets_and_tables_state_their_seeds_and_agree(tmp_path):
    problems = clean(summarize_all_planners(_all_planner_records()))
    runs = [{"role": "seeded", "trials": 15, "budgets_ms": [1.0, 10.0, 100.0], "seconds": 1.0, "command": "A"},
            {"role": "long", "trials": 3, "budgets_ms": [1000.0], "seconds": 1.0, "command": "B"}]
    res = {"planners": {"runs": runs, "first_path_budget_ms": 100.0, "first_seed": 1, "problems": problems,
                        "descriptions": {"MAP": "floor plan"}}}
    targets = {t["name"]: t for t in evaluate_targets(res) if t["name"].startswith("problem MAP")}
    for b in ("1", "10", "100"):
        name = f"problem MAP: best cost at {b} ms vs best OMPL (RRTConnect; medians over 15 seeds (1..15))"
        assert name in targets, sorted(targets)
    assert "problem MAP: best cost at 1000 ms vs best OMPL (RRTConnect; medians over 3 seeds (1..3))" in targets
    assert ("problem MAP: first path incl. set-up vs fastest OMPL (RRTConnect; medians over 15 seeds (1..15))"
            in targets)
    doc = tmp_path / "benchmarks.md"
    res["targets"] = evaluate_targets(res)
    write_markdown(res, doc, Path("results.json"))
    text = doc.read_text()
    lines = text.splitlines()
    head = lines.index("### Problem MAP (floor plan)")
    assert lines[head + 2] == ("Set-up and first path: medians over 15 seeds (1..15) at 100 ms; cost: at 1, 10 and "
                               "100 ms medians over 15 seeds (1..15), at 1000 ms medians over 3 seeds (1..3).")
    assert lines[head + 4] == ("| planner | set-up ms | first path incl. set-up ms | cost @ 1 ms (15 seeds) | "
                               "cost @ 10 ms (15 seeds) | cost @ 100 ms (15 seeds) | cost @ 1000 ms (3 seeds) |")
    # The scene-by-scene targets state the load of the run that measured the planners, also when
    # the section was carried over from an earlier run into a partial one (merge_sections).
    res.update(load_before=[1.0, 1.0, 1.0], load_after=[2.0, 2.0, 2.0])
    assert "(load [1.0, 1.0, 1.0] before, [2.0, 2.0, 2.0] after" in "\n".join(
        _planner_targets_summary(res, res["planners"]))
    full = dict(res, date_utc="d", host={"commit": "c", "nproc": 2}, load_before=[0.1, 0.2, 0.3],
                load_after=[0.4, 0.5, 0.6])
    partial = {"learner": {}, "date_utc": "e", "host": {"commit": "f", "nproc": 2}, "load_before": [1.0, 1.0, 1.0],
               "load_after": [2.0, 2.0, 2.0]}
    merged = merge(full, partial)
    assert merged["planners"] is full["planners"] and merged["carried_over"]["planners"]["commit"] == "c"
    assert "(load [0.1, 0.2, 0.3] before, [0.4, 0.5, 0.6] after" in "\n".join(
        _planner_targets_summary(merged, merged["planners"]))
    # Merged once more: the planners keep the run that measured them, not the one in between.
    again = merge(merged, dict(partial, date_utc="g", load_before=[3.0, 3.0, 3.0]))
    assert again["carried_over"]["planners"]["load_before"] == [0.1, 0.2, 0.3]
    ours = next(line for line in lines[head:] if line.startswith("| gmmrrt |")).split(" | ")
    # The table's cells are the figures the target rows judge (a reader sees one cost per cell).
    assert ours[1:3] == ["0.008", "0.080"]
    assert [float(v.strip(" |")) for v in ours[3:]] == [pytest.approx(problems["MAP"]["cost"][b]["ours"])
                                                        for b in ("1", "10", "100", "1000")]
    assert targets["problem MAP: best cost at 1 ms vs best OMPL (RRTConnect; medians over 15 seeds (1..15))"][
        "value_text"] == "10.9000 vs 11.0000"
    assert "at 1, 10 and 100 ms medians over 15 seeds (1..15), at 1000 ms medians over 3 seeds (1..3)" in text
