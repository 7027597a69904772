/*
 * daemon_fixture.h - the daemon under test, as the cmocka cases of tests/unit/daemon drive it:
 * gmmrrtd_t with default settings, the log clock, plain RRT* (no model needed), an iteration
 * budget instead of a time budget (a run is the same on any machine), a planner in its own block
 * and an LCM that publishes into file:///dev/null. Every case feeds inputs through
 * gmmrrtd_handle_message, as the LCM handlers do.
 */
#ifndef GMMRRT_TESTS_DAEMON_FIXTURE_H
#define GMMRRT_TESTS_DAEMON_FIXTURE_H

#include <stdint.h>

#include "daemon.h"

/* Makes *d ready for inputs: budget_iterations per cycle, max_nodes in the pool, the RNG seed. */
void daemon_fixture_setup(gmmrrtd_t *d, int64_t budget_iterations, int32_t max_nodes, uint64_t seed);

/* Releases what daemon_fixture_setup took. */
void daemon_fixture_teardown(gmmrrtd_t *d);

#endif /* GMMRRT_TESTS_DAEMON_FIXTURE_H */
