/*
 * test_people_motion.c - gmmrrtd's cycles with walking people, starts in collision and the
 * drivable path, through its seam gmmrrtd_handle_message in log mode with a real planner
 * (plain RRT*, a fixed seed and an iteration budget: the same tree every run). Oracles are
 * geometry computed here from the published plan, not the planner's own report:
 *  - a person walking head-on into the robot's path is passed at a safe distance at the times
 *    the plan says (and the same plan made as if the person stood would not be);
 *  - a start inside a person's disc publishes, in that same cycle, an escape (status 43,
 *    counted) whose clearance grows until the robot is out;
 *  - a start deep inside an obstacle is the only stop left (frozen), counted with the reason;
 *  - no published plan turns tighter than the configured radius unless the core said it had to
 *    (a corner with no free arc), and such plans are counted;
 *  - an approach from behind the person arrives facing them within 15 degrees;
 *  - a person faster than the core's bound refuses the list (counted), the last list stays;
 *  - the planning bounds are the core's rule (problem_bounds.h).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "daemon.h"
#include "daemon_fixture.h"
#include "gmmrrt/problem_bounds.h"

#define MS ((int64_t)1000)
#define T0 DAEMON_FIXTURE_T0
#define ST(x) GMMRRT_PLANNER_STATUS_T_##x

static gmmrrtd_t g_d;

typedef struct {
    double x, y, yaw, vx, vy;
} person_in_t;

static int setup(void **state)
{
    /* plain RRT*: geometry cases: no model needed */
    daemon_fixture_setup(&g_d, 1500, 4096, 11);
    *state = &g_d;
    return 0;
}

static int teardown(void **state)
{
    daemon_fixture_teardown(*state);
    return 0;
}

static void send_pose(gmmrrtd_t *d, int64_t t, double x, double y)
{
    const gmmrrt_pose2d_t m = daemon_fixture_pose(T0 + t, x, y, 0.0);
    daemon_fixture_send_pose(d, t, &m);
}

static void send_people(gmmrrtd_t *d, int64_t t, const person_in_t *p, int n_people)
{
    gmmrrt_people_t *m = daemon_fixture_people(T0 + t);
    m->num_people = n_people;
    for (int i = 0; i < n_people; ++i) {
        m->people[i].utime = T0 + t;
        m->people[i].id = i + 1;
        m->people[i].x = p[i].x;
        m->people[i].y = p[i].y;
        m->people[i].yaw = p[i].yaw;
        m->people[i].vx = p[i].vx;
        m->people[i].vy = p[i].vy;
    }
    daemon_fixture_send_people(d, t, m);
}

/* One goal, updated: a changed content replans, as a new goal would. */
static void send_goal(gmmrrtd_t *d, int64_t t, double x, double y, int8_t task, int32_t target)
{
    const gmmrrt_nav_goal_t m = daemon_fixture_goal(T0 + t, 1, x, y, task, target);
    daemon_fixture_send_goal(d, t, &m);
}

static void send_circle(gmmrrtd_t *d, int64_t t, double x, double y, double r)
{
    gmmrrt_obstacles_t *m = daemon_fixture_obstacles(T0 + t);
    m->num_circles = 1;
    m->circle_x[0] = x;
    m->circle_y[0] = y;
    m->circle_radius[0] = r;
    daemon_fixture_send_obstacles(d, t, m);
}

/* The situation at t = 0 and one cycle on it: the cycle runs when the log time passes the
 * first tick (dispatch.c), so a pose 1 ms later brings it. */
static void one_cycle(gmmrrtd_t *d, double rx, double ry)
{
    send_pose(d, 0, rx, ry);
    send_pose(d, 100 * MS, rx, ry);
    assert_true(d->cycles >= 1);
}

static double wrap(double a) { return atan2(sin(a), cos(a)); }

/* Smallest distance between a waypoint and the walker where it is predicted when the robot
 * gets there at `speed` (constant velocity, held at `horizon_s`). */
static double min_predicted_distance(const gmmrrt_waypoints_t *m, person_in_t p, double speed, double horizon_s)
{
    double s = 0.0, best = INFINITY;
    for (int32_t i = 0; i < m->num_waypoints; ++i) {
        if (i > 0)
            s += hypot(m->x[i] - m->x[i - 1], m->y[i] - m->y[i - 1]);
        const double t = fmin(s / speed, horizon_s);
        best = fmin(best, hypot(m->x[i] - (p.x + p.vx * t), m->y[i] - (p.y + p.vy * t)));
    }
    return best;
}

/* The planning bounds are the core's rule (problem_bounds.h), the one gmmrrt-plan and the Python
 * tools use: the scene of planner.problem_bounds (tests/unit/planner/test_problem_bounds.py) gives
 * the same box here. The person and the far circle do not widen it. */
static void test_planning_bounds_are_the_core_rule(void **state)
{
    gmmrrtd_t *d = *state;
    const person_in_t person = {2.0, 3.0, 0.0, 0.0, 0.0};
    send_goal(d, 0, 5.0, 1.0, GMMRRT_NAV_GOAL_T_TASK_NONE, -1);
    send_people(d, 0, &person, 1);
    send_circle(d, 0, 10.0, 10.0, 0.5);
    one_cycle(d, 0.5, -1.0);
    const gmmrrt_bounds_t *b = &d->problem.obstacles.bounds;
    gmmrrt_bounds_t rule;
    assert_int_equal(gmmrrt_problem_bounds(0.5, -1.0, 5.0, 1.0, d->set.bounds_margin_m, &rule), GMMRRT_OK);
    assert_memory_equal(b, &rule, sizeof rule);
    assert_true(d->set.bounds_margin_m == GMMRRT_DEFAULT_BOUNDS_MARGIN_M);
    assert_true(b->xmin == -2.5 && b->ymin == -4.0 && b->xmax == 8.0 && b->ymax == 4.0);
}

static void test_walker_head_on_is_passed_at_a_safe_distance(void **state)
{
    gmmrrtd_t *d = *state;
    const double contact = d->set.cfg.robot_radius_m + d->set.cfg.person_radius_m;
    /* Walking head-on at 0.8 m/s, 0.2 m off the robot's line: they meet near x = 2.2 after 4.4 s. */
    const person_in_t walker = {6.0, 0.2, M_PI, -0.8, 0.0};
    send_goal(d, 0, 8.0, 0.0, GMMRRT_NAV_GOAL_T_TASK_NONE, -1);
    send_people(d, 0, &walker, 1);
    one_cycle(d, 0.0, 0.0);
    assert_int_equal(d->plan_msg.status, GMMRRT_OK);
    assert_true(d->plan_msg.num_waypoints >= 2);
    assert_true(d->problem.person_vx[0] == -0.8); /* the velocity reached the planner */
    const double walking = min_predicted_distance(&d->plan_msg, walker, d->set.nominal_speed_m_s,
                                                  d->set.prediction_horizon_s);
    assert_true(walking > contact);

    /* The oracle can fail: planned as if the person stood, the path meets the walker. */
    person_in_t standing = walker;
    standing.vx = 0.0;
    send_people(d, 150 * MS, &standing, 1);
    send_pose(d, 200 * MS, 0.0, 0.0);
    send_pose(d, 300 * MS, 0.0, 0.0);
    assert_true(d->problem.person_vx[0] == 0.0);
    assert_int_equal(d->plan_msg.status, GMMRRT_OK);
    assert_true(min_predicted_distance(&d->plan_msg, walker, d->set.nominal_speed_m_s, d->set.prediction_horizon_s) <
                contact);
}

static void test_start_inside_a_disc_escapes_in_the_same_cycle(void **state)
{
    gmmrrtd_t *d = *state;
    const double contact = d->set.cfg.robot_radius_m + d->set.cfg.person_radius_m;
    const person_in_t stepped_in = {0.3, 0.1, M_PI, 0.0, 0.0}; /* 0.32 m from the robot's centre */
    send_goal(d, 0, 5.0, 0.0, GMMRRT_NAV_GOAL_T_TASK_NONE, -1);
    send_people(d, 0, &stepped_in, 1);
    send_pose(d, 0, 0.0, 0.0);
    send_pose(d, 100 * MS, 0.0, 0.0);
    assert_int_equal(d->cycles, 1);
    const gmmrrt_waypoints_t *m = &d->plan_msg;
    assert_int_equal(m->status, GMMRRT_ESCAPE);
    assert_int_equal(d->status.escapes, 1);
    assert_int_equal(d->status.state, ST(STATE_PLANNING));
    for (int i = 0; i < ST(NUM_STOP_REASONS); ++i)
        assert_int_equal(d->status.stops[i], 0);
    assert_true(m->num_waypoints >= 2);
    assert_true(hypot(m->x[0], m->y[0]) < 1e-9); /* from the robot, not from the exit */
    /* Clearance grows waypoint by waypoint until the discs are apart; the plan then reaches the goal. */
    int32_t out = -1;
    double prev = hypot(m->x[0] - stepped_in.x, m->y[0] - stepped_in.y);
    for (int32_t i = 1; i < m->num_waypoints && out < 0; ++i) {
        const double dist = hypot(m->x[i] - stepped_in.x, m->y[i] - stepped_in.y);
        assert_true(dist >= prev - 1e-9);
        prev = dist;
        if (dist >= contact)
            out = i;
    }
    assert_true(out > 0);
    assert_true(hypot(m->x[m->num_waypoints - 1] - 5.0, m->y[m->num_waypoints - 1]) <= 0.3 + 1e-9);
}

static void test_frozen_start_stops_with_the_reason_counted(void **state)
{
    gmmrrtd_t *d = *state;
    /* Deeper in an obstacle than any escape reaches: the only stop a start in collision gets. */
    send_goal(d, 0, 9.0, 0.0, GMMRRT_NAV_GOAL_T_TASK_NONE, -1);
    send_circle(d, 0, 0.0, 0.0, 6.0);
    one_cycle(d, 0.0, 0.0);
    assert_int_equal(d->plan_msg.num_waypoints, 0);
    assert_int_equal(d->plan_msg.status, GMMRRT_ERR_FROZEN);
    assert_int_equal(d->status.last_error, GMMRRT_ERR_FROZEN);
    assert_int_equal(d->status.stops[ST(STOP_FROZEN)], d->cycles);
    assert_int_equal(d->status.stops[ST(STOP_START_BLOCKED)], 0);
    assert_int_equal(d->status.escapes, 0);
    assert_true(gmmrrt_planner_escape_reason(d->planner)[0] != '\0');
}

static void check_turns(const gmmrrt_waypoints_t *m, double r)
{
    for (int32_t i = 1; i < m->num_waypoints; ++i) {
        const double chord = hypot(m->x[i] - m->x[i - 1], m->y[i] - m->y[i - 1]);
        const double allowed = 2.0 * asin(fmin(1.0, chord / (2.0 * r))); /* an arc of radius r over that chord */
        assert_true(fabs(wrap(m->yaw[i] - m->yaw[i - 1])) <= allowed + 1e-6);
        if (chord > 1e-9) /* yaw is the tangent: the chord lies between the two headings */
            assert_true(fabs(wrap(atan2(m->y[i] - m->y[i - 1], m->x[i] - m->x[i - 1]) - m->yaw[i - 1])) <=
                        allowed + 1e-6);
    }
}

static void test_no_published_plan_turns_tighter_than_the_bound(void **state)
{
    gmmrrtd_t *d = *state;
    d->set.min_turn_radius_m = 0.5;
    const person_in_t people[2] = {{2.0, 0.1, 0.0, 0.0, 0.0}, {4.0, -0.6, M_PI / 2, 0.0, 0.0}};
    send_goal(d, 0, 6.0, 0.5, GMMRRT_NAV_GOAL_T_TASK_AVOID, -1);
    send_circle(d, 0, 3.0, 1.2, 0.4);
    int published = 0;
    int64_t tight_plans = 0;
    for (int k = 0; k < 20; ++k) { /* the robot moves along; every cycle's plan is checked */
        send_people(d, k * 100 * MS + 10 * MS, people, 2);
        send_pose(d, k * 100 * MS + 20 * MS, 0.05 * k, 0.0);
        if (d->plan_msg.num_waypoints >= 2) {
            /* A corner whose arc would not be free is turned tighter (drivable.h); such a plan is
             * counted, and every plan not counted must keep the bound. */
            const int tight = d->drive_report.tight_turns > 0 || d->drive_report.turns_in_place > 0;
            assert_int_equal(d->status.tight_turn_plans, tight_plans + tight);
            assert_int_equal(d->plan_msg.status, tight ? GMMRRT_TIGHT_TURNS : GMMRRT_OK); /* flagged per plan */
            tight_plans += tight;
            if (!tight)
                check_turns(&d->plan_msg, d->set.min_turn_radius_m);
            published++;
        }
    }
    assert_true(published >= 15);
    assert_true(published - tight_plans >= 10);
}

static void test_approach_from_behind_arrives_facing_the_person(void **state)
{
    gmmrrtd_t *d = *state;
    d->set.yaw_tolerance_deg = 15.0;
    /* The person faces +x; the robot comes from behind and must end in front, facing them. */
    const person_in_t person = {0.0, 0.0, 0.0, 0.0, 0.0};
    send_goal(d, 0, 1.2, 0.0, GMMRRT_NAV_GOAL_T_TASK_APPROACH, 1);
    send_people(d, 0, &person, 1);
    one_cycle(d, -3.0, 0.2);
    const gmmrrt_waypoints_t *m = &d->plan_msg;
    assert_int_equal(m->status, GMMRRT_OK);
    assert_true(m->num_waypoints >= 2);
    const int32_t n = m->num_waypoints - 1;
    const double facing = atan2(person.y - m->y[n], person.x - m->x[n]);
    assert_true(fabs(wrap(m->yaw[n] - facing)) <= 15.0 * M_PI / 180.0);
    assert_true(d->drive_report.arrival_met);
}

static void test_person_faster_than_the_bound_is_refused_and_counted(void **state)
{
    gmmrrtd_t *d = *state;
    const person_in_t ok = {2.0, 2.0, 0.0, 0.8, 0.0};
    send_people(d, 0, &ok, 1);
    const person_in_t fast[2] = {{2.0, 2.0, 0.0, 0.8, 0.0}, {3.0, 2.0, 0.0, 2.5, -2.0}}; /* 3.2 m/s */
    send_people(d, 100 * MS, fast, 2);
    assert_int_equal(d->status.rejected[ST(REJECT_PERSON_SPEED)], 1);
    assert_int_equal(d->people.num_people, 1); /* the last good list stays */
    assert_true(d->people.people[0].vx == 0.8);
    const person_in_t just_ok = {3.0, 2.0, 0.0, 0.0, GMMRRT_MAX_PERSON_SPEED_M_S};
    send_people(d, 200 * MS, &just_ok, 1);
    assert_int_equal(d->status.rejected[ST(REJECT_PERSON_SPEED)], 1);
    assert_true(d->people.people[0].vy == GMMRRT_MAX_PERSON_SPEED_M_S);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_planning_bounds_are_the_core_rule, setup, teardown),
        cmocka_unit_test_setup_teardown(test_walker_head_on_is_passed_at_a_safe_distance, setup, teardown),
        cmocka_unit_test_setup_teardown(test_start_inside_a_disc_escapes_in_the_same_cycle, setup, teardown),
        cmocka_unit_test_setup_teardown(test_frozen_start_stops_with_the_reason_counted, setup, teardown),
        cmocka_unit_test_setup_teardown(test_no_published_plan_turns_tighter_than_the_bound, setup, teardown),
        cmocka_unit_test_setup_teardown(test_approach_from_behind_arrives_facing_the_person, setup, teardown),
        cmocka_unit_test_setup_teardown(test_person_faster_than_the_bound_is_refused_and_counted, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
