#!/usr/bin/env python3
"""Writes the scenario logs of logs/scenarios/ for gmmrrtd's replay tests: entry point of
gmmrrt_tools.scenario_logs (what each scenario holds is described there).

    .venv/bin/python tools/make_scenarios.py                     # writes logs/scenarios/
    .venv/bin/python tools/make_scenarios.py --out DIR --check   # exit 1 if DIR is stale
"""
import sys

from gmmrrt_tools.scenario_logs import main

if __name__ == "__main__":
    sys.exit(main())
