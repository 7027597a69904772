"""Shared by the tests of the scripts in tools/ (side_rules.py, walkers_ucy.py, record_demo.py): the
scripts are entry points, not part of the gmmrrt_tools package, so a test loads one as a module by
its path. tests/common is on the tests' PYTHONPATH (cmake/GmmrrtTesting.cmake)."""
import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def load_tool_script(name):
    """tools/<name>.py of this checkout as a module named <name>."""
    path = ROOT / "tools" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
