/*
 * test_scan_grid.c - gmmrrtd's SCAN and GRID inputs through its seam gmmrrtd_handle_message, log
 * mode, a real planner: a scan is placed with the robot pose interpolated at its stamp (checked
 * at the marked cell), refused and counted when no pose places it (stamped before every pose,
 * or too long after the newest), a flood is cut at scan_max_per_cycle, all-NaN ranges mark
 * nothing, a plan goes around what scans mark (checked against the raster's marks by brute
 * force, not through the planner's field), stale scans stop or are forgotten as configured, and
 * a grid replaces the map, a malformed one or one in another frame keeps the last good grid, a
 * stale one stops.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
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

/* A 12 m x 10 m free map at 5 cm, origin (-1, 0): the robot drives along y = 5. */
static int setup(void **state)
{
    daemon_fixture_setup(&g_d, 400, 2048, 11);
    gmmrrtd_t *d = &g_d;
    const size_t size = gmmrrt_raster_mem_size(240 * 200, 240);
    d->map_mem = aligned_alloc(64, (size + 63u) / 64u * 64u);
    assert_non_null(d->map_mem);
    assert_int_equal(gmmrrt_raster_init(&d->map, d->map_mem, size, 240 * 200, 240), GMMRRT_OK);
    assert_int_equal(gmmrrt_raster_set_geometry(&d->map, 240, 200, 0.05, -1.0, 0.0, 0.0, 0), GMMRRT_OK);
    memset(d->map.cells, GMMRRT_RASTER_FREE, 240 * 200);
    assert_int_equal(gmmrrt_raster_update_distance(&d->map, 0, 0.0), GMMRRT_OK);
    d->have_map = 1;
    assert_int_equal(gmmrrtd_grid_setup(d), 0);
    *state = d;
    return 0;
}

static int teardown(void **state)
{
    gmmrrtd_t *d = *state;
    free(d->map_mem);
    free(d->grid_mem);
    daemon_fixture_teardown(d);
    return 0;
}

static void send_pose(gmmrrtd_t *d, int64_t recv, int64_t utime, double x, double y)
{
    const gmmrrt_pose2d_t m = daemon_fixture_pose(utime, x, y, 0.0);
    daemon_fixture_send_pose(d, recv, &m);
}

static void send_goal(gmmrrtd_t *d, int64_t recv, double x, double y)
{
    const gmmrrt_nav_goal_t m = daemon_fixture_goal(T0 + recv, 1, x, y, GMMRRT_NAV_GOAL_T_TASK_AVOID, 0);
    daemon_fixture_send_goal(d, recv, &m);
}

/* A scan of n beams from rad0 in steps of radstep, every range `range` (NaN: no return). */
static void send_scan(gmmrrtd_t *d, int64_t recv, int64_t utime, int n, double rad0, double radstep, float range)
{
    static gmmrrt_planar_scan_t m;
    memset(&m, 0, sizeof m);
    m.utime = utime;
    m.rad0 = rad0;
    m.radstep = radstep;
    m.range_min_m = 0.05;
    m.range_max_m = 8.0;
    m.num_ranges = n;
    for (int k = 0; k < n; ++k)
        m.ranges[k] = range;
    daemon_fixture_send_scan(d, recv, &m);
}

/* Whether the map cell holding world point (x, y) carries a scan mark. */
static int marked_at(const gmmrrtd_t *d, double x, double y)
{
    const gmmrrt_raster_t *r = &d->map;
    const int32_t i = (int32_t)floor((x - r->origin_x) / r->resolution_m);
    const int32_t j = (int32_t)floor((y - r->origin_y) / r->resolution_m);
    return r->marks[(size_t)j * (size_t)r->width + (size_t)i] != 0;
}

static int64_t marks_count(const gmmrrtd_t *d)
{
    int64_t n = 0;
    for (int32_t k = 0; k < d->map.width * d->map.height; ++k)
        n += d->map.marks[k] != 0;
    return n;
}

static void test_scan_is_placed_at_the_pose_interpolated_at_its_stamp(void **state)
{
    gmmrrtd_t *d = *state;
    send_pose(d, 0, T0, 0.0, 5.0);
    send_pose(d, 100 * MS, T0 + 100 * MS, 1.0, 5.0);
    /* Taken half-way between the poses: the robot was at x = 0.5; one beam ahead, 2 m. */
    send_scan(d, 110 * MS, T0 + 50 * MS, 1, 0.0, 0.0, 2.0f);
    assert_int_equal(d->scans_applied, 1);
    assert_true(marked_at(d, 2.5 + 0.01, 5.0 + 0.025));
    assert_false(marked_at(d, 3.0 + 0.01, 5.0 + 0.025)); /* not placed at the newest pose */
    assert_false(marked_at(d, 2.0 + 0.01, 5.0 + 0.025)); /* nor at the oldest */
    assert_int_equal(marks_count(d), 1);
}

static void test_scans_no_pose_places_are_refused_and_counted(void **state)
{
    gmmrrtd_t *d = *state;
    send_scan(d, 0, T0, 1, 0.0, 0.0, 2.0f); /* no pose at all yet */
    assert_int_equal(d->status.rejected[ST(REJECT_TIME_BACKWARDS)], 1);
    send_pose(d, 100 * MS, T0 + 100 * MS, 0.0, 5.0);
    send_pose(d, 200 * MS, T0 + 200 * MS, 0.1, 5.0);
    send_scan(d, 210 * MS, T0 + 50 * MS, 1, 0.0, 0.0, 2.0f); /* before every pose kept */
    assert_int_equal(d->status.rejected[ST(REJECT_TIME_BACKWARDS)], 2);
    send_scan(d, 450 * MS, T0 + 450 * MS, 1, 0.0, 0.0, 2.0f); /* 250 ms after the newest pose */
    assert_int_equal(d->status.rejected[ST(REJECT_TIME_FUTURE)], 1);
    send_scan(d, 260 * MS, T0 + 260 * MS, 1, 0.0, 0.0, 2.0f); /* 60 ms after it: held there */
    assert_int_equal(d->scans_applied, 1);
    assert_true(marked_at(d, 2.1 + 0.01, 5.0 + 0.025));
    assert_int_equal(marks_count(d), 1);
}

static void test_pose_ring_restarts_when_pose_stamps_step_back(void **state)
{
    gmmrrtd_t *d = *state;
    gmmrrt_pose2d_t p;
    memset(&p, 0, sizeof p);
    p.y = 5.0;
    p.utime = T0 + 1000 * MS;
    gmmrrtd_scan_add_pose(d, &p);
    p.utime = T0 + 1100 * MS;
    gmmrrtd_scan_add_pose(d, &p);
    p.utime = T0 + 500 * MS; /* the pose source's clock stepped back (accepted after a resync) */
    p.x = 1.0;
    gmmrrtd_scan_add_pose(d, &p);
    assert_int_equal(d->pose_ring_n, 1);
    static gmmrrt_planar_scan_t m;
    memset(&m, 0, sizeof m);
    m.range_max_m = 8.0;
    m.utime = T0 + 1050 * MS; /* bracketed only by the old clock's poses: no longer placed */
    assert_int_equal(gmmrrtd_scan_place(d, &m), 0);
    assert_int_equal(d->status.rejected[ST(REJECT_TIME_FUTURE)], 1);
    m.utime = T0 + 520 * MS;
    assert_int_equal(gmmrrtd_scan_place(d, &m), 1);
    assert_true(d->staged.sensor_x == 1.0 && d->staged.sensor_y == 5.0);
}

static void test_a_flood_is_cut_and_nan_ranges_mark_nothing(void **state)
{
    gmmrrtd_t *d = *state;
    send_goal(d, 0, 8.0, 5.0);
    send_pose(d, 0, T0, 0.0, 5.0);
    for (int k = 0; k < 20; ++k) /* 20 all-NaN scans of 1081 beams within one 100 ms period */
        send_scan(d, 10 * MS + k * MS, T0 + 10 * MS + k * MS, 1081, -2.356, 0.00436, NAN);
    assert_int_equal(d->scans_applied, d->set.scan_max_per_cycle);
    assert_int_equal(d->scans_dropped, 20 - d->set.scan_max_per_cycle);
    assert_int_equal(d->status.rejected[ST(REJECT_COUNT_OVER_BOUND)], 20 - d->set.scan_max_per_cycle);
    assert_int_equal(d->scan_cells_marked, 0);
    assert_int_equal(d->scans_blind, d->set.scan_max_per_cycle);
    assert_int_equal(marks_count(d), 0);
    for (int k = 1; k <= 5; ++k)
        send_pose(d, k * 100 * MS, T0 + k * 100 * MS, 0.0, 5.0);
    assert_int_equal(d->status.state, ST(STATE_PLANNING)); /* planning on, on the last good world */
    for (int i = 0; i < ST(NUM_STOP_REASONS); ++i)
        assert_int_equal(d->status.stops[i], 0);
}

/* Every published waypoint and the segments between them keep more than the robot's radius
 * from every marked cell's square (brute force over the marks). */
static void assert_path_clear_of_marks(const gmmrrtd_t *d)
{
    const gmmrrt_raster_t *r = &d->map;
    const gmmrrt_path_t *p = &d->path;
    assert_true(p->num_points >= 2);
    for (int32_t w = 0; w + 1 < p->num_points; ++w)
        for (int s = 0; s <= 20; ++s) {
            const double x = p->x[w] + (p->x[w + 1] - p->x[w]) * s / 20.0;
            const double y = p->y[w] + (p->y[w + 1] - p->y[w]) * s / 20.0;
            for (int32_t j = 0; j < r->height; ++j)
                for (int32_t i = 0; i < r->width; ++i) {
                    if (!r->marks[(size_t)j * (size_t)r->width + (size_t)i])
                        continue;
                    const double cx = r->origin_x + (i + 0.5) * r->resolution_m;
                    const double cy = r->origin_y + (j + 0.5) * r->resolution_m;
                    const double dx = fmax(fabs(x - cx) - 0.5 * r->resolution_m, 0.0);
                    const double dy = fmax(fabs(y - cy) - 0.5 * r->resolution_m, 0.0);
                    assert_true(hypot(dx, dy) > d->set.cfg.robot_radius_m);
                }
        }
}

/* A wall 2 m wide across the way at x = 4: scanned by beams from the robot at (0, 5). */
static void scan_wall(gmmrrtd_t *d, int64_t t)
{
    static gmmrrt_planar_scan_t m;
    memset(&m, 0, sizeof m);
    m.utime = T0 + t;
    m.range_min_m = 0.05;
    m.range_max_m = 8.0;
    m.rad0 = -0.25;
    m.radstep = 0.5 / 200;
    m.num_ranges = 201;
    for (int k = 0; k < m.num_ranges; ++k)
        m.ranges[k] = (float)(4.0 / cos(m.rad0 + k * m.radstep));
    daemon_fixture_send_scan(d, t, &m);
}

static void test_plan_goes_around_what_scans_mark_and_stale_scans_stop(void **state)
{
    gmmrrtd_t *d = *state;
    send_goal(d, 0, 8.0, 5.0);
    for (int k = 0; k < 10; ++k) {
        send_pose(d, k * 100 * MS, T0 + k * 100 * MS, 0.0, 5.0);
        scan_wall(d, k * 100 * MS + 20 * MS);
    }
    send_pose(d, 1000 * MS, T0 + 1000 * MS, 0.0, 5.0);
    assert_true(d->scan_cells_marked > 0);
    assert_int_equal(d->status.state, ST(STATE_PLANNING));
    assert_path_clear_of_marks(d);
    /* The lidar goes quiet: after scan_timeout_ms (500 ms) the robot stops, counted once. */
    for (int k = 11; k <= 20; ++k)
        send_pose(d, k * 100 * MS, T0 + k * 100 * MS, 0.0, 5.0);
    assert_true(d->status.stale_inputs & ST(STALE_SCAN));
    assert_int_equal(d->status.rejected[ST(REJECT_SCAN_STALE)], 1);
    assert_true(d->status.stops[ST(STOP_SCAN_STALE)] > 0);
    assert_int_equal(d->status.state, ST(STATE_STOPPED));
    assert_int_equal(d->plan_msg.status, GMMRRTD_STOP_SCAN_STALE);
}

static void test_stale_scans_are_forgotten_when_configured(void **state)
{
    gmmrrtd_t *d = *state;
    d->set.scan_stale_stop = 0;
    d->set.scan_decay_ms = 1e6; /* the marks would block for good */
    send_goal(d, 0, 8.0, 5.0);
    for (int k = 0; k < 10; ++k) {
        send_pose(d, k * 100 * MS, T0 + k * 100 * MS, 0.0, 5.0);
        scan_wall(d, k * 100 * MS + 20 * MS);
    }
    for (int k = 10; k <= 20; ++k)
        send_pose(d, k * 100 * MS, T0 + k * 100 * MS, 0.0, 5.0);
    assert_true(d->status.stale_inputs & ST(STALE_SCAN));
    assert_int_equal(d->status.stops[ST(STOP_SCAN_STALE)], 0);
    assert_int_equal(d->status.state, ST(STATE_PLANNING));
    /* Planned without the marks: the straight line through the wall is free again. */
    assert_true(gmmrrt_raster_clearance_bound(&d->map, 4.0, 5.0) > 1.0);
}

static void test_grid_replaces_the_map_keeps_the_last_good_one_and_stale_stops(void **state)
{
    gmmrrtd_t *d = *state;
    static gmmrrt_occupancy_grid_t g;
    memset(&g, 0, sizeof g);
    g.frame = k_map;
    g.resolution_m = 0.1;
    g.origin_x = -1.0;
    g.origin_y = 0.0;
    g.width = 120;
    g.height = 100;
    g.num_cells = 120 * 100;
    for (int j = 0; j < 100; ++j) /* a wall at x = 4 from y = 3 to 7 */
        for (int i = 0; i < 120; ++i)
            g.data[j * 120 + i] = (i == 50 && j >= 30 && j < 70) ? 100 : (i == 0 ? -1 : 0);
    send_goal(d, 0, 8.0, 5.0);
    send_pose(d, 0, T0, 0.0, 5.0);
    g.utime = T0 + 10 * MS;
    daemon_fixture_send_grid(d, 10 * MS, &g);
    assert_int_equal(d->have_grid, 1);
    assert_int_equal(d->grid_version, 1);
    for (int k = 1; k <= 5; ++k)
        send_pose(d, k * 100 * MS, T0 + k * 100 * MS, 0.0, 5.0);
    assert_int_equal(d->status.state, ST(STATE_PLANNING));
    assert_ptr_equal(d->problem.obstacles.raster, &d->grid);
    for (int32_t w = 0; w < d->path.num_points; ++w) /* around the wall, not through it */
        assert_true(fabs(d->path.x[w] - 4.05) > d->set.cfg.robot_radius_m || fabs(d->path.y[w] - 5.0) > 2.0);
    /* A cell out of range: counted, the last good grid stays. */
    g.data[5] = 101;
    g.utime = T0 + 520 * MS;
    daemon_fixture_send_grid(d, 520 * MS, &g);
    assert_int_equal(d->status.rejected[ST(REJECT_BAD_VALUE)], 1);
    assert_int_equal(d->grid_version, 1);
    /* A grid in a frame other than [world] frame: counted as such, the last good grid stays. */
    g.data[5] = 0;
    g.frame = k_odom;
    g.utime = T0 + 530 * MS;
    daemon_fixture_send_grid(d, 530 * MS, &g);
    assert_int_equal(d->status.rejected[ST(REJECT_WRONG_FRAME)], 1);
    assert_int_equal(d->grid_version, 1);
    g.frame = k_map;
    send_pose(d, 600 * MS, T0 + 600 * MS, 0.0, 5.0);
    assert_int_equal(d->status.state, ST(STATE_PLANNING));
    /* No good grid for grid_timeout_ms (1 s): stop, counted once. */
    for (int k = 7; k <= 15; ++k)
        send_pose(d, k * 100 * MS, T0 + k * 100 * MS, 0.0, 5.0);
    assert_true(d->status.stale_inputs & ST(STALE_GRID));
    assert_int_equal(d->status.rejected[ST(REJECT_GRID_STALE)], 1);
    assert_true(d->status.stops[ST(STOP_GRID_STALE)] > 0);
    assert_int_equal(d->plan_msg.status, GMMRRTD_STOP_GRID_STALE);
    /* The input's fault, not the goal's: stopped for longer than goal_fail_after_ms (3 s), the goal
     * lives on and plans again once a grid comes. */
    for (int k = 16; k <= 50; ++k)
        send_pose(d, k * 100 * MS, T0 + k * 100 * MS, 0.0, 5.0);
    assert_int_equal(d->plan_msg.status, GMMRRTD_STOP_GRID_STALE);
    assert_int_equal(d->status.goal_state, ST(GOAL_PLANNING));
    assert_int_equal(d->status.goal_failure, ST(FAILURE_NONE));
    g.utime = T0 + 5010 * MS;
    daemon_fixture_send_grid(d, 5010 * MS, &g);
    assert_int_equal(d->grid_version, 2);
    send_pose(d, 5100 * MS, T0 + 5100 * MS, 0.0, 5.0);
    assert_int_equal(d->status.state, ST(STATE_PLANNING));
    assert_true(d->plan_msg.num_waypoints >= 2);
}

/* The grid's frame is judged as every input's: against [world] frame, whatever it is. */
static void test_grid_is_taken_in_the_configured_frame_only(void **state)
{
    gmmrrtd_t *d = *state;
    snprintf(d->set.frame, sizeof d->set.frame, "odom");
    static gmmrrt_occupancy_grid_t g;
    memset(&g, 0, sizeof g);
    g.utime = T0;
    g.frame = k_map;
    g.resolution_m = 0.1;
    g.width = g.height = 10;
    g.num_cells = 100;
    daemon_fixture_send_grid(d, 0, &g);
    assert_int_equal(d->status.rejected[ST(REJECT_WRONG_FRAME)], 1);
    assert_int_equal(d->have_grid, 0);
    g.frame = k_odom;
    daemon_fixture_send_grid(d, 0, &g);
    assert_int_equal(d->status.rejected[ST(REJECT_WRONG_FRAME)], 1);
    assert_int_equal(d->have_grid, 1);
    assert_int_equal(d->grid_version, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_scan_is_placed_at_the_pose_interpolated_at_its_stamp, setup, teardown),
        cmocka_unit_test_setup_teardown(test_scans_no_pose_places_are_refused_and_counted, setup, teardown),
        cmocka_unit_test_setup_teardown(test_pose_ring_restarts_when_pose_stamps_step_back, setup, teardown),
        cmocka_unit_test_setup_teardown(test_a_flood_is_cut_and_nan_ranges_mark_nothing, setup, teardown),
        cmocka_unit_test_setup_teardown(test_plan_goes_around_what_scans_mark_and_stale_scans_stop, setup, teardown),
        cmocka_unit_test_setup_teardown(test_stale_scans_are_forgotten_when_configured, setup, teardown),
        cmocka_unit_test_setup_teardown(test_grid_replaces_the_map_keeps_the_last_good_one_and_stale_stops, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(test_grid_is_taken_in_the_configured_frame_only, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
