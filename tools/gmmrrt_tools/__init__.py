"""gmmrrt_tools: the Python side of gmmrrt (demonstrations, converters, metrics, plots, experiments).

Modules that need the paper's features or the mixture call the C core through `core` (ctypes on
build/lib/libgmmrrt.so), so there is one definition of each, in planner/src/.
"""
