#!/usr/bin/env python3
"""Writes or checks tests/data/model_vectors/: entry point of gmmrrt_tools.model_vectors (the
independent oracle of the model format and density; see its docstring).

    .venv/bin/python tools/gen_model_vectors.py [--out DIR] [--check]
"""
import sys

from gmmrrt_tools.model_vectors import main

if __name__ == "__main__":
    sys.exit(main())
