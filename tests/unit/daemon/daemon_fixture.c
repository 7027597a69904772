/* daemon_fixture.c - see daemon_fixture.h. */
#include "daemon_fixture.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

char daemon_fixture_map[] = "map";

/* One buffer for every encoded message: the largest (a grid, a scan) fit. */
static uint8_t g_buf[1 << 20];

void daemon_fixture_setup(gmmrrtd_t *d, int64_t budget_iterations, int32_t max_nodes, uint64_t seed)
{
    memset(d, 0, sizeof *d);
    gmmrrtd_log_set_level(GMMRRTD_LOG_ERROR);
    gmmrrtd_settings_default(&d->set);
    d->set.budget_ms = 0.0;
    d->set.budget_iterations = budget_iterations;
    d->set.cfg.max_nodes = max_nodes;
    d->set.cfg.seed = seed;
    d->set.cfg.planner = GMMRRT_PLANNER_RRT_STAR;
    d->clock_mode = GMMRRTD_CLOCK_LOG;
    d->staged.input = -1;
    d->mem_size = gmmrrt_planner_mem_size(&d->set.cfg);
    d->mem = aligned_alloc(64, (d->mem_size + 63u) / 64u * 64u);
    assert_non_null(d->mem);
    assert_int_equal(gmmrrt_planner_init(&d->planner, d->mem, d->mem_size, &d->set.cfg), GMMRRT_OK);
    d->lcm_in = d->lcm_out = lcm_create("file:///dev/null?mode=w");
    assert_non_null(d->lcm_out);
}

void daemon_fixture_teardown(gmmrrtd_t *d)
{
    lcm_destroy(d->lcm_out);
    free(d->mem);
}

static void hand_over(gmmrrtd_t *d, int input, int64_t recv_us, int encoded)
{
    assert_true(encoded > 0);
    gmmrrtd_handle_message(d, input, recv_us, g_buf, (size_t)encoded);
}

#define DAEMON_FIXTURE_SENDER(name, type, input)                                                                     \
    void daemon_fixture_send_##name(gmmrrtd_t *d, int64_t recv_us, const type *m)                                   \
    {                                                                                                                \
        hand_over(d, input, recv_us, type##_encode(g_buf, 0, (int)sizeof g_buf, m));                                 \
    }
DAEMON_FIXTURE_SENDER(pose, gmmrrt_pose2d_t, GMMRRTD_IN_POSE)
DAEMON_FIXTURE_SENDER(people, gmmrrt_people_t, GMMRRTD_IN_PEOPLE)
DAEMON_FIXTURE_SENDER(goal, gmmrrt_nav_goal_t, GMMRRTD_IN_GOAL)
DAEMON_FIXTURE_SENDER(obstacles, gmmrrt_obstacles_t, GMMRRTD_IN_OBSTACLES)
DAEMON_FIXTURE_SENDER(scan, gmmrrt_planar_scan_t, GMMRRTD_IN_SCAN)
DAEMON_FIXTURE_SENDER(grid, gmmrrt_occupancy_grid_t, GMMRRTD_IN_GRID)

/* blank_<type>(utime): a zeroed message in static storage, stamped utime in the map frame. */
#define DAEMON_FIXTURE_BLANK(type)                                                                                   \
    static type *blank_##type(int64_t utime)                                                                         \
    {                                                                                                                \
        static type m;                                                                                               \
        memset(&m, 0, sizeof m);                                                                                     \
        m.utime = utime;                                                                                             \
        m.frame = daemon_fixture_map;                                                                                \
        return &m;                                                                                                   \
    }
DAEMON_FIXTURE_BLANK(gmmrrt_pose2d_t)
DAEMON_FIXTURE_BLANK(gmmrrt_nav_goal_t)
DAEMON_FIXTURE_BLANK(gmmrrt_people_t)
DAEMON_FIXTURE_BLANK(gmmrrt_obstacles_t)

gmmrrt_pose2d_t daemon_fixture_pose(int64_t utime, double x, double y, double yaw)
{
    gmmrrt_pose2d_t m = *blank_gmmrrt_pose2d_t(utime);
    m.x = x;
    m.y = y;
    m.yaw = yaw;
    return m;
}

gmmrrt_nav_goal_t daemon_fixture_goal(int64_t utime, int64_t id, double x, double y, int8_t task, int32_t target)
{
    gmmrrt_nav_goal_t m = *blank_gmmrrt_nav_goal_t(utime);
    m.goal_id = id;
    m.command = GMMRRT_NAV_GOAL_T_COMMAND_NEW;
    m.x = x;
    m.y = y;
    m.tolerance_m = 0.3;
    m.task = task;
    m.target_person_id = target;
    return m;
}

gmmrrt_people_t *daemon_fixture_people(int64_t utime) { return blank_gmmrrt_people_t(utime); }

gmmrrt_obstacles_t *daemon_fixture_obstacles(int64_t utime) { return blank_gmmrrt_obstacles_t(utime); }

void daemon_fixture_send_person(gmmrrtd_t *d, int64_t recv_us, int64_t utime, double x, double y, double yaw)
{
    gmmrrt_people_t *m = daemon_fixture_people(utime);
    m->num_people = 1;
    m->people[0].id = 1;
    m->people[0].x = x;
    m->people[0].y = y;
    m->people[0].yaw = yaw;
    daemon_fixture_send_people(d, recv_us, m);
}
