/*
 * test_goal_life.c - the goal's life in gmmrrtd (docs/daemon.md, "The goal's life") through its
 * seam gmmrrtd_handle_message in log mode with a real planner (plain RRT*, a fixed seed and an
 * iteration budget): accepted -> planning -> reached (on position; on heading when asked),
 * cancelled during planning, replaced by a new goal while planning, failed after
 * goal_fail_after_ms with its reason; each refusal (a finished goal's id, an unknown command, a
 * frame other than [world] frame, a cancel of a goal that is not the current one, a NaN
 * tolerance) is counted and keeps the current goal; the preferred side is kept when a path
 * exists on it and otherwise the plan takes the other side and the status says so.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "daemon.h"
#include "daemon_fixture.h"

#define MS ((int64_t)1000)
#define T0 DAEMON_FIXTURE_T0
#define ST(x) GMMRRT_PLANNER_STATUS_T_##x

static gmmrrtd_t g_d;
static char *const k_map = daemon_fixture_map;
static char k_odom[] = "odom";
static int64_t g_t; /* the log time of the last message, us after T0 */

static int setup(void **state)
{
    daemon_fixture_setup(&g_d, 1500, 4096, 11);
    g_t = 0;
    *state = &g_d;
    return 0;
}

static int teardown(void **state)
{
    daemon_fixture_teardown(*state);
    return 0;
}

static void send_pose_in(gmmrrtd_t *d, double x, double y, double yaw, char *frame)
{
    gmmrrt_pose2d_t m = daemon_fixture_pose(T0 + g_t, x, y, yaw);
    m.frame = frame;
    daemon_fixture_send_pose(d, g_t, &m);
}

/* A pose every 50 ms for `ms`: one cycle per 100 ms of log time (dispatch.c). */
static void hold_pose(gmmrrtd_t *d, double x, double y, double yaw, int64_t ms)
{
    for (int64_t k = 0; k < ms / 50; ++k) {
        g_t += 50 * MS;
        send_pose_in(d, x, y, yaw, k_map);
    }
}

static gmmrrt_nav_goal_t goal_msg(int64_t id, double x, double y)
{
    return daemon_fixture_goal(T0 + g_t, id, x, y, GMMRRT_NAV_GOAL_T_TASK_NONE, -1);
}

static void send_goal_msg(gmmrrtd_t *d, gmmrrt_nav_goal_t m)
{
    m.utime = T0 + g_t;
    daemon_fixture_send_goal(d, g_t, &m);
}

static void send_cancel(gmmrrtd_t *d, int64_t id)
{
    gmmrrt_nav_goal_t m = goal_msg(id, 0.0, 0.0);
    m.command = GMMRRT_NAV_GOAL_T_COMMAND_CANCEL;
    m.tolerance_m = 0.0; /* a cancel reads the id only */
    send_goal_msg(d, m);
}

static void send_person(gmmrrtd_t *d, double x, double y)
{
    daemon_fixture_send_person(d, g_t, T0 + g_t, x, y, M_PI);
}

static void send_boxes(gmmrrtd_t *d, int nb, const double (*box)[4])
{
    gmmrrt_obstacles_t *m = daemon_fixture_obstacles(T0 + g_t);
    m->num_boxes = nb;
    for (int i = 0; i < nb; ++i) {
        m->box_x[i] = box[i][0];
        m->box_y[i] = box[i][1];
        m->box_width[i] = box[i][2];
        m->box_height[i] = box[i][3];
    }
    daemon_fixture_send_obstacles(d, g_t, m);
}

static void test_goal_is_accepted_then_planned_with_its_remaining_length(void **state)
{
    gmmrrtd_t *d = *state;
    send_pose_in(d, 0.0, 0.0, 0.0, k_map);
    send_goal_msg(d, goal_msg(7, 5.0, 0.0));
    assert_int_equal(d->life.state, ST(GOAL_ACCEPTED));
    assert_int_equal(d->life.id, 7);
    hold_pose(d, 0.0, 0.0, 0.0, 100);
    assert_true(d->cycles >= 1);
    assert_int_equal(d->status.goal_id, 7);
    assert_int_equal(d->status.goal_state, ST(GOAL_PLANNING));
    assert_int_equal(d->status.goal_failure, ST(FAILURE_NONE));
    assert_true(d->plan_msg.num_waypoints >= 2);
    assert_string_equal(d->plan_msg.frame, "map");
    assert_true(d->status.remaining_m == d->plan_msg.length_m);
    assert_true(d->status.remaining_m >= 5.0 - 1e-9);
}

/* Reached on position: within tolerance_m of the goal, heading not asked. One empty plan, then
 * only statuses; a re-send of the finished goal is refused and counted. */
static void test_reached_on_position_publishes_one_empty_plan(void **state)
{
    gmmrrtd_t *d = *state;
    send_pose_in(d, 0.0, 0.0, 0.0, k_map);
    send_goal_msg(d, goal_msg(1, 3.0, 0.0));
    hold_pose(d, 0.0, 0.0, 0.0, 100);
    assert_int_equal(d->status.goal_state, ST(GOAL_PLANNING));
    hold_pose(d, 2.75, 0.1, 2.0, 100); /* 0.27 m away, heading far off: not judged */
    assert_int_equal(d->status.goal_state, ST(GOAL_REACHED));
    assert_int_equal(d->status.state, ST(STATE_IDLE));
    assert_int_equal(d->plan_msg.num_waypoints, 0);
    assert_int_equal(d->plan_msg.status, GMMRRTD_STOP_GOAL_REACHED);
    assert_true(d->status.remaining_m == 0.0);
    assert_int_equal(d->status.stops[ST(STOP_GOAL_REACHED)], 1);
    const int64_t plans = d->status.plans_published, cycles = d->cycles;
    hold_pose(d, 2.75, 0.1, 2.0, 300);
    assert_true(d->cycles > cycles);
    assert_int_equal(d->status.plans_published, plans); /* the empty plan once */
    send_goal_msg(d, goal_msg(1, 3.0, 0.0));
    assert_int_equal(d->status.rejected[ST(REJECT_GOAL_ID_REUSED)], 1);
    hold_pose(d, 2.75, 0.1, 2.0, 200);
    assert_int_equal(d->status.plans_published, plans);
    assert_int_equal(d->status.goal_state, ST(GOAL_REACHED));
}

/* Reached on heading: within the position, the heading must also be within yaw_tolerance_rad. */
static void test_reached_needs_the_heading_when_asked(void **state)
{
    gmmrrtd_t *d = *state;
    gmmrrt_nav_goal_t g = goal_msg(2, 3.0, 0.0);
    g.yaw = 1.0;
    g.yaw_tolerance_rad = 0.2;
    send_pose_in(d, 0.0, 0.0, 0.0, k_map);
    send_goal_msg(d, g);
    hold_pose(d, 2.9, 0.0, 1.0 + 0.5, 200); /* in place, 0.5 rad off */
    assert_int_equal(d->status.goal_state, ST(GOAL_PLANNING));
    hold_pose(d, 2.9, 0.0, 1.0 - 0.15, 100); /* turned within 0.2 rad */
    assert_int_equal(d->status.goal_state, ST(GOAL_REACHED));
    assert_int_equal(d->plan_msg.status, GMMRRTD_STOP_GOAL_REACHED);
}

/* Cancel during planning: one empty plan with the cancel's code, no more plans; a re-sent cancel
 * is ignored without a count; a cancel of a goal that never was is counted as a bad value. */
static void test_cancel_during_planning_stops_once(void **state)
{
    gmmrrtd_t *d = *state;
    send_pose_in(d, 0.0, 0.0, 0.0, k_map);
    send_goal_msg(d, goal_msg(3, 5.0, 0.0));
    hold_pose(d, 0.0, 0.0, 0.0, 200);
    assert_true(d->plan_msg.num_waypoints >= 2);
    send_cancel(d, 99);
    assert_int_equal(d->status.rejected[ST(REJECT_BAD_VALUE)], 1);
    assert_int_equal(d->life.state, ST(GOAL_PLANNING)); /* kept */
    send_cancel(d, 3);
    assert_int_equal(d->event_pending, 1);
    hold_pose(d, 0.0, 0.0, 0.0, 100);
    assert_int_equal(d->status.goal_state, ST(GOAL_CANCELLED));
    assert_int_equal(d->plan_msg.num_waypoints, 0);
    assert_int_equal(d->plan_msg.status, GMMRRTD_STOP_GOAL_CANCELLED);
    assert_int_equal(d->status.stops[ST(STOP_GOAL_CANCELLED)], 1);
    const int64_t plans = d->status.plans_published;
    send_cancel(d, 3);
    hold_pose(d, 0.0, 0.0, 0.0, 300);
    assert_int_equal(d->status.plans_published, plans);
    assert_int_equal(d->status.rejected[ST(REJECT_BAD_VALUE)], 1);
    assert_int_equal(d->status.goal_state, ST(GOAL_CANCELLED));
}

/* A new id while a goal is planned replaces it; the replaced goal's id is finished for good. */
static void test_new_goal_during_planning_replaces_the_old_for_good(void **state)
{
    gmmrrtd_t *d = *state;
    send_pose_in(d, 0.0, 0.0, 0.0, k_map);
    send_goal_msg(d, goal_msg(4, 5.0, 0.0));
    hold_pose(d, 0.0, 0.0, 0.0, 200);
    send_goal_msg(d, goal_msg(5, 0.0, 4.0));
    assert_int_equal(d->life.state, ST(GOAL_ACCEPTED));
    hold_pose(d, 0.0, 0.0, 0.0, 100);
    assert_int_equal(d->status.goal_id, 5);
    assert_int_equal(d->status.goal_state, ST(GOAL_PLANNING));
    const int32_t n = d->plan_msg.num_waypoints;
    assert_true(n >= 2 && hypot(d->plan_msg.x[n - 1], d->plan_msg.y[n - 1] - 4.0) < 0.3 + 1e-9);
    send_goal_msg(d, goal_msg(4, 5.0, 0.0)); /* the replaced goal, late */
    assert_int_equal(d->status.rejected[ST(REJECT_GOAL_ID_REUSED)], 1);
    assert_int_equal(d->life.id, 5);
    /* A re-send of the current goal changes nothing; new content under its id updates it. */
    const int64_t version = d->goal_version;
    send_goal_msg(d, goal_msg(5, 0.0, 4.0));
    assert_int_equal(d->goal_version, version);
    send_goal_msg(d, goal_msg(5, 0.0, 3.0));
    assert_int_equal(d->goal_version, version + 1);
    assert_int_equal(d->life.state, ST(GOAL_PLANNING));
}

/* Refused goal messages are counted by reason and leave the current goal as it is. */
static void test_bad_goal_messages_are_counted_and_the_goal_kept(void **state)
{
    gmmrrtd_t *d = *state;
    send_pose_in(d, 0.0, 0.0, 0.0, k_map);
    send_goal_msg(d, goal_msg(6, 5.0, 0.0));
    hold_pose(d, 0.0, 0.0, 0.0, 100);
    gmmrrt_nav_goal_t m = goal_msg(8, 1.0, 1.0);
    m.command = 0;
    send_goal_msg(d, m);
    assert_int_equal(d->status.rejected[ST(REJECT_UNKNOWN_COMMAND)], 1);
    m = goal_msg(8, 1.0, 1.0);
    m.command = 3;
    send_goal_msg(d, m);
    assert_int_equal(d->status.rejected[ST(REJECT_UNKNOWN_COMMAND)], 2);
    m = goal_msg(8, 1.0, 1.0);
    m.frame = k_odom;
    send_goal_msg(d, m);
    assert_int_equal(d->status.rejected[ST(REJECT_WRONG_FRAME)], 1);
    m = goal_msg(8, 1.0, 1.0);
    m.yaw_tolerance_rad = NAN;
    send_goal_msg(d, m);
    assert_int_equal(d->status.rejected[ST(REJECT_NOT_FINITE)], 1);
    m = goal_msg(0, 1.0, 1.0);
    send_goal_msg(d, m);
    assert_int_equal(d->status.rejected[ST(REJECT_BAD_VALUE)], 1);
    assert_int_equal(d->life.id, 6);
    assert_true(d->goal.x == 5.0 && d->goal.y == 0.0);
    /* A pose in another frame is refused too; the last good pose stays. */
    send_pose_in(d, 9.0, 9.0, 0.0, k_odom);
    assert_int_equal(d->status.rejected[ST(REJECT_WRONG_FRAME)], 2);
    assert_true(d->pose.x == 0.0);
    hold_pose(d, 0.0, 0.0, 0.0, 100);
    assert_int_equal(d->status.goal_state, ST(GOAL_PLANNING));
}

/* Another planning frame: inputs in it are taken, "map" is refused, plans are published in it. */
static void test_the_planning_frame_is_the_configured_one(void **state)
{
    gmmrrtd_t *d = *state;
    snprintf(d->set.frame, sizeof d->set.frame, "odom");
    send_pose_in(d, 0.0, 0.0, 0.0, k_map);
    assert_int_equal(d->status.rejected[ST(REJECT_WRONG_FRAME)], 1);
    assert_int_equal(d->have[GMMRRTD_IN_POSE], 0);
    send_pose_in(d, 0.0, 0.0, 0.0, k_odom);
    gmmrrt_nav_goal_t g = goal_msg(1, 4.0, 0.0);
    g.frame = k_odom;
    send_goal_msg(d, g);
    assert_int_equal(d->life.state, ST(GOAL_ACCEPTED));
    for (int k = 0; k < 2; ++k) {
        g_t += 50 * MS;
        send_pose_in(d, 0.0, 0.0, 0.0, k_odom);
    }
    assert_true(d->plan_msg.num_waypoints >= 2);
    assert_string_equal(d->plan_msg.frame, "odom");
    assert_int_equal(d->status.rejected[ST(REJECT_WRONG_FRAME)], 1);
}

/* A goal that no cycle can plan fails after goal_fail_after_ms with its reason, then idles. */
static void test_goal_in_an_obstacle_fails_after_the_limit(void **state)
{
    gmmrrtd_t *d = *state;
    d->set.goal_fail_after_ms = 500.0;
    const double box[1][4] = {{4.0, 0.0, 1.0, 1.0}};
    send_pose_in(d, 0.0, 0.0, 0.0, k_map);
    send_boxes(d, 1, box);
    send_goal_msg(d, goal_msg(9, 4.0, 0.0));
    hold_pose(d, 0.0, 0.0, 0.0, 300);
    assert_int_equal(d->status.goal_state, ST(GOAL_PLANNING));
    assert_int_equal(d->plan_msg.num_waypoints, 0);
    assert_int_equal(d->status.rejected[ST(REJECT_GOAL_IN_COLLISION)], 1);
    hold_pose(d, 0.0, 0.0, 0.0, 400);
    assert_int_equal(d->status.goal_state, ST(GOAL_FAILED));
    assert_int_equal(d->status.goal_failure, ST(FAILURE_GOAL_BLOCKED));
    assert_true(d->status.remaining_m == -1.0);
    const int64_t plans = d->status.plans_published;
    hold_pose(d, 0.0, 0.0, 0.0, 300);
    assert_int_equal(d->status.plans_published, plans);
    assert_int_equal(d->status.state, ST(STATE_IDLE));
    assert_int_equal(d->status.goal_state, ST(GOAL_FAILED));
}

/* Each cause fails with its own reason: an approach target nobody tracks, a goal walled in (no
 * path). A stale pose is the robot's problem, not the goal's: it never fails a goal. */
static void test_each_failure_has_its_reason_and_a_stale_pose_fails_nothing(void **state)
{
    gmmrrtd_t *d = *state;
    d->set.goal_fail_after_ms = 500.0;
    send_pose_in(d, 0.0, 0.0, 0.0, k_map);
    gmmrrt_nav_goal_t g = goal_msg(20, 4.0, 0.0);
    g.task = GMMRRT_NAV_GOAL_T_TASK_APPROACH;
    g.target_person_id = 99;
    send_goal_msg(d, g);
    hold_pose(d, 0.0, 0.0, 0.0, 800);
    assert_int_equal(d->status.goal_state, ST(GOAL_FAILED));
    assert_int_equal(d->status.goal_failure, ST(FAILURE_UNKNOWN_TARGET));

    const double room[4][4] = {{4.0, 1.0, 2.2, 0.2}, {4.0, -1.0, 2.2, 0.2}, {3.0, 0.0, 0.2, 2.2}, {5.0, 0.0, 0.2, 2.2}};
    send_boxes(d, 4, room);
    send_goal_msg(d, goal_msg(21, 4.0, 0.0)); /* free, inside the walls */
    hold_pose(d, 0.0, 0.0, 0.0, 800);
    assert_int_equal(d->status.goal_state, ST(GOAL_FAILED));
    assert_int_equal(d->status.goal_failure, ST(FAILURE_UNREACHABLE));
    assert_true(d->status.rejected[ST(REJECT_GOAL_UNREACHABLE)] >= 1);

    /* No pose for 2 s (four times the limit): stops for a stale pose, the goal stays planned. */
    send_goal_msg(d, goal_msg(22, 0.0, 3.0));
    hold_pose(d, 0.0, 0.0, 0.0, 200);
    assert_int_equal(d->status.goal_state, ST(GOAL_PLANNING));
    for (int k = 0; k < 20; ++k) { /* only the obstacles arrive: the log time moves on */
        g_t += 100 * MS;
        send_boxes(d, 4, room);
    }
    assert_int_equal(d->plan_msg.status, GMMRRTD_STOP_POSE_STALE);
    assert_int_equal(d->status.goal_state, ST(GOAL_PLANNING));
    hold_pose(d, 0.0, 0.0, 0.0, 100);
    assert_true(d->plan_msg.num_waypoints >= 2);
    assert_int_equal(d->status.goal_state, ST(GOAL_PLANNING));
}

/* The middle of a plan's waypoints at x near `x`: the y it passes at. */
static double y_at(const gmmrrt_waypoints_t *m, double x)
{
    double best = INFINITY, y = NAN;
    for (int32_t i = 0; i < m->num_waypoints; ++i)
        if (fabs(m->x[i] - x) < best) {
            best = fabs(m->x[i] - x);
            y = m->y[i];
        }
    return y;
}

/* The side: LEFT keeps the person on the robot's left (the robot passes at y < 0 here), RIGHT
 * at y > 0; with the left side walled off, the plan takes the right and the status says so. */
static void test_preferred_side_is_kept_or_reported_not_found(void **state)
{
    gmmrrtd_t *d = *state;
    send_pose_in(d, 0.0, 0.0, 0.0, k_map);
    send_person(d, 3.0, 0.0);
    gmmrrt_nav_goal_t g = goal_msg(10, 6.0, 0.0);
    g.preferred_side = GMMRRT_NAV_GOAL_T_SIDE_LEFT;
    send_goal_msg(d, g);
    hold_pose(d, 0.0, 0.0, 0.0, 100);
    assert_int_equal(d->status.side_result, ST(SIDE_KEPT));
    assert_true(y_at(&d->plan_msg, 3.0) < 0.0);
    g = goal_msg(11, 6.0, 0.0);
    g.preferred_side = GMMRRT_NAV_GOAL_T_SIDE_RIGHT;
    send_goal_msg(d, g);
    send_person(d, 3.0, 0.0);
    hold_pose(d, 0.0, 0.0, 0.0, 100);
    assert_int_equal(d->status.side_result, ST(SIDE_KEPT));
    assert_true(y_at(&d->plan_msg, 3.0) > 0.0);
    /* A wall from the person down to y = -3.5 closes the left side (the bounds end at -3). */
    const double wall[1][4] = {{3.0, -2.0, 0.2, 3.0}};
    send_boxes(d, 1, wall);
    g = goal_msg(12, 6.0, 0.0);
    g.preferred_side = GMMRRT_NAV_GOAL_T_SIDE_LEFT;
    send_goal_msg(d, g);
    send_person(d, 3.0, 0.0);
    hold_pose(d, 0.0, 0.0, 0.0, 100);
    assert_int_equal(d->status.side_result, ST(SIDE_NOT_FOUND));
    assert_true(d->plan_msg.num_waypoints >= 2);
    assert_true(y_at(&d->plan_msg, 3.0) > 0.0);
    assert_int_equal(d->status.goal_state, ST(GOAL_PLANNING));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_goal_is_accepted_then_planned_with_its_remaining_length, setup, teardown),
        cmocka_unit_test_setup_teardown(test_reached_on_position_publishes_one_empty_plan, setup, teardown),
        cmocka_unit_test_setup_teardown(test_reached_needs_the_heading_when_asked, setup, teardown),
        cmocka_unit_test_setup_teardown(test_cancel_during_planning_stops_once, setup, teardown),
        cmocka_unit_test_setup_teardown(test_new_goal_during_planning_replaces_the_old_for_good, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_goal_messages_are_counted_and_the_goal_kept, setup, teardown),
        cmocka_unit_test_setup_teardown(test_the_planning_frame_is_the_configured_one, setup, teardown),
        cmocka_unit_test_setup_teardown(test_goal_in_an_obstacle_fails_after_the_limit, setup, teardown),
        cmocka_unit_test_setup_teardown(test_each_failure_has_its_reason_and_a_stale_pose_fails_nothing, setup, teardown),
        cmocka_unit_test_setup_teardown(test_preferred_side_is_kept_or_reported_not_found, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
