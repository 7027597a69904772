"""architecture.constants: the Python tools take the numbers the C and C++ code defines from
gmmrrt_constants (generated at build time by tools/constants/print_constants.cpp from the headers)
instead of writing them again.

Checks that the generated module holds what the compiler read, that the tools use it, and that no
Python file under tools/ assigns a number literal to one of its names (a copy that would drift).
"""
import ast
from pathlib import Path

import gmmrrt_constants

from gmmrrt_tools import demonstration_log, replay_check

REPO = Path(__file__).resolve().parents[3]


def test_generated_values_are_the_headers():
    # The values themselves are the compiler's; these are the documented ones (docs/planner.md,
    # docs/daemon.md, docs/demonstrations.md), so a header change shows up here too.
    assert gmmrrt_constants.GMMRRT_STANDING_SPEED_M_S == 0.2
    assert gmmrrt_constants.GMMRRT_DEFAULT_NOMINAL_SPEED_M_S == 0.5
    assert gmmrrt_constants.GMMRRT_DEFAULT_PREDICTION_HORIZON_S == 5.0
    assert gmmrrt_constants.GMMRRTD_MAX_UTIME == 1 << 53
    assert gmmrrt_constants.LEARNER_MAX_PERSON_AGE_S == 5.0


def test_tools_use_the_generated_values():
    assert replay_check.STANDING_SPEED_M_S is gmmrrt_constants.GMMRRT_STANDING_SPEED_M_S
    assert replay_check.NOMINAL_SPEED_M_S is gmmrrt_constants.GMMRRT_DEFAULT_NOMINAL_SPEED_M_S
    assert replay_check.PREDICTION_HORIZON_S is gmmrrt_constants.GMMRRT_DEFAULT_PREDICTION_HORIZON_S
    assert replay_check.MAX_UTIME is gmmrrt_constants.GMMRRTD_MAX_UTIME
    assert demonstration_log.MAX_PERSON_AGE_S is gmmrrt_constants.LEARNER_MAX_PERSON_AGE_S


def literal_copies(tree, suffixes):
    """(line, name) of every `NAME = <number>` whose name ends with one of `suffixes`."""
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Assign) and isinstance(node.value, (ast.Constant, ast.BinOp)):
            if isinstance(node.value, ast.Constant) and not isinstance(node.value.value, (int, float)):
                continue
            for t in node.targets:
                if isinstance(t, ast.Name) and any(t.id.endswith(s) for s in suffixes):
                    out.append((node.lineno, t.id))
    return out


SUFFIXES = ("STANDING_SPEED_M_S", "NOMINAL_SPEED_M_S", "PREDICTION_HORIZON_S", "MAX_UTIME", "MAX_PERSON_AGE_S")


def test_the_checker_finds_a_planted_copy():
    assert literal_copies(ast.parse("MAX_UTIME = 1 << 53\nX = 2\n"), SUFFIXES) == [(1, "MAX_UTIME")]


def test_no_tool_writes_these_numbers_again():
    found = []
    for path in sorted((REPO / "tools").rglob("*.py")):
        for line, name in literal_copies(ast.parse(path.read_text(), str(path)), SUFFIXES):
            found.append(f"{path.relative_to(REPO)}:{line}: {name}")
    assert not found, "numbers defined in C/C++ written again in Python:\n" + "\n".join(found)
