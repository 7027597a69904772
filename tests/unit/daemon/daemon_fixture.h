/*
 * daemon_fixture.h - the daemon under test, as the cmocka cases of tests/unit/daemon drive it:
 * gmmrrtd_t with default settings, the log clock, plain RRT* (no model needed), an iteration
 * budget instead of a time budget (a run is the same on any machine), a planner in its own block
 * and an LCM that publishes into file:///dev/null. Every case feeds inputs through
 * gmmrrtd_handle_message, as the LCM handlers do: the senders below encode a message and hand
 * it over, and the builders start the messages the cases send most.
 */
#ifndef GMMRRT_TESTS_DAEMON_FIXTURE_H
#define GMMRRT_TESTS_DAEMON_FIXTURE_H

#include <stdint.h>

#include "daemon.h"

/* The senders' clocks in the cases: Unix time (us) at log time 0. */
#define DAEMON_FIXTURE_T0 ((int64_t)1700000000000000)

/* The daemon's default [world] frame ("map"), writable as the messages' frame fields are. */
extern char daemon_fixture_map[];

/* Makes *d ready for inputs: budget_iterations per cycle, max_nodes in the pool, the RNG seed. */
void daemon_fixture_setup(gmmrrtd_t *d, int64_t budget_iterations, int32_t max_nodes, uint64_t seed);

/* Releases what daemon_fixture_setup took. */
void daemon_fixture_teardown(gmmrrtd_t *d);

/* Encode *m (the test fails when it does not encode) and hand it to gmmrrtd_handle_message as
 * received at log time recv_us. */
void daemon_fixture_send_pose(gmmrrtd_t *d, int64_t recv_us, const gmmrrt_pose2d_t *m);
void daemon_fixture_send_people(gmmrrtd_t *d, int64_t recv_us, const gmmrrt_people_t *m);
void daemon_fixture_send_goal(gmmrrtd_t *d, int64_t recv_us, const gmmrrt_nav_goal_t *m);
void daemon_fixture_send_obstacles(gmmrrtd_t *d, int64_t recv_us, const gmmrrt_obstacles_t *m);
void daemon_fixture_send_scan(gmmrrtd_t *d, int64_t recv_us, const gmmrrt_planar_scan_t *m);
void daemon_fixture_send_grid(gmmrrtd_t *d, int64_t recv_us, const gmmrrt_occupancy_grid_t *m);

/* A pose stamped utime in the map frame at (x, y, yaw). */
gmmrrt_pose2d_t daemon_fixture_pose(int64_t utime, double x, double y, double yaw);

/* A new goal (COMMAND_NEW) stamped utime in the map frame: id, position, tolerance 0.3 m, task
 * (GMMRRT_NAV_GOAL_T_TASK_*) and target person id (-1: none). */
gmmrrt_nav_goal_t daemon_fixture_goal(int64_t utime, int64_t id, double x, double y, int8_t task, int32_t target);

/* Zeroed messages stamped utime in the map frame, in static storage (too large for a case's
 * stack): each call clears and returns the same one. */
gmmrrt_people_t *daemon_fixture_people(int64_t utime);
gmmrrt_obstacles_t *daemon_fixture_obstacles(int64_t utime);

/* One standing person (id 1) at (x, y) facing yaw, stamped utime, received at recv_us. */
void daemon_fixture_send_person(gmmrrtd_t *d, int64_t recv_us, int64_t utime, double x, double y, double yaw);

#endif /* GMMRRT_TESTS_DAEMON_FIXTURE_H */
