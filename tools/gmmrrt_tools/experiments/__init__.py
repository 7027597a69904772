"""The studies of tools/experiments.py, one module each (common: what they share)."""
