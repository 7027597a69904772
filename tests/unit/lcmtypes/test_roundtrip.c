/*
 * test_roundtrip.c - lcmtypes.roundtrip: every gmmrrt message type through the validating
 * decoders of lcmtypes/include/gmmrrt/msg_decode.h.
 *
 * 1. Round trip: a message with every field set to a distinct value, encoded by the
 *    generated code and decoded by gmmrrt_msg_decode_*, equals the original field by field
 *    and re-encodes to the same bytes.
 * 2. Every validation rule of lcmtypes/msg_decode.c (listed in docs/messages.md) rejects
 *    a message that breaks it with its gmmrrt_msg_result_t and an error naming the type
 *    and the field; slots beyond a count are not validated.
 * 3. Every truncation length and a wrong fingerprint are DECODE_FAILED, never a crash.
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

#include "gmmrrt/msg_decode.h"

#define BUF_CAP (2 * 65536) /* an occupancy grid at capacity is 64 KiB and its header */
static uint8_t g_buf[BUF_CAP];
static uint8_t g_buf2[BUF_CAP];
static char g_err[256];
static char k_map[] = "map";

/* Releases a decoded message's frame (msg_decode.h); types without one hold nothing. */
static void release_nothing(const void *m) { (void)m; }
#define RELEASE(m)                                                                                  \
    _Generic((m), gmmrrt_pose2d_t *: gmmrrt_msg_release_pose2d, gmmrrt_people_t *: gmmrrt_msg_release_people, \
             gmmrrt_nav_goal_t *: gmmrrt_msg_release_nav_goal, gmmrrt_obstacles_t *: gmmrrt_msg_release_obstacles, \
             gmmrrt_waypoints_t *: gmmrrt_msg_release_waypoints,                                   \
             gmmrrt_occupancy_grid_t *: gmmrrt_msg_release_occupancy_grid, default: release_nothing)(m)

/* ------------------------------------------------------------------ valid messages */

static void fill_pose(gmmrrt_pose2d_t *m)
{
    memset(m, 0, sizeof *m);
    m->utime = 1700000000123456LL;
    m->frame = k_map;
    m->x = 1.25;
    m->y = -2.5;
    m->yaw = 0.75;
    m->velocity_valid = 1;
    m->vx = 0.3;
    m->vy = -0.1;
    m->yaw_rate = 0.05;
}

static void fill_people(gmmrrt_people_t *m, int32_t n)
{
    memset(m, 0, sizeof *m);
    m->utime = 1700000000200000LL;
    m->frame = k_map;
    m->num_people = n;
    for (int32_t i = 0; i < GMMRRT_PEOPLE_T_MAX_PEOPLE; ++i) {
        gmmrrt_person_t *p = &m->people[i];
        p->utime = m->utime - i;
        p->id = 100 + i;
        p->x = 0.5 * i;
        p->y = -0.25 * i;
        p->yaw = 0.01 * i;
        p->vx = 0.1 + i;
        p->vy = 0.2 - i;
    }
}

static void fill_goal(gmmrrt_nav_goal_t *m)
{
    memset(m, 0, sizeof *m);
    m->utime = 1700000000300000LL;
    m->frame = k_map;
    m->x = 8.0;
    m->y = 1.5;
    m->yaw = -0.5;
    m->tolerance_m = 0.3;
    m->yaw_tolerance_rad = 0.2;
    m->task = GMMRRT_NAV_GOAL_T_TASK_APPROACH;
    m->target_person_id = 7;
    m->goal_id = 5000000000LL; /* beyond 32 bits */
    m->command = GMMRRT_NAV_GOAL_T_COMMAND_NEW;
    m->preferred_side = GMMRRT_NAV_GOAL_T_SIDE_RIGHT;
}

static void fill_obstacles(gmmrrt_obstacles_t *m, int32_t nc, int32_t nb)
{
    memset(m, 0, sizeof *m);
    m->utime = 1700000000400000LL;
    m->frame = k_map;
    m->num_circles = nc;
    m->num_boxes = nb;
    for (int i = 0; i < GMMRRT_OBSTACLES_T_MAX_CIRCLES; ++i) {
        m->circle_x[i] = 1.0 + i;
        m->circle_y[i] = 2.0 - i;
        m->circle_radius[i] = 0.1 + 0.01 * i;
    }
    for (int i = 0; i < GMMRRT_OBSTACLES_T_MAX_BOXES; ++i) {
        m->box_x[i] = -1.0 - i;
        m->box_y[i] = 3.0 + i;
        m->box_width[i] = 0.5 + 0.01 * i;
        m->box_height[i] = 0.25 + 0.02 * i;
        m->box_yaw[i] = 0.001 * i;
    }
}

static void fill_waypoints(gmmrrt_waypoints_t *m, int32_t n)
{
    memset(m, 0, sizeof *m);
    m->utime = 1700000000500000LL;
    m->frame = k_map;
    m->seq = 42;
    m->num_waypoints = n;
    for (int i = 0; i < GMMRRT_WAYPOINTS_T_MAX_WAYPOINTS; ++i) {
        m->x[i] = 0.1 * i;
        m->y[i] = -0.05 * i;
        m->yaw[i] = 0.002 * i;
    }
    m->total_cost = 12.5;
    m->length_m = 10.75;
    m->planner = GMMRRT_WAYPOINTS_T_PLANNER_GMM_RRT_STAR;
    m->task = GMMRRT_NAV_GOAL_T_TASK_AVOID;
    m->status = 40;
}

static void fill_status(gmmrrt_planner_status_t *m)
{
    memset(m, 0, sizeof *m);
    m->utime = 1700000000600000LL;
    m->state = GMMRRT_PLANNER_STATUS_T_STATE_PLANNING;
    m->last_error = 31;
    m->iterations = 123456789LL;
    m->nodes = 4321;
    m->first_solution_ms = 3.5;
    m->best_cost = 11.25;
    m->plan_time_ms = 80.0;
    m->plans_published = 99;
    m->missed_deadlines = 2;
    for (int i = 0; i < GMMRRT_PLANNER_STATUS_T_NUM_REJECT_REASONS; ++i)
        m->rejected[i] = 1000 + i;
    m->escapes = 17;
    m->approach_model = 4;
    m->goal_id = 77;
    m->goal_state = GMMRRT_PLANNER_STATUS_T_GOAL_FAILED;
    m->goal_failure = GMMRRT_PLANNER_STATUS_T_FAILURE_UNREACHABLE;
    m->remaining_m = 4.5;
    m->side_result = GMMRRT_PLANNER_STATUS_T_SIDE_NOT_FOUND;
}

static void fill_demo(gmmrrt_demo_info_t *m)
{
    memset(m, 0, sizeof *m);
    m->utime = 1700000000700000LL;
    m->episode = 12;
    m->task = GMMRRT_NAV_GOAL_T_TASK_AVOID;
    m->homotopy = GMMRRT_DEMO_INFO_T_HOMOTOPY_RIGHT;
    m->person_id = 3;
}

static void fill_scan(gmmrrt_planar_scan_t *m, int32_t n)
{
    memset(m, 0, sizeof *m);
    m->utime = 1700000000800000LL;
    m->rad0 = -2.35619449;
    m->radstep = 0.004363323;
    m->range_min_m = 0.05;
    m->range_max_m = 30.0;
    m->sensor_x = 0.2;
    m->sensor_y = -0.05;
    m->sensor_yaw = 0.01;
    m->num_ranges = n;
    for (int i = 0; i < GMMRRT_PLANAR_SCAN_T_MAX_RANGES; ++i)
        m->ranges[i] = 0.5f + 0.001f * (float)i;
}

static void fill_grid(gmmrrt_occupancy_grid_t *m, int32_t w, int32_t h)
{
    memset(m, 0, sizeof *m);
    m->utime = 1700000000900000LL;
    m->frame = k_map;
    m->resolution_m = 0.05;
    m->origin_x = -3.0;
    m->origin_y = 2.5;
    m->origin_yaw = 0.1;
    m->width = w;
    m->height = h;
    /* Sides whose product overflows 32 bits are a case of their own: the count then wraps
     * (computed in 64 bits, then narrowed) and the decoder must judge the sides, not it. */
    m->num_cells = (int32_t)(uint32_t)((uint64_t)(uint32_t)w * (uint64_t)(uint32_t)h);
    for (int i = 0; i < GMMRRT_OCCUPANCY_GRID_T_MAX_CELLS; ++i)
        m->data[i] = (int8_t)(i % 102 - 1); /* -1, 0 .. 100 */
}

/* ------------------------------------------------------------------ round trips */

/* Encode, decode through msg_decode.h, re-encode: same bytes. Field checks follow. */
#define ROUNDTRIP(type, fn, orig, out)                                                              \
    do {                                                                                            \
        int n_ = gmmrrt_##type##_encode(g_buf, 0, BUF_CAP, (orig));                                 \
        assert_true(n_ > 0);                                                                        \
        assert_int_equal(n_, gmmrrt_##type##_encoded_size(orig));                                   \
        memset((out), 0xA5, sizeof *(out));                                                         \
        assert_int_equal(fn(g_buf, (size_t)n_, (out), g_err, sizeof g_err), GMMRRT_MSG_OK);         \
        int m_ = gmmrrt_##type##_encode(g_buf2, 0, BUF_CAP, (out));                                 \
        assert_int_equal(m_, n_);                                                                   \
        assert_memory_equal(g_buf, g_buf2, (size_t)n_);                                             \
        RELEASE(out);                                                                               \
    } while (0)

static void test_pose2d_round_trips(void **state)
{
    (void)state;
    gmmrrt_pose2d_t a, b;
    fill_pose(&a);
    ROUNDTRIP(pose2d_t, gmmrrt_msg_decode_pose2d, &a, &b);
    assert_true(b.utime == a.utime);
    assert_true(b.x == a.x && b.y == a.y && b.yaw == a.yaw);
    assert_int_equal(b.velocity_valid, 1);
    assert_true(b.vx == a.vx && b.vy == a.vy && b.yaw_rate == a.yaw_rate);
}

static void test_people_round_trips_all_slots(void **state)
{
    (void)state;
    gmmrrt_people_t a, b;
    fill_people(&a, GMMRRT_PEOPLE_T_MAX_PEOPLE);
    ROUNDTRIP(people_t, gmmrrt_msg_decode_people, &a, &b);
    assert_true(b.utime == a.utime);
    assert_int_equal(b.num_people, GMMRRT_PEOPLE_T_MAX_PEOPLE);
    for (int i = 0; i < GMMRRT_PEOPLE_T_MAX_PEOPLE; ++i) {
        assert_true(b.people[i].utime == a.people[i].utime);
        assert_int_equal(b.people[i].id, a.people[i].id);
        assert_true(b.people[i].x == a.people[i].x && b.people[i].y == a.people[i].y);
        assert_true(b.people[i].yaw == a.people[i].yaw);
        assert_true(b.people[i].vx == a.people[i].vx && b.people[i].vy == a.people[i].vy);
    }
}

static void test_nav_goal_round_trips(void **state)
{
    (void)state;
    gmmrrt_nav_goal_t a, b;
    fill_goal(&a);
    ROUNDTRIP(nav_goal_t, gmmrrt_msg_decode_nav_goal, &a, &b);
    assert_true(b.utime == a.utime && b.x == a.x && b.y == a.y && b.yaw == a.yaw);
    assert_true(b.tolerance_m == a.tolerance_m);
    assert_int_equal(b.task, a.task);
    assert_int_equal(b.target_person_id, a.target_person_id);
}

static void test_obstacles_round_trip_at_capacity(void **state)
{
    (void)state;
    gmmrrt_obstacles_t a, b;
    fill_obstacles(&a, GMMRRT_OBSTACLES_T_MAX_CIRCLES, GMMRRT_OBSTACLES_T_MAX_BOXES);
    ROUNDTRIP(obstacles_t, gmmrrt_msg_decode_obstacles, &a, &b);
    assert_int_equal(b.num_circles, a.num_circles);
    assert_int_equal(b.num_boxes, a.num_boxes);
    for (int i = 0; i < GMMRRT_OBSTACLES_T_MAX_CIRCLES; ++i)
        assert_true(b.circle_x[i] == a.circle_x[i] && b.circle_y[i] == a.circle_y[i] &&
                    b.circle_radius[i] == a.circle_radius[i]);
    for (int i = 0; i < GMMRRT_OBSTACLES_T_MAX_BOXES; ++i)
        assert_true(b.box_x[i] == a.box_x[i] && b.box_y[i] == a.box_y[i] && b.box_width[i] == a.box_width[i] &&
                    b.box_height[i] == a.box_height[i] && b.box_yaw[i] == a.box_yaw[i]);
}

static void test_waypoints_round_trip_at_capacity(void **state)
{
    (void)state;
    gmmrrt_waypoints_t a, b;
    fill_waypoints(&a, GMMRRT_WAYPOINTS_T_MAX_WAYPOINTS);
    ROUNDTRIP(waypoints_t, gmmrrt_msg_decode_waypoints, &a, &b);
    assert_true(b.seq == a.seq);
    assert_int_equal(b.num_waypoints, a.num_waypoints);
    for (int i = 0; i < GMMRRT_WAYPOINTS_T_MAX_WAYPOINTS; ++i)
        assert_true(b.x[i] == a.x[i] && b.y[i] == a.y[i] && b.yaw[i] == a.yaw[i]);
    assert_true(b.total_cost == a.total_cost && b.length_m == a.length_m);
    assert_int_equal(b.planner, a.planner);
    assert_int_equal(b.task, a.task);
    assert_int_equal(b.status, a.status);
}

static void test_empty_plan_round_trips(void **state)
{
    (void)state;
    gmmrrt_waypoints_t a, b;
    fill_waypoints(&a, 0);
    ROUNDTRIP(waypoints_t, gmmrrt_msg_decode_waypoints, &a, &b);
    assert_int_equal(b.num_waypoints, 0);
}

static void test_planner_status_round_trips(void **state)
{
    (void)state;
    gmmrrt_planner_status_t a, b;
    fill_status(&a);
    ROUNDTRIP(planner_status_t, gmmrrt_msg_decode_planner_status, &a, &b);
    assert_int_equal(b.state, a.state);
    assert_int_equal(b.last_error, a.last_error);
    assert_true(b.iterations == a.iterations && b.nodes == a.nodes);
    assert_true(b.first_solution_ms == a.first_solution_ms && b.best_cost == a.best_cost);
    assert_true(b.plan_time_ms == a.plan_time_ms);
    assert_true(b.plans_published == a.plans_published && b.missed_deadlines == a.missed_deadlines);
    for (int i = 0; i < GMMRRT_PLANNER_STATUS_T_NUM_REJECT_REASONS; ++i)
        assert_true(b.rejected[i] == a.rejected[i]);
}

static void test_demo_info_round_trips(void **state)
{
    (void)state;
    gmmrrt_demo_info_t a, b;
    fill_demo(&a);
    ROUNDTRIP(demo_info_t, gmmrrt_msg_decode_demo_info, &a, &b);
    assert_true(b.utime == a.utime);
    assert_int_equal(b.episode, a.episode);
    assert_int_equal(b.task, a.task);
    assert_int_equal(b.homotopy, a.homotopy);
    assert_int_equal(b.person_id, a.person_id);
}

/* ------------------------------------------------------------------ validation rules */

/* Encodes *msg, decodes it, and checks the result and that the error names each of the
 * given substrings (type and field). */
#define EXPECT_REJECT(type, fn, msg, want, s1, s2)                                                  \
    do {                                                                                            \
        int n_ = gmmrrt_##type##_encode(g_buf, 0, BUF_CAP, (msg));                                  \
        assert_true(n_ > 0);                                                                        \
        __typeof__(*(msg)) out_;                                                                    \
        g_err[0] = '\0';                                                                            \
        gmmrrt_msg_result_t r_ = fn(g_buf, (size_t)n_, &out_, g_err, sizeof g_err);                 \
        if (r_ != (want))                                                                           \
            fail_msg("%s:%d: got %s (%s), want %s", __FILE__, __LINE__, gmmrrt_msg_result_str(r_),  \
                     g_err, gmmrrt_msg_result_str(want));                                           \
        if (strstr(g_err, (s1)) == NULL || strstr(g_err, (s2)) == NULL)                             \
            fail_msg("%s:%d: error \"%s\" does not name \"%s\" and \"%s\"", __FILE__, __LINE__,       \
                     g_err, (s1), (s2));                                                            \
    } while (0)

#define EXPECT_OK(type, fn, msg)                                                                    \
    do {                                                                                            \
        int n_ = gmmrrt_##type##_encode(g_buf, 0, BUF_CAP, (msg));                                  \
        __typeof__(*(msg)) out_;                                                                    \
        gmmrrt_msg_result_t r_ = fn(g_buf, (size_t)n_, &out_, g_err, sizeof g_err);                 \
        if (r_ != GMMRRT_MSG_OK)                                                                    \
            fail_msg("%s:%d: rejected: %s", __FILE__, __LINE__, g_err);                             \
        RELEASE(&out_);                                                                             \
    } while (0)

static const double k_bad_numbers[] = {NAN, INFINITY, -INFINITY};
#define N_BAD (sizeof k_bad_numbers / sizeof k_bad_numbers[0])

static void test_planar_scan_round_trips_at_capacity_keeping_no_returns(void **state)
{
    (void)state;
    gmmrrt_planar_scan_t a, b;
    fill_scan(&a, GMMRRT_PLANAR_SCAN_T_MAX_RANGES);
    /* "No return" values are kept as they are, not rejected. */
    a.ranges[0] = NAN;
    a.ranges[1] = INFINITY;
    a.ranges[2] = -INFINITY;
    a.ranges[3] = 1e6f;  /* beyond range_max_m */
    a.ranges[4] = 0.01f; /* below range_min_m */
    a.ranges[5] = -1.0f;
    ROUNDTRIP(planar_scan_t, gmmrrt_msg_decode_planar_scan, &a, &b);
    assert_true(b.utime == a.utime && b.rad0 == a.rad0 && b.radstep == a.radstep);
    assert_true(b.range_min_m == a.range_min_m && b.range_max_m == a.range_max_m);
    assert_true(b.sensor_x == a.sensor_x && b.sensor_y == a.sensor_y && b.sensor_yaw == a.sensor_yaw);
    assert_int_equal(b.num_ranges, GMMRRT_PLANAR_SCAN_T_MAX_RANGES);
    assert_true(isnan(b.ranges[0]) && isinf(b.ranges[1]) && b.ranges[1] > 0 && isinf(b.ranges[2]) && b.ranges[2] < 0);
    for (int i = 3; i < GMMRRT_PLANAR_SCAN_T_MAX_RANGES; ++i)
        assert_true(b.ranges[i] == a.ranges[i]);
}

static void test_planar_scan_rules(void **state)
{
    (void)state;
    gmmrrt_planar_scan_t m;
    const int32_t bad_counts[] = {-1, GMMRRT_PLANAR_SCAN_T_MAX_RANGES + 1, INT32_MIN, INT32_MAX};
    for (size_t i = 0; i < sizeof bad_counts / sizeof bad_counts[0]; ++i) {
        fill_scan(&m, 10);
        m.num_ranges = bad_counts[i];
        EXPECT_REJECT(planar_scan_t, gmmrrt_msg_decode_planar_scan, &m, GMMRRT_MSG_COUNT_OVER_BOUND, "planar_scan_t",
                      "num_ranges");
    }
    for (size_t b = 0; b < N_BAD; ++b) {
        fill_scan(&m, 10); m.rad0 = k_bad_numbers[b];
        EXPECT_REJECT(planar_scan_t, gmmrrt_msg_decode_planar_scan, &m, GMMRRT_MSG_NOT_FINITE, "planar_scan_t", "rad0");
        fill_scan(&m, 10); m.radstep = k_bad_numbers[b];
        EXPECT_REJECT(planar_scan_t, gmmrrt_msg_decode_planar_scan, &m, GMMRRT_MSG_NOT_FINITE, "planar_scan_t",
                      "radstep");
        fill_scan(&m, 10); m.range_min_m = k_bad_numbers[b];
        EXPECT_REJECT(planar_scan_t, gmmrrt_msg_decode_planar_scan, &m, GMMRRT_MSG_NOT_FINITE, "planar_scan_t",
                      "range_min_m");
        fill_scan(&m, 10); m.range_max_m = k_bad_numbers[b];
        EXPECT_REJECT(planar_scan_t, gmmrrt_msg_decode_planar_scan, &m, GMMRRT_MSG_NOT_FINITE, "planar_scan_t",
                      "range_max_m");
        fill_scan(&m, 10); m.sensor_x = k_bad_numbers[b];
        EXPECT_REJECT(planar_scan_t, gmmrrt_msg_decode_planar_scan, &m, GMMRRT_MSG_NOT_FINITE, "planar_scan_t",
                      "sensor_x");
        fill_scan(&m, 10); m.sensor_y = k_bad_numbers[b];
        EXPECT_REJECT(planar_scan_t, gmmrrt_msg_decode_planar_scan, &m, GMMRRT_MSG_NOT_FINITE, "planar_scan_t",
                      "sensor_y");
        fill_scan(&m, 10); m.sensor_yaw = k_bad_numbers[b];
        EXPECT_REJECT(planar_scan_t, gmmrrt_msg_decode_planar_scan, &m, GMMRRT_MSG_NOT_FINITE, "planar_scan_t",
                      "sensor_yaw");
    }
    /* Finite rad0 and radstep whose last beam overflows. */
    fill_scan(&m, 10); m.rad0 = 1e308; m.radstep = 1e308;
    EXPECT_REJECT(planar_scan_t, gmmrrt_msg_decode_planar_scan, &m, GMMRRT_MSG_NOT_FINITE, "planar_scan_t",
                  "last beam");
    fill_scan(&m, 10); m.range_min_m = -0.1;
    EXPECT_REJECT(planar_scan_t, gmmrrt_msg_decode_planar_scan, &m, GMMRRT_MSG_BAD_VALUE, "planar_scan_t",
                  "range_min_m");
    fill_scan(&m, 10); m.range_max_m = m.range_min_m;
    EXPECT_REJECT(planar_scan_t, gmmrrt_msg_decode_planar_scan, &m, GMMRRT_MSG_BAD_VALUE, "planar_scan_t",
                  "range_max_m");
    /* Every range NaN is a valid scan with no return; so is an empty one; slots beyond the
     * count are not looked at. */
    fill_scan(&m, 100);
    for (int i = 0; i < 100; ++i)
        m.ranges[i] = NAN;
    EXPECT_OK(planar_scan_t, gmmrrt_msg_decode_planar_scan, &m);
    fill_scan(&m, 0);
    m.rad0 = 1e308; m.radstep = 1e308; /* no beam: no last angle */
    EXPECT_OK(planar_scan_t, gmmrrt_msg_decode_planar_scan, &m);
}

static void test_occupancy_grid_round_trips_at_capacity(void **state)
{
    (void)state;
    static gmmrrt_occupancy_grid_t a, b;
    fill_grid(&a, 256, 256);
    ROUNDTRIP(occupancy_grid_t, gmmrrt_msg_decode_occupancy_grid, &a, &b);
    assert_true(b.utime == a.utime && b.resolution_m == a.resolution_m && b.origin_x == a.origin_x &&
                b.origin_y == a.origin_y && b.origin_yaw == a.origin_yaw);
    assert_int_equal(b.width, 256);
    assert_int_equal(b.height, 256);
    assert_int_equal(b.num_cells, GMMRRT_OCCUPANCY_GRID_T_MAX_CELLS);
    assert_memory_equal(a.data, b.data, sizeof a.data);
    assert_null(b.frame); /* released by ROUNDTRIP, as for every framed type */
}

static void test_occupancy_grid_rules(void **state)
{
    (void)state;
    static gmmrrt_occupancy_grid_t m;
    fill_grid(&m, 300, 300);
    m.num_cells = GMMRRT_OCCUPANCY_GRID_T_MAX_CELLS;
    EXPECT_REJECT(occupancy_grid_t, gmmrrt_msg_decode_occupancy_grid, &m, GMMRRT_MSG_COUNT_OVER_BOUND,
                  "occupancy_grid_t", "MAX_CELLS");
    fill_grid(&m, 65536, 65536); /* the product overflows 32 bits */
    EXPECT_REJECT(occupancy_grid_t, gmmrrt_msg_decode_occupancy_grid, &m, GMMRRT_MSG_COUNT_OVER_BOUND,
                  "occupancy_grid_t", "MAX_CELLS");
    const int32_t bad_sides[][2] = {{0, 5}, {5, 0}, {-1, 5}, {5, INT32_MIN}};
    for (size_t i = 0; i < sizeof bad_sides / sizeof bad_sides[0]; ++i) {
        fill_grid(&m, bad_sides[i][0], bad_sides[i][1]);
        EXPECT_REJECT(occupancy_grid_t, gmmrrt_msg_decode_occupancy_grid, &m, GMMRRT_MSG_BAD_VALUE,
                      "occupancy_grid_t", "width");
    }
    fill_grid(&m, 10, 10); m.num_cells = 99;
    EXPECT_REJECT(occupancy_grid_t, gmmrrt_msg_decode_occupancy_grid, &m, GMMRRT_MSG_BAD_VALUE, "occupancy_grid_t",
                  "num_cells");
    for (size_t b = 0; b < N_BAD; ++b) {
        fill_grid(&m, 10, 10); m.resolution_m = k_bad_numbers[b];
        EXPECT_REJECT(occupancy_grid_t, gmmrrt_msg_decode_occupancy_grid, &m, GMMRRT_MSG_NOT_FINITE,
                      "occupancy_grid_t", "resolution_m");
        fill_grid(&m, 10, 10); m.origin_x = k_bad_numbers[b];
        EXPECT_REJECT(occupancy_grid_t, gmmrrt_msg_decode_occupancy_grid, &m, GMMRRT_MSG_NOT_FINITE,
                      "occupancy_grid_t", "origin_x");
        fill_grid(&m, 10, 10); m.origin_y = k_bad_numbers[b];
        EXPECT_REJECT(occupancy_grid_t, gmmrrt_msg_decode_occupancy_grid, &m, GMMRRT_MSG_NOT_FINITE,
                      "occupancy_grid_t", "origin_y");
        fill_grid(&m, 10, 10); m.origin_yaw = k_bad_numbers[b];
        EXPECT_REJECT(occupancy_grid_t, gmmrrt_msg_decode_occupancy_grid, &m, GMMRRT_MSG_NOT_FINITE,
                      "occupancy_grid_t", "origin_yaw");
    }
    fill_grid(&m, 10, 10); m.resolution_m = 0.0;
    EXPECT_REJECT(occupancy_grid_t, gmmrrt_msg_decode_occupancy_grid, &m, GMMRRT_MSG_BAD_VALUE, "occupancy_grid_t",
                  "resolution_m");
    fill_grid(&m, 10, 10); m.data[57] = 101;
    EXPECT_REJECT(occupancy_grid_t, gmmrrt_msg_decode_occupancy_grid, &m, GMMRRT_MSG_BAD_VALUE, "occupancy_grid_t",
                  "data[57]");
    fill_grid(&m, 10, 10); m.data[3] = -2;
    EXPECT_REJECT(occupancy_grid_t, gmmrrt_msg_decode_occupancy_grid, &m, GMMRRT_MSG_BAD_VALUE, "occupancy_grid_t",
                  "cell 3, 0");
    /* Cells beyond the count are not looked at. Which frame is right is the receiver's to say
     * (any valid name decodes; gmmrrtd compares it with its [world] frame). */
    fill_grid(&m, 10, 10); m.frame = (char *)"odom"; m.data[100] = 127;
    EXPECT_OK(occupancy_grid_t, gmmrrt_msg_decode_occupancy_grid, &m);
}

static void test_pose2d_non_finite_fields_are_rejected(void **state)
{
    (void)state;
    for (size_t b = 0; b < N_BAD; ++b) {
        gmmrrt_pose2d_t m;
        fill_pose(&m); m.x = k_bad_numbers[b];
        EXPECT_REJECT(pose2d_t, gmmrrt_msg_decode_pose2d, &m, GMMRRT_MSG_NOT_FINITE, "pose2d_t", "x");
        fill_pose(&m); m.y = k_bad_numbers[b];
        EXPECT_REJECT(pose2d_t, gmmrrt_msg_decode_pose2d, &m, GMMRRT_MSG_NOT_FINITE, "pose2d_t", "y");
        fill_pose(&m); m.yaw = k_bad_numbers[b];
        EXPECT_REJECT(pose2d_t, gmmrrt_msg_decode_pose2d, &m, GMMRRT_MSG_NOT_FINITE, "pose2d_t", "yaw");
        fill_pose(&m); m.vx = k_bad_numbers[b];
        EXPECT_REJECT(pose2d_t, gmmrrt_msg_decode_pose2d, &m, GMMRRT_MSG_NOT_FINITE, "pose2d_t", "vx");
        fill_pose(&m); m.vy = k_bad_numbers[b];
        EXPECT_REJECT(pose2d_t, gmmrrt_msg_decode_pose2d, &m, GMMRRT_MSG_NOT_FINITE, "pose2d_t", "vy");
        fill_pose(&m); m.yaw_rate = k_bad_numbers[b];
        EXPECT_REJECT(pose2d_t, gmmrrt_msg_decode_pose2d, &m, GMMRRT_MSG_NOT_FINITE, "pose2d_t", "yaw_rate");
    }
}

static void test_pose2d_velocity_is_ignored_when_not_valid(void **state)
{
    (void)state;
    gmmrrt_pose2d_t m;
    fill_pose(&m);
    m.velocity_valid = 0;
    m.vx = NAN;
    m.vy = INFINITY;
    m.yaw_rate = NAN;
    EXPECT_OK(pose2d_t, gmmrrt_msg_decode_pose2d, &m);
}

static void test_people_count_out_of_bounds_is_rejected(void **state)
{
    (void)state;
    const int32_t bad[] = {-1, INT32_MIN, GMMRRT_PEOPLE_T_MAX_PEOPLE + 1, INT32_MAX};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        gmmrrt_people_t m;
        fill_people(&m, bad[i]);
        EXPECT_REJECT(people_t, gmmrrt_msg_decode_people, &m, GMMRRT_MSG_COUNT_OVER_BOUND, "people_t",
                      "num_people");
    }
    gmmrrt_people_t m;
    fill_people(&m, 0);
    EXPECT_OK(people_t, gmmrrt_msg_decode_people, &m);
}

static void test_people_non_finite_and_negative_id_are_rejected(void **state)
{
    (void)state;
    static const char *fields[] = {"x", "y", "yaw", "vx", "vy"};
    for (size_t b = 0; b < N_BAD; ++b) {
        for (size_t f = 0; f < 5; ++f) {
            gmmrrt_people_t m;
            fill_people(&m, 5);
            gmmrrt_person_t *p = &m.people[4];
            double *slot[] = {&p->x, &p->y, &p->yaw, &p->vx, &p->vy};
            *slot[f] = k_bad_numbers[b];
            char want[64];
            snprintf(want, sizeof want, "people[4].%s", fields[f]);
            EXPECT_REJECT(people_t, gmmrrt_msg_decode_people, &m, GMMRRT_MSG_NOT_FINITE, "people_t", want);
        }
    }
    gmmrrt_people_t m;
    fill_people(&m, 3);
    m.people[2].id = -1;
    EXPECT_REJECT(people_t, gmmrrt_msg_decode_people, &m, GMMRRT_MSG_BAD_VALUE, "people_t", "people[2].id");
}

static void test_people_slots_beyond_count_are_not_validated(void **state)
{
    (void)state;
    gmmrrt_people_t m;
    fill_people(&m, 2);
    m.people[2].x = NAN;
    m.people[3].id = -5;
    EXPECT_OK(people_t, gmmrrt_msg_decode_people, &m);
}

static void test_nav_goal_rules(void **state)
{
    (void)state;
    gmmrrt_nav_goal_t m;
    for (size_t b = 0; b < N_BAD; ++b) {
        fill_goal(&m); m.x = k_bad_numbers[b];
        EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_NOT_FINITE, "nav_goal_t", "x");
        fill_goal(&m); m.y = k_bad_numbers[b];
        EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_NOT_FINITE, "nav_goal_t", "y");
        fill_goal(&m); m.yaw = k_bad_numbers[b];
        EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_NOT_FINITE, "nav_goal_t", "yaw");
        fill_goal(&m); m.tolerance_m = k_bad_numbers[b];
        EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_NOT_FINITE, "nav_goal_t",
                      "tolerance_m");
    }
    fill_goal(&m); m.tolerance_m = 0.0;
    EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_BAD_VALUE, "nav_goal_t", "tolerance_m");
    fill_goal(&m); m.tolerance_m = -0.5;
    EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_BAD_VALUE, "nav_goal_t", "tolerance_m");
    fill_goal(&m); m.task = 3;
    EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_BAD_VALUE, "nav_goal_t", "task");
    fill_goal(&m); m.task = -1;
    EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_BAD_VALUE, "nav_goal_t", "task");
    fill_goal(&m); m.task = GMMRRT_NAV_GOAL_T_TASK_APPROACH; m.target_person_id = -1;
    EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_BAD_VALUE, "nav_goal_t",
                  "target_person_id");
    /* Avoid and none do not need a target. */
    fill_goal(&m); m.task = GMMRRT_NAV_GOAL_T_TASK_AVOID; m.target_person_id = -1;
    EXPECT_OK(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m);
    fill_goal(&m); m.task = GMMRRT_NAV_GOAL_T_TASK_NONE; m.target_person_id = -1;
    EXPECT_OK(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m);
}

static void test_obstacles_counts_out_of_bounds_are_rejected(void **state)
{
    (void)state;
    const int32_t bad[] = {-1, INT32_MIN, 65, INT32_MAX};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        gmmrrt_obstacles_t m;
        fill_obstacles(&m, bad[i], 1);
        EXPECT_REJECT(obstacles_t, gmmrrt_msg_decode_obstacles, &m, GMMRRT_MSG_COUNT_OVER_BOUND, "obstacles_t",
                      "num_circles");
        fill_obstacles(&m, 1, bad[i]);
        EXPECT_REJECT(obstacles_t, gmmrrt_msg_decode_obstacles, &m, GMMRRT_MSG_COUNT_OVER_BOUND, "obstacles_t",
                      "num_boxes");
    }
}

static void test_obstacles_non_finite_and_sizes_are_rejected(void **state)
{
    (void)state;
    gmmrrt_obstacles_t m;
    for (size_t b = 0; b < N_BAD; ++b) {
        const double v = k_bad_numbers[b];
        fill_obstacles(&m, 3, 3); m.circle_x[2] = v;
        EXPECT_REJECT(obstacles_t, gmmrrt_msg_decode_obstacles, &m, GMMRRT_MSG_NOT_FINITE, "obstacles_t", "circle_x[2]");
        fill_obstacles(&m, 3, 3); m.circle_y[1] = v;
        EXPECT_REJECT(obstacles_t, gmmrrt_msg_decode_obstacles, &m, GMMRRT_MSG_NOT_FINITE, "obstacles_t", "circle_y[1]");
        fill_obstacles(&m, 3, 3); m.circle_radius[0] = v;
        EXPECT_REJECT(obstacles_t, gmmrrt_msg_decode_obstacles, &m, GMMRRT_MSG_NOT_FINITE, "obstacles_t",
                      "circle_radius[0]");
        fill_obstacles(&m, 3, 3); m.box_x[2] = v;
        EXPECT_REJECT(obstacles_t, gmmrrt_msg_decode_obstacles, &m, GMMRRT_MSG_NOT_FINITE, "obstacles_t", "box_x[2]");
        fill_obstacles(&m, 3, 3); m.box_y[2] = v;
        EXPECT_REJECT(obstacles_t, gmmrrt_msg_decode_obstacles, &m, GMMRRT_MSG_NOT_FINITE, "obstacles_t", "box_y[2]");
        fill_obstacles(&m, 3, 3); m.box_width[1] = v;
        EXPECT_REJECT(obstacles_t, gmmrrt_msg_decode_obstacles, &m, GMMRRT_MSG_NOT_FINITE, "obstacles_t",
                      "box_width[1]");
        fill_obstacles(&m, 3, 3); m.box_height[1] = v;
        EXPECT_REJECT(obstacles_t, gmmrrt_msg_decode_obstacles, &m, GMMRRT_MSG_NOT_FINITE, "obstacles_t",
                      "box_height[1]");
        fill_obstacles(&m, 3, 3); m.box_yaw[0] = v;
        EXPECT_REJECT(obstacles_t, gmmrrt_msg_decode_obstacles, &m, GMMRRT_MSG_NOT_FINITE, "obstacles_t", "box_yaw[0]");
    }
    const double nonpositive[] = {0.0, -0.1};
    for (size_t i = 0; i < 2; ++i) {
        fill_obstacles(&m, 3, 3); m.circle_radius[2] = nonpositive[i];
        EXPECT_REJECT(obstacles_t, gmmrrt_msg_decode_obstacles, &m, GMMRRT_MSG_BAD_VALUE, "obstacles_t",
                      "circle_radius[2]");
        fill_obstacles(&m, 3, 3); m.box_width[2] = nonpositive[i];
        EXPECT_REJECT(obstacles_t, gmmrrt_msg_decode_obstacles, &m, GMMRRT_MSG_BAD_VALUE, "obstacles_t",
                      "box_width[2]");
        fill_obstacles(&m, 3, 3); m.box_height[2] = nonpositive[i];
        EXPECT_REJECT(obstacles_t, gmmrrt_msg_decode_obstacles, &m, GMMRRT_MSG_BAD_VALUE, "obstacles_t",
                      "box_height[2]");
    }
    /* Slots beyond the counts are not looked at. */
    fill_obstacles(&m, 3, 3);
    m.circle_radius[3] = -1.0;
    m.box_x[3] = NAN;
    EXPECT_OK(obstacles_t, gmmrrt_msg_decode_obstacles, &m);
}

static void test_waypoints_rules(void **state)
{
    (void)state;
    gmmrrt_waypoints_t m;
    const int32_t bad[] = {-1, GMMRRT_WAYPOINTS_T_MAX_WAYPOINTS + 1, INT32_MAX};
    for (size_t i = 0; i < 3; ++i) {
        fill_waypoints(&m, bad[i]);
        EXPECT_REJECT(waypoints_t, gmmrrt_msg_decode_waypoints, &m, GMMRRT_MSG_COUNT_OVER_BOUND, "waypoints_t",
                      "num_waypoints");
    }
    for (size_t b = 0; b < N_BAD; ++b) {
        fill_waypoints(&m, 10); m.x[9] = k_bad_numbers[b];
        EXPECT_REJECT(waypoints_t, gmmrrt_msg_decode_waypoints, &m, GMMRRT_MSG_NOT_FINITE, "waypoints_t", "x[9]");
        fill_waypoints(&m, 10); m.y[0] = k_bad_numbers[b];
        EXPECT_REJECT(waypoints_t, gmmrrt_msg_decode_waypoints, &m, GMMRRT_MSG_NOT_FINITE, "waypoints_t", "y[0]");
        fill_waypoints(&m, 10); m.yaw[5] = k_bad_numbers[b];
        EXPECT_REJECT(waypoints_t, gmmrrt_msg_decode_waypoints, &m, GMMRRT_MSG_NOT_FINITE, "waypoints_t", "yaw[5]");
    }
    fill_waypoints(&m, 10); m.planner = 4;
    EXPECT_REJECT(waypoints_t, gmmrrt_msg_decode_waypoints, &m, GMMRRT_MSG_BAD_VALUE, "waypoints_t", "planner");
    fill_waypoints(&m, 10); m.task = -1;
    EXPECT_REJECT(waypoints_t, gmmrrt_msg_decode_waypoints, &m, GMMRRT_MSG_BAD_VALUE, "waypoints_t", "task");
    fill_waypoints(&m, 10); m.x[10] = NAN;
    EXPECT_OK(waypoints_t, gmmrrt_msg_decode_waypoints, &m);
}

static void test_planner_status_bad_state_is_rejected(void **state)
{
    (void)state;
    gmmrrt_planner_status_t m;
    fill_status(&m); m.state = -1;
    EXPECT_REJECT(planner_status_t, gmmrrt_msg_decode_planner_status, &m, GMMRRT_MSG_BAD_VALUE, "planner_status_t",
                  "state");
    fill_status(&m); m.state = GMMRRT_PLANNER_STATUS_T_STATE_ERROR + 1;
    EXPECT_REJECT(planner_status_t, gmmrrt_msg_decode_planner_status, &m, GMMRRT_MSG_BAD_VALUE, "planner_status_t",
                  "state");
    /* The goal's life fields: each enum's range. */
    fill_status(&m); m.goal_state = GMMRRT_PLANNER_STATUS_T_GOAL_FAILED + 1;
    EXPECT_REJECT(planner_status_t, gmmrrt_msg_decode_planner_status, &m, GMMRRT_MSG_BAD_VALUE, "planner_status_t",
                  "goal_state");
    fill_status(&m); m.goal_failure = -1;
    EXPECT_REJECT(planner_status_t, gmmrrt_msg_decode_planner_status, &m, GMMRRT_MSG_BAD_VALUE, "planner_status_t",
                  "goal_failure");
    fill_status(&m); m.side_result = GMMRRT_PLANNER_STATUS_T_SIDE_NOT_FOUND + 1;
    EXPECT_REJECT(planner_status_t, gmmrrt_msg_decode_planner_status, &m, GMMRRT_MSG_BAD_VALUE, "planner_status_t",
                  "side_result");
}

static void test_demo_info_rules(void **state)
{
    (void)state;
    gmmrrt_demo_info_t m;
    fill_demo(&m); m.task = 3;
    EXPECT_REJECT(demo_info_t, gmmrrt_msg_decode_demo_info, &m, GMMRRT_MSG_BAD_VALUE, "demo_info_t", "task");
    fill_demo(&m); m.homotopy = 4;
    EXPECT_REJECT(demo_info_t, gmmrrt_msg_decode_demo_info, &m, GMMRRT_MSG_BAD_VALUE, "demo_info_t", "homotopy");
    fill_demo(&m); m.homotopy = -1;
    EXPECT_REJECT(demo_info_t, gmmrrt_msg_decode_demo_info, &m, GMMRRT_MSG_BAD_VALUE, "demo_info_t", "homotopy");
    fill_demo(&m); m.episode = -1;
    EXPECT_REJECT(demo_info_t, gmmrrt_msg_decode_demo_info, &m, GMMRRT_MSG_BAD_VALUE, "demo_info_t", "episode");
}

/* The goal's life fields: an unknown command is its own result, judged before anything else; a
 * CANCEL is read for its id only; the id must be > 0; the heading tolerance is in [0, pi]; the
 * side is one of three. */
static void test_nav_goal_command_id_side_and_yaw_tolerance_rules(void **state)
{
    (void)state;
    gmmrrt_nav_goal_t m;
    const int8_t bad_commands[] = {0, 3, -1, 127};
    for (size_t i = 0; i < sizeof bad_commands; ++i) {
        fill_goal(&m); m.command = bad_commands[i]; m.x = NAN;
        EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_UNKNOWN_COMMAND, "nav_goal_t", "command");
    }
    const int64_t bad_ids[] = {0, -1, INT64_MIN};
    for (size_t i = 0; i < sizeof bad_ids / sizeof bad_ids[0]; ++i) {
        fill_goal(&m); m.goal_id = bad_ids[i];
        EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_BAD_VALUE, "nav_goal_t", "goal_id");
        fill_goal(&m); m.goal_id = bad_ids[i]; m.command = GMMRRT_NAV_GOAL_T_COMMAND_CANCEL;
        EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_BAD_VALUE, "nav_goal_t", "goal_id");
    }
    /* A CANCEL needs no position, tolerance or task. */
    fill_goal(&m); m.command = GMMRRT_NAV_GOAL_T_COMMAND_CANCEL; m.x = NAN; m.tolerance_m = 0.0; m.task = 9;
    EXPECT_OK(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m);
    for (size_t b = 0; b < N_BAD; ++b) {
        fill_goal(&m); m.yaw_tolerance_rad = k_bad_numbers[b];
        EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_NOT_FINITE, "nav_goal_t",
                      "yaw_tolerance_rad");
    }
    fill_goal(&m); m.yaw_tolerance_rad = -0.01;
    EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_BAD_VALUE, "nav_goal_t", "yaw_tolerance_rad");
    fill_goal(&m); m.yaw_tolerance_rad = 3.2;
    EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_BAD_VALUE, "nav_goal_t", "yaw_tolerance_rad");
    fill_goal(&m); m.yaw_tolerance_rad = 0.0; /* heading not judged */
    EXPECT_OK(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m);
    fill_goal(&m); m.yaw_tolerance_rad = M_PI;
    EXPECT_OK(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m);
    const int8_t sides[] = {-1, 0, 1};
    for (size_t i = 0; i < sizeof sides; ++i) {
        fill_goal(&m); m.preferred_side = sides[i];
        EXPECT_OK(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m);
    }
    fill_goal(&m); m.preferred_side = 2;
    EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_BAD_VALUE, "nav_goal_t", "preferred_side");
    fill_goal(&m); m.preferred_side = -2;
    EXPECT_REJECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &m, GMMRRT_MSG_BAD_VALUE, "nav_goal_t", "preferred_side");
}

/* Frames, on every type that has one: 1..64 printable bytes without spaces; a 64-byte name
 * round-trips; the frame's length on the wire is judged before anything is allocated (a length
 * of 2^31 - 1 in a 40-byte message is refused, not allocated); the receiver's frame check. */
#define EXPECT_FRAME_RULES(type, fn, msg)                                                           \
    do {                                                                                            \
        char name_[80];                                                                             \
        memset(name_, 'a', sizeof name_);                                                           \
        name_[GMMRRT_MSG_FRAME_MAX] = '\0';                                                         \
        (msg)->frame = name_;                                                                       \
        EXPECT_OK(type, fn, (msg));                                                                 \
        name_[GMMRRT_MSG_FRAME_MAX] = 'a';                                                          \
        name_[GMMRRT_MSG_FRAME_MAX + 1] = '\0';                                                     \
        EXPECT_REJECT(type, fn, (msg), GMMRRT_MSG_BAD_VALUE, #type, "frame");                       \
        (msg)->frame = (char *)"";                                                                  \
        EXPECT_REJECT(type, fn, (msg), GMMRRT_MSG_BAD_VALUE, #type, "frame");                       \
        (msg)->frame = (char *)"base link";                                                         \
        EXPECT_REJECT(type, fn, (msg), GMMRRT_MSG_BAD_VALUE, #type, "frame");                       \
        (msg)->frame = (char *)"odom\t";                                                            \
        EXPECT_REJECT(type, fn, (msg), GMMRRT_MSG_BAD_VALUE, #type, "frame");                       \
        (msg)->frame = (char *)"/map";                                                              \
        EXPECT_OK(type, fn, (msg));                                                                 \
        int n_ = gmmrrt_##type##_encode(g_buf, 0, BUF_CAP, (msg));                                  \
        g_buf[16] = 0x7f; g_buf[17] = g_buf[18] = g_buf[19] = 0xff; /* length 2^31 - 1 */           \
        __typeof__(*(msg)) o_;                                                                      \
        memset(&o_, 0, sizeof o_); /* a refused decode must leave no frame allocated */             \
        assert_int_equal(fn(g_buf, 40, &o_, g_err, sizeof g_err), GMMRRT_MSG_DECODE_FAILED);         \
        assert_int_equal(fn(g_buf, (size_t)n_, &o_, g_err, sizeof g_err), GMMRRT_MSG_DECODE_FAILED); \
        assert_null(o_.frame == NULL ? NULL : "held");                                              \
        g_buf[16] = 0x80; /* negative */                                                            \
        assert_int_equal(fn(g_buf, (size_t)n_, &o_, g_err, sizeof g_err), GMMRRT_MSG_DECODE_FAILED); \
        n_ = gmmrrt_##type##_encode(g_buf, 0, BUF_CAP, (msg));                                      \
        g_buf[24] = (uint8_t)'x'; /* the NUL of "/map" */                                           \
        assert_int_equal(fn(g_buf, (size_t)n_, &o_, g_err, sizeof g_err), GMMRRT_MSG_DECODE_FAILED); \
        assert_non_null(strstr(g_err, "NUL"));                                                      \
    } while (0)

static void test_frames_are_bounded_printable_and_judged_before_allocation(void **state)
{
    (void)state;
    gmmrrt_pose2d_t pose; fill_pose(&pose);
    EXPECT_FRAME_RULES(pose2d_t, gmmrrt_msg_decode_pose2d, &pose);
    gmmrrt_people_t people; fill_people(&people, 2);
    EXPECT_FRAME_RULES(people_t, gmmrrt_msg_decode_people, &people);
    gmmrrt_nav_goal_t goal; fill_goal(&goal);
    EXPECT_FRAME_RULES(nav_goal_t, gmmrrt_msg_decode_nav_goal, &goal);
    gmmrrt_obstacles_t obs; fill_obstacles(&obs, 1, 1);
    EXPECT_FRAME_RULES(obstacles_t, gmmrrt_msg_decode_obstacles, &obs);
    gmmrrt_waypoints_t wp; fill_waypoints(&wp, 2);
    EXPECT_FRAME_RULES(waypoints_t, gmmrrt_msg_decode_waypoints, &wp);
    static gmmrrt_occupancy_grid_t grid; fill_grid(&grid, 3, 2);
    EXPECT_FRAME_RULES(occupancy_grid_t, gmmrrt_msg_decode_occupancy_grid, &grid);

    /* A rejection after the frame was allocated holds nothing (ASan's leak check). */
    fill_pose(&pose); pose.x = NAN;
    int n = gmmrrt_pose2d_t_encode(g_buf, 0, BUF_CAP, &pose);
    gmmrrt_pose2d_t out;
    assert_int_equal(gmmrrt_msg_decode_pose2d(g_buf, (size_t)n, &out, g_err, sizeof g_err), GMMRRT_MSG_NOT_FINITE);
    assert_null(out.frame);
    /* An accepted one holds its frame until released; a second release is a no-op. */
    fill_pose(&pose);
    n = gmmrrt_pose2d_t_encode(g_buf, 0, BUF_CAP, &pose);
    assert_int_equal(gmmrrt_msg_decode_pose2d(g_buf, (size_t)n, &out, g_err, sizeof g_err), GMMRRT_MSG_OK);
    assert_string_equal(out.frame, "map");
    assert_int_equal(gmmrrt_msg_check_frame("pose2d_t", out.frame, "map", g_err, sizeof g_err), GMMRRT_MSG_OK);
    assert_int_equal(gmmrrt_msg_check_frame("pose2d_t", out.frame, "odom", g_err, sizeof g_err),
                     GMMRRT_MSG_WRONG_FRAME);
    assert_non_null(strstr(g_err, "pose2d_t.frame \"map\""));
    assert_non_null(strstr(g_err, "\"odom\""));
    assert_int_equal(gmmrrt_msg_check_frame("pose2d_t", "map2", "map", g_err, sizeof g_err), GMMRRT_MSG_WRONG_FRAME);
    assert_int_equal(gmmrrt_msg_check_frame(NULL, NULL, "map", g_err, sizeof g_err), GMMRRT_MSG_WRONG_FRAME);
    gmmrrt_msg_release_pose2d(&out);
    assert_null(out.frame);
    gmmrrt_msg_release_pose2d(&out);
    gmmrrt_msg_release_pose2d(NULL);
    /* The setting's rule is the same rule. */
    assert_int_equal(gmmrrt_msg_check_frame_name("map", g_err, sizeof g_err), GMMRRT_MSG_OK);
    assert_int_equal(gmmrrt_msg_check_frame_name("", g_err, sizeof g_err), GMMRRT_MSG_BAD_VALUE);
    assert_int_equal(gmmrrt_msg_check_frame_name("my map", g_err, sizeof g_err), GMMRRT_MSG_BAD_VALUE);
    assert_int_equal(gmmrrt_msg_check_frame_name(NULL, g_err, sizeof g_err), GMMRRT_MSG_BAD_VALUE);
}

/* ------------------------------------------------------------------ wire faults */

/* Every prefix shorter than the encoding is DECODE_FAILED with the type named. The prefix
 * is copied into an exactly-sized heap block so ASan catches any read past its end. */
#define EXPECT_EVERY_TRUNCATION_FAILS(type, fn, msg)                                                \
    do {                                                                                            \
        int n_ = gmmrrt_##type##_encode(g_buf, 0, BUF_CAP, (msg));                                  \
        assert_true(n_ > 0);                                                                        \
        __typeof__(*(msg)) out_;                                                                    \
        for (int len_ = 0; len_ < n_; ++len_) {                                                     \
            uint8_t *copy_ = malloc(len_ > 0 ? (size_t)len_ : 1);                                   \
            assert_non_null(copy_);                                                                 \
            memcpy(copy_, g_buf, (size_t)len_);                                                     \
            g_err[0] = '\0';                                                                        \
            gmmrrt_msg_result_t r_ = fn(copy_, (size_t)len_, &out_, g_err, sizeof g_err);            \
            free(copy_);                                                                            \
            if (r_ != GMMRRT_MSG_DECODE_FAILED || strstr(g_err, #type) == NULL)                     \
                fail_msg("%s truncated to %d of %d bytes: got %s (%s)", #type, len_, n_,            \
                         gmmrrt_msg_result_str(r_), g_err);                                         \
        }                                                                                           \
    } while (0)

static void test_every_truncation_is_rejected(void **state)
{
    (void)state;
    gmmrrt_pose2d_t pose; fill_pose(&pose);
    EXPECT_EVERY_TRUNCATION_FAILS(pose2d_t, gmmrrt_msg_decode_pose2d, &pose);
    gmmrrt_people_t people; fill_people(&people, 4);
    EXPECT_EVERY_TRUNCATION_FAILS(people_t, gmmrrt_msg_decode_people, &people);
    gmmrrt_nav_goal_t goal; fill_goal(&goal);
    EXPECT_EVERY_TRUNCATION_FAILS(nav_goal_t, gmmrrt_msg_decode_nav_goal, &goal);
    gmmrrt_obstacles_t obs; fill_obstacles(&obs, 2, 2);
    EXPECT_EVERY_TRUNCATION_FAILS(obstacles_t, gmmrrt_msg_decode_obstacles, &obs);
    gmmrrt_waypoints_t wp; fill_waypoints(&wp, 5);
    EXPECT_EVERY_TRUNCATION_FAILS(waypoints_t, gmmrrt_msg_decode_waypoints, &wp);
    gmmrrt_planner_status_t st; fill_status(&st);
    EXPECT_EVERY_TRUNCATION_FAILS(planner_status_t, gmmrrt_msg_decode_planner_status, &st);
    gmmrrt_demo_info_t demo; fill_demo(&demo);
    EXPECT_EVERY_TRUNCATION_FAILS(demo_info_t, gmmrrt_msg_decode_demo_info, &demo);
    gmmrrt_planar_scan_t scan; fill_scan(&scan, 3);
    EXPECT_EVERY_TRUNCATION_FAILS(planar_scan_t, gmmrrt_msg_decode_planar_scan, &scan);
    /* A grid is 64 KiB on the wire: every cut in its header (the frame string included), the end, and
     * every 97th inside the cells. */
    static gmmrrt_occupancy_grid_t grid, grid_out;
    fill_grid(&grid, 4, 4);
    const int n = gmmrrt_occupancy_grid_t_encode(g_buf, 0, BUF_CAP, &grid);
    assert_true(n > 0);
    for (int len = 0; len < n; len += (len < 128 || len > n - 128) ? 1 : 97) {
        memcpy(g_buf2, g_buf, (size_t)len);
        g_err[0] = '\0';
        const gmmrrt_msg_result_t r = gmmrrt_msg_decode_occupancy_grid(g_buf2, (size_t)len, &grid_out, g_err, sizeof g_err);
        if (r != GMMRRT_MSG_DECODE_FAILED || strstr(g_err, "occupancy_grid_t") == NULL)
            fail_msg("occupancy_grid_t truncated to %d of %d bytes: got %s (%s)", len, n, gmmrrt_msg_result_str(r), g_err);
    }
}

static void test_wrong_fingerprint_is_rejected(void **state)
{
    (void)state;
    /* A pose on the goal's decoder: same kind of bytes, other fingerprint. */
    gmmrrt_pose2d_t pose;
    fill_pose(&pose);
    int n = gmmrrt_pose2d_t_encode(g_buf, 0, BUF_CAP, &pose);
    gmmrrt_nav_goal_t goal;
    assert_int_equal(gmmrrt_msg_decode_nav_goal(g_buf, (size_t)n, &goal, g_err, sizeof g_err),
                     GMMRRT_MSG_DECODE_FAILED);
    assert_non_null(strstr(g_err, "nav_goal_t"));

    /* Every single-bit flip in the 8-byte fingerprint of every type. */
    gmmrrt_people_t people; fill_people(&people, 1);
    gmmrrt_obstacles_t obs; fill_obstacles(&obs, 1, 1);
    gmmrrt_waypoints_t wp; fill_waypoints(&wp, 1);
    gmmrrt_planner_status_t st; fill_status(&st);
    gmmrrt_demo_info_t demo; fill_demo(&demo);
    gmmrrt_planar_scan_t scan; fill_scan(&scan, 3);
    static gmmrrt_occupancy_grid_t grid; fill_grid(&grid, 4, 4);
    fill_goal(&goal);
    for (int bit = 0; bit < 64; ++bit) {
        const int byte = bit / 8, mask = 1 << (bit % 8);
#define FLIP_AND_EXPECT(type, fn, msg)                                                              \
    do {                                                                                            \
        int k_ = gmmrrt_##type##_encode(g_buf, 0, BUF_CAP, (msg));                                  \
        g_buf[byte] ^= (uint8_t)mask;                                                               \
        __typeof__(*(msg)) o_;                                                                      \
        assert_int_equal(fn(g_buf, (size_t)k_, &o_, g_err, sizeof g_err), GMMRRT_MSG_DECODE_FAILED); \
    } while (0)
        FLIP_AND_EXPECT(pose2d_t, gmmrrt_msg_decode_pose2d, &pose);
        FLIP_AND_EXPECT(people_t, gmmrrt_msg_decode_people, &people);
        FLIP_AND_EXPECT(nav_goal_t, gmmrrt_msg_decode_nav_goal, &goal);
        FLIP_AND_EXPECT(obstacles_t, gmmrrt_msg_decode_obstacles, &obs);
        FLIP_AND_EXPECT(waypoints_t, gmmrrt_msg_decode_waypoints, &wp);
        FLIP_AND_EXPECT(planner_status_t, gmmrrt_msg_decode_planner_status, &st);
        FLIP_AND_EXPECT(demo_info_t, gmmrrt_msg_decode_demo_info, &demo);
        FLIP_AND_EXPECT(planar_scan_t, gmmrrt_msg_decode_planar_scan, &scan);
        FLIP_AND_EXPECT(occupancy_grid_t, gmmrrt_msg_decode_occupancy_grid, &grid);
#undef FLIP_AND_EXPECT
    }
}

static void test_null_arguments_and_null_err_are_safe(void **state)
{
    (void)state;
    gmmrrt_pose2d_t pose;
    fill_pose(&pose);
    int n = gmmrrt_pose2d_t_encode(g_buf, 0, BUF_CAP, &pose);
    assert_int_equal(gmmrrt_msg_decode_pose2d(NULL, (size_t)n, &pose, g_err, sizeof g_err), GMMRRT_MSG_DECODE_FAILED);
    assert_int_equal(gmmrrt_msg_decode_pose2d(g_buf, (size_t)n, NULL, g_err, sizeof g_err), GMMRRT_MSG_DECODE_FAILED);
    assert_int_equal(gmmrrt_msg_decode_pose2d(g_buf, (size_t)INT32_MAX + 1u, &pose, NULL, 0),
                     GMMRRT_MSG_DECODE_FAILED);
    pose.x = NAN;
    n = gmmrrt_pose2d_t_encode(g_buf, 0, BUF_CAP, &pose);
    assert_int_equal(gmmrrt_msg_decode_pose2d(g_buf, (size_t)n, &pose, NULL, 0), GMMRRT_MSG_NOT_FINITE);
    /* A tiny error buffer is truncated, still terminated. */
    char small[8];
    memset(small, 'z', sizeof small);
    assert_int_equal(gmmrrt_msg_decode_pose2d(g_buf, (size_t)n, &pose, small, sizeof small), GMMRRT_MSG_NOT_FINITE);
    assert_int_equal(small[sizeof small - 1], '\0');
}

static void test_result_strings_are_distinct(void **state)
{
    (void)state;
    const gmmrrt_msg_result_t all[] = {GMMRRT_MSG_OK, GMMRRT_MSG_DECODE_FAILED, GMMRRT_MSG_COUNT_OVER_BOUND,
                                       GMMRRT_MSG_NOT_FINITE, GMMRRT_MSG_BAD_VALUE, GMMRRT_MSG_UNKNOWN_COMMAND,
                                       GMMRRT_MSG_WRONG_FRAME};
    for (size_t i = 0; i < 7; ++i)
        for (size_t j = i + 1; j < 7; ++j)
            assert_string_not_equal(gmmrrt_msg_result_str(all[i]), gmmrrt_msg_result_str(all[j]));
    assert_string_equal(gmmrrt_msg_result_str((gmmrrt_msg_result_t)99), "unknown");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pose2d_round_trips),
        cmocka_unit_test(test_people_round_trips_all_slots),
        cmocka_unit_test(test_nav_goal_round_trips),
        cmocka_unit_test(test_obstacles_round_trip_at_capacity),
        cmocka_unit_test(test_waypoints_round_trip_at_capacity),
        cmocka_unit_test(test_empty_plan_round_trips),
        cmocka_unit_test(test_planner_status_round_trips),
        cmocka_unit_test(test_demo_info_round_trips),
        cmocka_unit_test(test_planar_scan_round_trips_at_capacity_keeping_no_returns),
        cmocka_unit_test(test_planar_scan_rules),
        cmocka_unit_test(test_occupancy_grid_round_trips_at_capacity),
        cmocka_unit_test(test_occupancy_grid_rules),
        cmocka_unit_test(test_pose2d_non_finite_fields_are_rejected),
        cmocka_unit_test(test_pose2d_velocity_is_ignored_when_not_valid),
        cmocka_unit_test(test_people_count_out_of_bounds_is_rejected),
        cmocka_unit_test(test_people_non_finite_and_negative_id_are_rejected),
        cmocka_unit_test(test_people_slots_beyond_count_are_not_validated),
        cmocka_unit_test(test_nav_goal_rules),
        cmocka_unit_test(test_nav_goal_command_id_side_and_yaw_tolerance_rules),
        cmocka_unit_test(test_frames_are_bounded_printable_and_judged_before_allocation),
        cmocka_unit_test(test_obstacles_counts_out_of_bounds_are_rejected),
        cmocka_unit_test(test_obstacles_non_finite_and_sizes_are_rejected),
        cmocka_unit_test(test_waypoints_rules),
        cmocka_unit_test(test_planner_status_bad_state_is_rejected),
        cmocka_unit_test(test_demo_info_rules),
        cmocka_unit_test(test_every_truncation_is_rejected),
        cmocka_unit_test(test_wrong_fingerprint_is_rejected),
        cmocka_unit_test(test_null_arguments_and_null_err_are_safe),
        cmocka_unit_test(test_result_strings_are_distinct),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
