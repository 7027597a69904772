"""Selections of the real demonstrations in ../shared/data/real (README.md there): the UPO avoid
episodes by split and by encounter. The paper's avoid task (Sect. 2) has the person facing the
oncoming robot: UPO flags those episodes frontal_encounter in upo_avoid_index.csv.
"""
from __future__ import annotations

import csv
import os
from typing import List

from .episodes import Episode, EpisodeError, read_episodes


def select_upo(real_data: str, split: str, encounter: str) -> List[Episode]:
    """UPO avoid episodes of a split (all|train|test) and encounter (frontal|all)."""
    index = os.path.join(real_data, "upo_avoid_index.csv")
    upo, _ = read_episodes(os.path.join(real_data, "upo_avoid_episodes.csv"), index=index)
    keep = {e.id for e in upo}
    if split != "all":
        keep &= {e.id for e in upo if e.split == split}
    if encounter == "frontal":
        keep &= frontal_encounters(index)
    return [e for e in upo if e.id in keep]


def frontal_encounters(index_path: str) -> set:
    """Episode ids whose frontal_encounter column is True."""
    try:
        with open(index_path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        raise EpisodeError(f"{index_path}: cannot open: {e.strerror}") from None
    if not rows or "frontal_encounter" not in rows[0] or "episode_id" not in rows[0]:
        raise EpisodeError(f"{index_path}: line 1: no episode_id or frontal_encounter column")
    return {r["episode_id"] for r in rows if r["frontal_encounter"] == "True"}
