"""The benchmark harness behind tools/bench.py (`tools/run bench`): statistics (stats), the planner
and learner runs against their peers (planner, learner; the programs are in tests/bench/), the
daemon latency (daemon) and set-up cost (daemon_setup_cost), the cost-over-time figure (plot),
the targets and docs/benchmarks.md (report, merge_sections), and the learner before/after timing
(learner_speed). Benchmarks report; they assert nothing (docs/benchmarks.md)."""
