#!/usr/bin/env python3
"""Writes or checks tests/data/model_vectors/: the command line of gmmrrt_tools.model_vectors (the
independent oracle of the model format and density; its docstring says what the files are and why
--check compares within a tolerance).

    .venv/bin/python tools/gen_model_vectors.py            # rewrite the checked-in files
    .venv/bin/python tools/gen_model_vectors.py --check    # verify they are up to date
"""
import sys

from gmmrrt_tools.model_vectors import main

if __name__ == "__main__":
    sys.exit(main())
