"""The real-data study: UPO avoid, UCY avoid and UCY approach with every standing person, each episode
re-planned and compared with what the human did (docs/experiments.md, "The real-data study").
"""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List, Optional, Tuple

import numpy as np

from gmmrrt_tools import metrics as M
from gmmrrt_tools import runner as R
from gmmrrt_tools import scenes as S

from .common import (
    CLEARANCE_M, Ctx, PERSON_RADIUS_M, ROBOT_RADIUS_M, UPO_APPROACH_SET, legend_handles,
    classify, fmt_ms, portable, record
)

# ==================================================================== real data

def real_dir(ctx: Ctx) -> Path:
    if ctx.real is None or not ctx.real.is_dir():
        raise RuntimeError(f"real data not found at {ctx.real} (set GMMRRT_REAL_DATA or --real-data to the folder "
                           f"of ../shared/data/real): the real-data experiment is skipped")
    return ctx.real


def _real_file(ctx: Ctx, name: str) -> str:
    f = real_dir(ctx) / name
    if not f.is_file():
        raise RuntimeError(f"{f}: missing (the real-data layout is ../shared/data/real/README.md)")
    return str(f)


def _push_out_all(p, people, min_dist_m: float, rounds: int = 4):
    """p pushed radially out of every person's min_dist_m disc (a few rounds: one push can land in
    a neighbour's disc)."""
    q = np.asarray(p, dtype=float)
    for _ in range(rounds):
        moved = False
        for (x, y, _yaw) in people:
            c = np.array([x, y])
            v = q - c
            n = float(np.linalg.norm(v))
            if n < min_dist_m:
                q = c + (v / n if n > 0 else np.array([1.0, 0.0])) * min_dist_m
                moved = True
        if not moved:
            break
    return (float(q[0]), float(q[1]))


def multi_person_scene(e: S.Episode, people, margin_m: float = 1.5) -> R.Scene:
    """The episode's problem with every standing person: bounds = the episode's (path and own person
    plus margin_m); people whose disc reaches into the bounds are passed (the others cannot touch a
    path inside), the episode's own person first; start and goal pushed out of every person's
    CLEARANCE_M disc."""
    base = S.episode_scene(e, margin_m=margin_m, clearance_m=CLEARANCE_M)
    b = base.bounds
    r = PERSON_RADIUS_M + ROBOT_RADIUS_M
    keep = [people[0]] + [p for p in people[1:] if b[0] - r <= p[0] <= b[2] + r and b[1] - r <= p[1] <= b[3] + r]
    start, goal = _push_out_all(base.start, keep, CLEARANCE_M), _push_out_all(base.goal, keep, CLEARANCE_M)
    return R.Scene(start, goal, [tuple(map(float, p)) for p in keep], b)


@dataclass
class RealSet:
    """One real-data study: its episodes, each one's scene (every standing person), and the planners."""
    name: str
    title: str
    what: str
    episodes: List[S.Episode]
    scenes: List[R.Scene]
    planners: List[Tuple[str, str, Optional[Path], Tuple[str, ...]]]  # label, planner, model, extra args
    approach: bool = False
    agreement: Tuple[float, float, int] = (math.nan, math.nan, 0)
    agreement_within: Optional[List[Tuple[float, int, float]]] = None  # realdata.side_agreement_within
    walkers: Optional[List[list]] = None  # per episode: (x, y, yaw, vx, vy) of the people walking at its start
    repeats: str = ""  # the reader's warnings: the episodes left out as repeats of an event listed before


# GMM-RRT* runs name their task cost (--task-cost) so a table does not depend on the CLI's default;
# DEFAULT_COST is that default (planner/src/config.c), the one the per-episode rankings follow.
DEFAULT_COST = "paper"
DEFAULT_LABEL = f"GMM-RRT* ({DEFAULT_COST} cost)"


def _avoid_planners(mdl: Path, one_person: bool) -> List[Tuple[str, str, Optional[Path], Tuple[str, ...]]]:
    """The avoid study's planners; mdl carries its background (gmmrrt-learn fit --background straight)."""
    d = ("--task-cost", DEFAULT_COST)
    out = [("GMM-RRT* (paper cost)", "gmm-rrt-star", mdl, ("--task-cost", "paper")),
           ("GMM-RRT* (inward cost)", "gmm-rrt-star", mdl, ("--task-cost", "inward"))]
    out.append(("GMM-RRT* (background cost)", "gmm-rrt-star", mdl, ("--task-cost", "background")))
    if one_person:
        out.append(("GMM-RRT* (paper cost, own person only)", "gmm-rrt-star", mdl, ("--task-cost", "paper", "ONE_PERSON")))
    out += [(f"GMM-RRT* ({DEFAULT_COST} cost, straight line's side)", "gmm-rrt-star", mdl, d + ("STRAIGHT_SIDE",)),
            (f"GMM-RRT* ({DEFAULT_COST} cost, human's side)", "gmm-rrt-star", mdl, d + ("HUMAN_SIDE",)),
            # What the background cost can reach once the side is right: the floor the side leaves.
            ("GMM-RRT* (background cost, human's side)", "gmm-rrt-star", mdl, ("--task-cost", "background", "HUMAN_SIDE")),
            # The same floor without a model: what the side alone is worth, so the model's share is visible.
            ("RRT* (human's side)", "rrt-star", None, ("HUMAN_SIDE",)),
            ("RRT*", "rrt-star", None, ())]
    return out


def _limit(ctx: Ctx, eps: list) -> list:
    n = ctx.s.real_max_episodes
    return eps[:: max(1, len(eps) // n)][:n] if n else eps


def _k_suffix(ctx: Ctx) -> str:
    return f"_k{ctx.real_k}" if ctx.real_k else ""


def _study_episodes(ctx: Ctx, ep_csv: str, idx: str) -> Tuple[list, str]:
    """Every episode of a study, with its split and index row (the learner's reader, which reads an event
    listed twice once and names the repeat), after checking that each has a standing person and that the
    training and evaluation splits exist. Returns the episodes and the reader's warnings (also printed on
    stderr), for the report."""
    from gmmrrt_tools import realdata as RD

    said: List[str] = []
    every = S.read_episodes(ep_csv, index=idx, warnings=said)
    for w in said:
        print(w, file=sys.stderr)
    RD._require_person(ep_csv, every)
    RD.require_split(idx, ctx.train_split, every)
    RD.require_split(idx, ctx.split, every)
    return every, "".join(w + "\n" for w in said)


def real_upo_avoid(ctx: Ctx) -> RealSet:
    from gmmrrt_tools import realdata as RD

    s = ctx.s
    ep_csv, idx = _real_file(ctx, "upo_avoid_episodes.csv"), _real_file(ctx, "upo_avoid_index.csv")
    every, repeats = _study_episodes(ctx, ep_csv, idx)
    mdl = R.fit_model(ctx.work / "models" / f"upo_avoid_{ctx.train_split}_all_bg{_k_suffix(ctx)}.gmm", "avoid", [ep_csv],
                      homotopy="all", k=ctx.real_k, seed=s.seed, index=idx, split=ctx.train_split, bin_dir=ctx.bin_dir,
                      background=True)
    people = RD.upo_people(idx, every)
    eps = _limit(ctx, [e for e in every if e.split == ctx.split])
    return RealSet("real_upo_avoid", f"Real data: UPO avoid, learned on the {ctx.train_split} split, evaluated on the "
                   f"{ctx.split} split, every standing person given",
                   f"Avoid model (all homotopies, features) fitted by `gmmrrt-learn fit --index upo_avoid_index.csv "
                   f"--split {ctx.train_split}` on $GMMRRT_REAL_DATA/upo_avoid_episodes.csv. Each of the {len(eps)} "
                   f"{ctx.split} episodes is re-planned from the mover's first to its last position with every standing "
                   "person of its recording (the index's scene column: the persons of all episodes of that recording), "
                   "its own person first, and compared with what the human drove.",
                   eps, [multi_person_scene(e, people[e.episode_id]) for e in eps],
                   _avoid_planners(mdl, one_person=True),
                   agreement=RD.human_side_agreement(every, lambda e: e.meta["scene"]),
                   agreement_within=RD.side_agreement_within(every, lambda e: e.meta["scene"]), repeats=repeats)


def real_ucy_avoid(ctx: Ctx) -> RealSet:
    from gmmrrt_tools import realdata as RD

    s = ctx.s
    ep_csv, idx = _real_file(ctx, "ucy_avoid_episodes.csv"), _real_file(ctx, "ucy_index.csv")
    tracks = _real_file(ctx, "ucy_tracks.csv")
    every, repeats = _study_episodes(ctx, ep_csv, idx)
    mdl = R.fit_model(ctx.work / "models" / f"ucy_avoid_{ctx.train_split}_all_bg{_k_suffix(ctx)}.gmm", "avoid", [ep_csv],
                      homotopy="all", k=ctx.real_k, seed=s.seed, index=idx, split=ctx.train_split, bin_dir=ctx.bin_dir,
                      background=True)
    eps = _limit(ctx, [e for e in every if e.split == ctx.split])
    people = RD.ucy_people(tracks, idx, eps, every)
    scenes = [multi_person_scene(e, people[e.episode_id]) for e in eps]
    # The crowd a planner would predict, without the walker's own group: a group walks as one, so the
    # robot in one member's place walks with the others rather than past them (realdata.walks_with).
    walkers = RD.ucy_walkers(tracks, idx, eps, {e.episode_id: sc.bounds for e, sc in zip(eps, scenes)},
                             exclude_group=True)
    planners = _avoid_planners(mdl, one_person=False)
    # The crowd: the same planners given everyone walking at the episode's start (constant-velocity
    # prediction), to see whether the people the standing-person models ignore explain the humans.
    planners += [("GMM-RRT* (paper cost, walking people given)", "gmm-rrt-star", mdl, ("--task-cost", "paper", "WALKERS")),
                 ("GMM-RRT* (background cost, walking people given)", "gmm-rrt-star", mdl,
                  ("--task-cost", "background", "WALKERS")),
                 ("RRT* (walking people given)", "rrt-star", None, ("WALKERS",))]
    return RealSet("real_ucy_avoid", f"Real data: UCY avoid, learned on the UCY {ctx.train_split} split, evaluated "
                   f"on the {ctx.split} split, every standing pedestrian given",
                   f"Avoid model (all homotopies, features) fitted by `gmmrrt-learn fit --index ucy_index.csv --split "
                   f"{ctx.train_split}` on $GMMRRT_REAL_DATA/ucy_avoid_episodes.csv (pedestrians walking past a standing "
                   f"one). Each of the {len(eps)} {ctx.split} episodes is re-planned with its standing person first and "
                   "every other pedestrian of the scene who stands (positions within "
                   f"{RD.STANDING_SPAN_M} m of their mean) through the whole episode (ucy_tracks.csv); their facing is "
                   "the annotated gaze when an episode is about them, else towards the walker.",
                   eps, scenes, planners,
                   agreement=RD.human_side_agreement(every, lambda e: (e.meta["scene"], e.meta["person_track"])),
                   agreement_within=RD.side_agreement_within(every, lambda e: (e.meta["scene"], e.meta["person_track"])),
                   walkers=[walkers[e.episode_id] for e in eps], repeats=repeats)


def real_ucy_approach(ctx: Ctx) -> RealSet:
    from gmmrrt_tools import realdata as RD

    s = ctx.s
    real = real_dir(ctx)
    gmms = Path(_real_file(ctx, "upo_approach_gmms.json"))
    ep_csv, idx = _real_file(ctx, "ucy_approach_episodes.csv"), _real_file(ctx, "ucy_index.csv")
    eps = S.read_episodes(ep_csv, index=idx)
    RD._require_person(ep_csv, eps)
    models = {}
    for e in eps:
        name = (e.meta or {}).get("upo_task") or ""
        if not name:
            continue
        if name not in models:
            out = ctx.work / "models" / f"upo_approach_{name}.gmm"
            if not out.exists():
                out.parent.mkdir(parents=True, exist_ok=True)
                R.learn(["import", "--json", str(gmms), "--set", UPO_APPROACH_SET, "--task-name", name, "--task",
                         "approach", "-o", str(out)], ctx.bin_dir)
            models[name] = out
    missing = [e.episode_id for e in eps if (e.meta or {}).get("upo_task") not in models]
    if missing:
        print(f"real ucy approach: {ep_csv}: episodes without an upo_task in {idx}, left out: {', '.join(missing)}",
              file=sys.stderr)
    eps = _limit(ctx, [e for e in eps if (e.meta or {}).get("upo_task") in models])
    people = RD.ucy_people(_real_file(ctx, "ucy_tracks.csv"), idx, eps, [])
    planners = []
    rs = RealSet("real_ucy_approach", "Real data: the lab's published approach models against the UCY approach episodes",
                 f"{gmms.name} (set {UPO_APPROACH_SET}; its two-homotopy mixtures, priors summing to 2, are imported as the "
                 "equal-weight union) imported with `gmmrrt-learn import`, one model per approach direction (the index's "
                 f"upo_task column); all {len(eps)} UCY approach episodes are held-out data for these models (learned by "
                 "the UPO lab on their robot data). Every standing pedestrian of the scene is given (as for UCY avoid), "
                 "the approached one is the target. Final heading error = angle between the path's last segment and "
                 "the bearing to the person.", eps, [multi_person_scene(e, people[e.episode_id]) for e in eps],
                 planners, approach=True)
    rs.planners = [("GMM-RRT* (paper cost)", "gmm-rrt-star", None, ("--task-cost", "paper")),
                   ("GMM-RRT* (inward cost)", "gmm-rrt-star", None, ("--task-cost", "inward")), ("RRT*", "rrt-star", None, ())]
    rs.models = models  # type: ignore[attr-defined]
    del real
    return rs


def _real_jobs(ctx: Ctx, rs: RealSet):
    from gmmrrt_tools import realdata as RD

    jobs = []
    for k, (e, scene) in enumerate(zip(rs.episodes, rs.scenes)):
        seed = ctx.s.seed + k
        for label, planner, mdl, extra in rs.planners:
            sc, args = scene, [a for a in extra if a not in ("HUMAN_SIDE", "ONE_PERSON", "STRAIGHT_SIDE", "WALKERS")]
            if "WALKERS" in extra and rs.walkers is not None:
                for w in rs.walkers[k]:
                    args += ["--person", ",".join(repr(float(v)) for v in w)]
                # The robot keeps the walker's own pace, so the prediction times the crowd as the human met it.
                dur = float(e.t[-1] - e.t[0])
                args += ["--nominal-speed", repr(M.path_length(e.xy) / dur if dur > 0 else 0.5)]
            if "ONE_PERSON" in extra:
                sc = R.Scene(scene.start, scene.goal, scene.people[:1], scene.bounds)
            if "HUMAN_SIDE" in extra:
                args += ["--side", RD.side_of_sweep(e.xy, e.person), "--side-person", "0"]
            if "STRAIGHT_SIDE" in extra:  # the default choice rule: the side the segment start-goal passes on
                args += ["--side", RD.side_of_sweep(np.array([sc.start, sc.goal]), e.person), "--side-person", "0"]
            if rs.approach:
                mdl = rs.models[e.meta["upo_task"]] if planner == "gmm-rrt-star" else None  # type: ignore[attr-defined]
                args += ["--task", "approach", "--target-person", "0"] if planner == "gmm-rrt-star" else []
            bias = ctx.s.bias if planner == "gmm-rrt-star" else None
            jobs.append(({"set": rs.name, "episode": e.episode_id, "planner": label, "k": k,
                          "people": len(sc.people)}, ctx.plan(sc, planner, seed, mdl, None, bias, args), seed))
    return jobs


def _episode_metrics(rs: RealSet, k: int, path, approach: bool) -> dict:
    e = rs.episodes[k]
    people = rs.scenes[k].people
    out = {"tdm_m": M.tdm_pair(e.xy, path), "le": M.length_error_pair(e.xy, path),
           "min_dist_any_m": M.min_distance_to_people(path, people),
           "length_m": M.path_length(path), "smoothness_rad": M.smoothness(path)}
    if approach:
        end = M.approach_end(path, e.person)
        out.update(final_dist_m=end.final_distance_m, final_heading_err_deg=math.degrees(end.heading_error_rad))
    else:
        out["same_side"] = bool(M.same_homotopy(path, e.xy, e.person))
    return out


def _fmt_pm(vals, digits=3, scale=1.0):
    m_, s_ = M.mean_std([scale * v for v in vals])
    return fmt_ms(m_, s_, digits)


def _real_report(ctx: Ctx, rs: RealSet, results) -> None:
    from gmmrrt_tools import realdata as RD

    labels = [p[0] for p in rs.planners]
    per: Dict[str, List[Optional[dict]]] = {l: [None] * len(rs.episodes) for l in labels}
    paths: Dict[str, List[Optional[list]]] = {l: [None] * len(rs.episodes) for l in labels}
    records = []
    for tag, res in results:
        k = tag["k"]
        sc = rs.scenes[k] if "own person only" not in tag["planner"] else R.Scene(
            rs.scenes[k].start, rs.scenes[k].goal, rs.scenes[k].people[:1], rs.scenes[k].bounds)
        o = classify(res, sc)
        extra = {"outcome": o}
        if o == M.SUCCESS:
            extra.update(_episode_metrics(rs, k, res.path, rs.approach))
            paths[tag["planner"]][k] = res.path
            per[tag["planner"]][k] = extra
        records.append(record(tag, res, **extra))
    human = [_episode_metrics(rs, k, e.xy, rs.approach) for k, e in enumerate(rs.episodes)]
    n = len(rs.episodes)
    head = ("| planner | success | TDM vs human (m) | TDM, same side as the human (m) | TDM, other side (m) | same side | "
            "l_e (%) | closest to any person (m) | plans within 0.55 m of a person | length (m) |"
            if not rs.approach else
            "| planner | success | TDM vs human (m) | l_e (%) | closest to any person (m) | final dist. (m) | "
            "final heading err. (deg) | length (m) |")
    lines = [head, "|" + "---|" * head.count(" | ") + "---|"]
    hv = human
    if rs.approach:
        lines.append(f"| human (reference) | – | – | – | {_fmt_pm([h['min_dist_any_m'] for h in hv], 2)} | "
                     f"{_fmt_pm([h['final_dist_m'] for h in hv], 2)} | {_fmt_pm([h['final_heading_err_deg'] for h in hv], 1)} | "
                     f"{_fmt_pm([h['length_m'] for h in hv], 2)} |")
    else:
        close = sum(h["min_dist_any_m"] < 0.55 for h in hv)
        lines.append(f"| human (reference) | – | – | – | – | – | – | {_fmt_pm([h['min_dist_any_m'] for h in hv], 2)} | "
                     f"{close}/{n} | {_fmt_pm([h['length_m'] for h in hv], 2)} |")
    summary = {}
    for l in labels:
        ok = [m for m in per[l] if m is not None]
        tdm = [m["tdm_m"] for m in ok]
        summary[l] = (float(np.mean(tdm)) if tdm else math.nan)
        succ = f"{len(ok)}/{n}"
        if rs.approach:
            lines.append(f"| {l} | {succ} | {_fmt_pm(tdm)} | {_fmt_pm([m['le'] for m in ok], 1, 100)} | "
                         f"{_fmt_pm([m['min_dist_any_m'] for m in ok], 2)} | {_fmt_pm([m['final_dist_m'] for m in ok], 2)} | "
                         f"{_fmt_pm([m['final_heading_err_deg'] for m in ok], 1)} | {_fmt_pm([m['length_m'] for m in ok], 2)} |")
        else:
            same = [m for m in ok if m["same_side"]]
            other = [m for m in ok if not m["same_side"]]
            close = sum(m["min_dist_any_m"] < 0.55 - 1e-3 for m in ok)
            lines.append(f"| {l} | {succ} | {_fmt_pm(tdm)} | {_fmt_pm([m['tdm_m'] for m in same])} ({len(same)}) | "
                         f"{_fmt_pm([m['tdm_m'] for m in other])} ({len(other)}) | "
                         f"{100 * len(same) / max(1, len(ok)):.0f} % | {_fmt_pm([m['le'] for m in ok], 1, 100)} | "
                         f"{_fmt_pm([m['min_dist_any_m'] for m in ok], 2)} | {close}/{len(ok)} | "
                         f"{_fmt_pm([m['length_m'] for m in ok], 2)} |")
    md = ctx.header(rs.title, rs.what + " TDM = mean distance from the human's points to the planned polyline (eq. (2)); "
                    "'same side' = the plan passes the episode's person on the human's side (swept bearing, "
                    "metrics.same_homotopy); the TDM columns split by it (episodes in brackets). Closest to any person = "
                    f"the path's smallest distance to a standing person's centre (robot {ROBOT_RADIUS_M} m + person "
                    f"{PERSON_RADIUS_M} m = 0.55 m is contact).")
    ppl = [len(sc.people) for sc in rs.scenes]
    if rs.repeats:
        md += ("The learner's reader's warnings on this data. It reads each event once: an episode that repeats an "
               "earlier one (the same person and positions at the same times) is in neither the models' fit nor "
               "their evaluation, the side rules or the humans' agreement:\n\n" + "".join(f"- {l}\n" for l in portable(rs.repeats).splitlines())
               + "\n")
    md += (f"People per episode: {min(ppl)}–{max(ppl)} (mean {np.mean(ppl):.1f}); {sum(p > 1 for p in ppl)} of {n} "
           "episodes have more than one.\n\n")
    md += "\n".join(lines) + "\n"
    if not rs.approach:
        a, dist, pairs = rs.agreement
        default_same = [m["same_side"] for m in per[DEFAULT_LABEL] if m is not None]
        straight = [m["same_side"] for m in per[f"GMM-RRT* ({DEFAULT_COST} cost, straight line's side)"] if m is not None]
        md += (f"\nSide agreement: {DEFAULT_LABEL} (one plan, whichever side is cheapest) passes on the human's side in "
               f"{100 * np.mean(default_same):.0f} % of the episodes; the straight line's side (the side the segment "
               f"start-goal passes the person on, given as --side) in {100 * np.mean(straight):.0f} %; two humans in "
               f"nearly the same situation (each episode of the whole data set and the episode of another "
               f"recording/person with the nearest start and goal in the person frame, median {dist:.2f} m apart; "
               f"{pairs} pairs) pass on the same side in {100 * a:.0f} %.\n")
        md += _agreement_ceiling(rs)
        md += _side_limit(rs, per, labels)
    # per-episode table
    ep_lines = ["| episode | people | human side | human length / straight distance | " + " | ".join(f"{l}: TDM (m){'' if rs.approach else ', side'}"
                                                                for l in labels) + " |",
                "|" + "---|" * (4 + len(labels))]
    for k, e in enumerate(rs.episodes):
        # How far the human went out of their way: a loop round the person, not a side choice, when large.
        straight = float(np.linalg.norm(np.asarray(e.xy[-1]) - np.asarray(e.xy[0])))
        detour = f"{M.path_length(e.xy) / straight:.2f}" if straight > 0 else "–"
        cells = [e.episode_id, str(len(rs.scenes[k].people)), RD.side_of_sweep(e.xy, e.person), detour]
        for l in labels:
            m = per[l][k]
            cells.append("–" if m is None else f"{m['tdm_m']:.3f}" + ("" if rs.approach else
                                                                      (", same" if m["same_side"] else ", other")))
        ep_lines.append("| " + " | ".join(cells) + " |")
    ep_md = (f"# {rs.title}: every episode\n\nMade with {rs.name}.md (same command). Seeds: base + k for the k-th "
             "episode of this table.\n\n" + "\n".join(ep_lines) + "\n")
    tmp = ctx.out / f"{rs.name}_episodes{ctx.suffix}.md.tmp"
    tmp.write_text(ep_md)
    tmp.replace(ctx.out / f"{rs.name}_episodes{ctx.suffix}.md")
    md += f"\nEvery episode: [{rs.name}_episodes{ctx.suffix}.md]({rs.name}_episodes{ctx.suffix}.md). "
    md += "The figure shows the six episodes where the default planner is farthest from the human.\n"
    fig = _worst_figure(rs, paths, per, labels)
    ctx.write(rs.name, md, records, fig)


# The project's TDM targets for the avoid studies (docs/experiments.md, "Targets"): an absolute TDM,
# or a fraction of plain RRT*'s TDM on the same episodes.
TDM_TARGETS = {"real_upo_avoid": ("m", 0.30), "real_ucy_avoid": ("x RRT*", 0.9)}


def _agreement_ceiling(rs: RealSet) -> str:
    """Whether closer situations make humans agree more, and at each distance an estimate of the most a
    side rule on the start and goal alone could agree with them (realdata.side_ceiling). Pairs that are
    not quite the same situation agree less, so the estimate errs low: it is not a bound."""
    from gmmrrt_tools import realdata as RD

    bands = [(r, n, q) for r, n, q in (rs.agreement_within or []) if n > 0]
    if not bands:
        return ""
    return ("\nWhether the situation decides the side: pairs of humans of different recordings/persons whose "
            "start and goal (summed distances in the person frame) lie within "
            + "; ".join(f"{r:g} m agree in {100 * q:.0f} % ({n} pairs; were they the same situation, a rule on the "
                        f"start and goal alone could agree with the humans {100 * RD.side_ceiling(q):.0f} % at most)"
                        for r, n, q in bands)
            + ". That figure (realdata.side_ceiling) assumes a situation makes a human pass on one side with some "
            "probability and two humans choose independently; pairs that are not quite the same situation agree "
            "less, so it errs low: an estimate, not a bound. A planner that also sees the other people is not held "
            "to it.\n")


def _side_limit(rs: RealSet, per, labels) -> str:
    """What the side costs: for each GMM-RRT* planner that picks its own side, the share of its total TDM
    carried by plans on the other side of the person from the human, and how many such plans the TDM
    target allows at the planner's own same-side and other-side means: mean TDM = ((n - X) s + X o) / n
    <= T gives X <= n (T - s) / (o - s), i.e. a side agreement of at least 1 - X / n, to compare with the
    humans' own agreement."""
    if rs.name not in TDM_TARGETS:
        return ""
    unit, t = TDM_TARGETS[rs.name]
    rrt = [m["tdm_m"] for m in per.get("RRT*", []) if m is not None]
    target = t if unit == "m" else t * float(np.mean(rrt)) if rrt else math.nan
    out = [f"\nWhat the side costs (target TDM ≤ {t:g} {unit} = {target:.3f} m): "]
    rows = []
    for l in labels:
        if not l.startswith("GMM-RRT*") or "side)" in l or "own person" in l:
            continue
        ok = [m for m in per[l] if m is not None]
        same = [m["tdm_m"] for m in ok if m["same_side"]]
        other = [m["tdm_m"] for m in ok if not m["same_side"]]
        if not ok or not same or not other:
            continue
        n, s_, o_ = len(ok), float(np.mean(same)), float(np.mean(other))
        share = sum(other) / max(1e-12, sum(same) + sum(other))
        x_max = n * (target - s_) / (o_ - s_) if o_ > s_ else math.inf
        need = "unreachable at this same-side TDM" if x_max < 0 else f"≥ {100 * (1 - max(0.0, x_max) / n):.0f} %"
        rows.append(f"{l}: {len(other)} of {n} plans on the other side carry {100 * share:.0f} % of its TDM "
                    f"({o_:.2f} m each against {s_:.2f} m); the target allows {max(0, math.floor(x_max)) if x_max >= 0 else 0} "
                    f"such plans, a side agreement {need} (it has {100 * len(same) / n:.0f} %)"
                    + (_shared_with_rrt(per[l], per.get(_rrt_peer(l, per), [])) if unit != "m" else ""))
    out.append("; ".join(rows) + ".\n")
    return "".join(out) if rows else ""


def _rrt_peer(label: str, per) -> str:
    """The RRT* row a GMM-RRT* row is compared with: the one given the same people (with the walking
    crowd where the row has it), so that only the cost differs."""
    walking = "RRT* (walking people given)"
    return walking if "walking people given" in label and walking in per else "RRT*"


def _shared_with_rrt(gmm, rrt) -> str:
    """For a target relative to RRT*: whether the planner's other-side plans are RRT*'s too (then they add
    about the same TDM to both and only a side choice unlike RRT*'s moves the ratio), and the ratio of the
    two on the episodes where both pass on the human's side (what the cost alone does)."""
    pairs = [(g, r) for g, r in zip(gmm, rrt) if g is not None and r is not None]
    both_other = [(g, r) for g, r in pairs if not g["same_side"] and not r["same_side"]]
    both_same = [(g, r) for g, r in pairs if g["same_side"] and r["same_side"]]
    if not pairs or not both_same:
        return ""
    out = (f"; RRT* takes the other side too in {len(both_other)} of its {sum(not g['same_side'] for g, _ in pairs)}"
           + (f" ({np.mean([g['tdm_m'] for g, _ in both_other]):.2f} m against RRT*'s "
              f"{np.mean([r['tdm_m'] for _, r in both_other]):.2f} m)" if both_other else ""))
    sg, sr = float(np.mean([g["tdm_m"] for g, _ in both_same])), float(np.mean([r["tdm_m"] for _, r in both_same]))
    return out + (f", and where both take the human's side ({len(both_same)} episodes) it scores {sg:.3f} m "
                  f"against RRT*'s {sr:.3f} m ({sg / sr:.2f}x)" if sr > 0 else "")


def _worst_figure(rs: RealSet, paths, per, labels, n=6):
    import matplotlib.patches as mp
    import matplotlib.pyplot as plt
    from gmmrrt_tools import core

    scored = [(per[DEFAULT_LABEL][k]["tdm_m"], k) for k in range(len(rs.episodes)) if per[DEFAULT_LABEL][k]]
    pick = [k for _, k in sorted(scored, reverse=True)[:n]]
    fig, axes = plt.subplots(1, max(1, len(pick)), figsize=(3.4 * max(1, len(pick)), 3.8), squeeze=False)
    colors = {"GMM-RRT* (paper cost)": "tab:red", "GMM-RRT* (inward cost)": "tab:orange", "RRT*": "tab:gray",
              f"GMM-RRT* ({DEFAULT_COST} cost, human's side)": "tab:purple"}
    for ax, k in zip(axes[0], pick):
        e = rs.episodes[k]

        def pf(p):
            return np.array([core.world_to_person(e.person, x, y) for x, y in p])
        h = pf(e.xy)
        ax.plot(h[:, 0], h[:, 1], color="tab:green", lw=1.8)
        for l in labels:
            if l in colors and paths[l][k] is not None:
                q = pf(paths[l][k])
                ax.plot(q[:, 0], q[:, 1], color=colors[l], lw=1)
        for j, person in enumerate(rs.scenes[k].people):
            px, py = core.world_to_person(e.person, person[0], person[1])
            ax.add_patch(mp.Circle((px, py), PERSON_RADIUS_M, fill=j > 0, color="k", alpha=1.0 if j == 0 else 0.4))
        ax.arrow(0, 0, 0.4, 0, head_width=0.12, color="k")
        ax.set_aspect("equal")
        ax.set_title(f"{e.episode_id}\nTDM {per[DEFAULT_LABEL][k]['tdm_m']:.2f} m", fontsize=8)
        ax.grid(alpha=0.3)
    axes[0][0].legend(handles=legend_handles([("human", "tab:green")] + [(l, c) for l, c in colors.items() if l in labels]),
                      fontsize=6)
    fig.suptitle(f"{rs.title.split(',')[0]}: the worst episodes of the default planner (person frame; "
                 "filled: other standing people)", fontsize=9)
    return fig


REAL_SETS = {"upo_avoid": real_upo_avoid, "ucy_avoid": real_ucy_avoid, "ucy_approach": real_ucy_approach}


def exp_real(ctx: Ctx) -> None:
    """UPO avoid (test split, every standing person), UCY avoid (UCY-trained model) and UCY approach
    (the lab's models): per data set a summary table, a per-episode table and the worst cases."""
    for key in ctx.real_sets:
        rs = REAL_SETS[key](ctx)
        if not rs.episodes:
            raise RuntimeError(f"{rs.name}: no episode in split '{ctx.split}'")
        results = ctx.run_plans(_real_jobs(ctx, rs), rs.name.replace("_", " "))
        _real_report(ctx, rs, results)
