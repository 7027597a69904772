"""pytest plugin loaded by every pytest registration of the suite (tests/CMakeLists.txt:
`-p gmmrrt_skip_status`, with tests/common on PYTHONPATH).

A pytest file whose tests were all skipped ends with exit code 77, which CTest reports as
"Skipped" (SKIP_RETURN_CODE 77) instead of "Passed": a skip must never look like a pass.
The reasons are printed by pytest's -rs summary ("SKIPPED [n] file:line: reason"), which
tools/run test collects into its end summary. A file with at least one passing test still
passes; its skipped tests appear in that summary all the same.
"""

SKIP_EXIT = 77


def pytest_sessionfinish(session, exitstatus):
    if exitstatus != 0:
        return
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    stats = reporter.stats if reporter is not None else {}
    ran = sum(len(stats.get(k, [])) for k in ("passed", "failed", "error", "xfailed", "xpassed"))
    if ran == 0 and stats.get("skipped"):
        session.exitstatus = SKIP_EXIT
