/*
 * test_escape.c - planner.escape: the way out of a start in collision (escape.c) when what the
 * robot touches is the map (an occupancy raster, raster.h) rather than a circle, box or person.
 * The map's walls are axis-aligned rectangles of whole cells, so the oracle is the exact
 * distance from the robot's centre to those rectangles, written here independently of the
 * raster's code. Each case checks: the start escapes (or freezes, when the only way out is
 * through a wall), the exit is free and leavable by the planner's own tests, the clearance to
 * the walls never falls along the straight motion to the exit while the robot is in contact,
 * the exit is on the start's side of every wall, and the search then finds a path to the goal.
 * The walls are the map's occupied cells, or the cells a range scan marked. The last case checks
 * that the map stays a wall while someone walks (the planner's world is then rebuilt without the
 * walkers, and must keep the map).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "gmmrrt/collision.h"
#include "gmmrrt/raster.h"
#include "planner_fixtures.h"

#define RES_M 0.05
#define ORIGIN_X (-2.5)
#define ORIGIN_Y (-1.5)
#define WIDTH 100 /* 5 m */
#define HEIGHT 60 /* 3 m */
#define ROBOT_M 0.3

typedef struct {
    double x0, y0, x1, y1; /* on cell edges */
} wall_t;

typedef struct {
    void *raster_mem;
    gmmrrt_raster_t raster;
    const wall_t *walls;
    int32_t num_walls;
} map_t;

/* A raster over the bounds, free but for the walls (every cell whose centre is in one). */
static void make_map(map_t *m, const wall_t *walls, int32_t num_walls)
{
    const size_t size = gmmrrt_raster_mem_size(WIDTH * HEIGHT, WIDTH);
    assert_true(size > 0);
    m->raster_mem = aligned_alloc(8, (size + 7u) & ~(size_t)7u);
    assert_non_null(m->raster_mem);
    assert_int_equal(gmmrrt_raster_init(&m->raster, m->raster_mem, size, WIDTH * HEIGHT, WIDTH), GMMRRT_OK);
    assert_int_equal(gmmrrt_raster_set_geometry(&m->raster, WIDTH, HEIGHT, RES_M, ORIGIN_X, ORIGIN_Y, 0.0, 0),
                     GMMRRT_OK);
    for (int32_t j = 0; j < HEIGHT; ++j)
        for (int32_t i = 0; i < WIDTH; ++i) {
            const double cx = ORIGIN_X + (i + 0.5) * RES_M, cy = ORIGIN_Y + (j + 0.5) * RES_M;
            uint8_t v = GMMRRT_RASTER_FREE;
            for (int32_t k = 0; k < num_walls; ++k)
                if (cx > walls[k].x0 && cx < walls[k].x1 && cy > walls[k].y0 && cy < walls[k].y1)
                    v = GMMRRT_RASTER_OCCUPIED;
            m->raster.cells[j * WIDTH + i] = v;
        }
    assert_int_equal(gmmrrt_raster_update_distance(&m->raster, 0, 0.0), GMMRRT_OK);
    m->walls = walls;
    m->num_walls = num_walls;
}

/* Oracle: signed clearance of the robot disc at (x, y) from the walls (distance to the nearest
 * rectangle, 0 inside one, less the radius). */
static double wall_clearance(const map_t *m, double x, double y)
{
    double best = INFINITY;
    for (int32_t k = 0; k < m->num_walls; ++k) {
        const wall_t *w = &m->walls[k];
        const double dx = fmax(fmax(w->x0 - x, x - w->x1), 0.0), dy = fmax(fmax(w->y0 - y, y - w->y1), 0.0);
        best = fmin(best, hypot(dx, dy));
    }
    return best - ROBOT_M;
}

static gmmrrt_planner_config_t robot_config(void)
{
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    cfg.robot_radius_m = ROBOT_M;
    return cfg;
}

static gmmrrt_problem_t map_problem(const map_t *m, double sx, double sy, double gx, double gy)
{
    gmmrrt_problem_t pr = empty_problem(sx, sy, gx, gy);
    pr.obstacles.bounds = (gmmrrt_bounds_t){ORIGIN_X, ORIGIN_Y, ORIGIN_X + WIDTH * RES_M, ORIGIN_Y + HEIGHT * RES_M};
    pr.obstacles.raster = &m->raster;
    return pr;
}

/* Escapes; checks the exit and the motion to it, then that the search reaches the goal.
 * side(x, y) says whether a point is on the start's side of the walls. Returns the exit. */
static void assert_escapes_on_its_side(const map_t *m, const gmmrrt_problem_t *pr, int (*side)(double, double),
                                       double *exit_x, double *exit_y)
{
    gmmrrt_planner_config_t cfg = robot_config();
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    assert_int_equal(gmmrrt_planner_set_problem(t.p, pr), GMMRRT_ESCAPE);
    const char *why = gmmrrt_planner_escape_reason(t.p);
    print_message("%s\n", why);
    assert_non_null(strstr(why, "the map"));
    double ex, ey, cost;
    int32_t parent;
    assert_int_equal(gmmrrt_planner_node(t.p, 0, &ex, &ey, &parent, &cost), GMMRRT_OK);
    const gmmrrt_world_t *w = gmmrrt_planner_world(t.p);
    assert_true(gmmrrt_world_point_free(w, ex, ey));
    assert_true(gmmrrt_world_point_leavable(w, ex, ey));
    assert_true(side(ex, ey));
    /* Along the motion, in 1 mm steps: while in contact, the clearance never falls. */
    const double len = hypot(ex - pr->start_x, ey - pr->start_y);
    const int32_t steps = (int32_t)ceil(len / 0.001);
    double prev = wall_clearance(m, pr->start_x, pr->start_y);
    for (int32_t k = 1; k <= steps; ++k) {
        const double s = (double)k / steps;
        const double x = pr->start_x + s * (ex - pr->start_x), y = pr->start_y + s * (ey - pr->start_y);
        const double c = wall_clearance(m, x, y);
        if (c <= 0.0 && c < prev - 1e-9)
            fail_msg("clearance falls from %.6f to %.6f at (%.4f, %.4f) on the way out", prev, c, x, y);
        assert_true(side(x, y));
        prev = c;
    }
    gmmrrt_budget_t b = {0.0, 4000, 0.0, 0};
    assert_int_equal(gmmrrt_planner_run(t.p, &b, NULL), GMMRRT_OK);
    gmmrrt_path_t path;
    assert_int_equal(gmmrrt_planner_best_path(t.p, &path), GMMRRT_OK);
    test_planner_free(&t);
    *exit_x = ex;
    *exit_y = ey;
}

/* A corridor 0.5 m wide (the robot is 0.6 m across), closed at x = -1, open at x = 0.8, between
 * walls one cell thick with open rooms beyond them. The robot stands in it at the origin. The
 * shortest way to a free point is through a wall (0.66 m, into the room beside); the
 * only way that does not cross one runs along the corridor and out of its open end. */
static const wall_t corridor[] = {
    {-1.05, -0.30, 0.80, -0.25}, /* lower wall */
    {-1.05, 0.25, 0.80, 0.30},   /* upper wall */
    {-1.05, -0.25, -1.00, 0.25}, /* closed end */
};

static int in_corridor_band(double x, double y) { return x > 0.8 || (y > -0.25 && y < 0.25); }

static void test_start_in_a_narrow_corridor_leaves_by_its_open_end(void **state)
{
    (void)state;
    map_t m;
    make_map(&m, corridor, 3);
    const gmmrrt_problem_t pr = map_problem(&m, 0.0, 0.0, 2.0, 0.0);
    assert_true(wall_clearance(&m, 0.0, 0.0) < 0.0); /* in contact with both walls */
    double ex, ey;
    assert_escapes_on_its_side(&m, &pr, in_corridor_band, &ex, &ey);
    assert_true(ex > 0.8 && fabs(ey) < 0.25);
    free(m.raster_mem);
}

/* The same corridor closed at both ends: every way out crosses a wall, so the robot freezes
 * with the map named, rather than driving through one. */
static void test_start_in_a_closed_pocket_freezes_naming_the_map(void **state)
{
    (void)state;
    const wall_t pocket[] = {corridor[0], corridor[1], corridor[2], {0.80, -0.30, 0.85, 0.30}};
    map_t m;
    make_map(&m, pocket, 4);
    gmmrrt_planner_config_t cfg = robot_config();
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    const gmmrrt_problem_t pr = map_problem(&m, 0.0, 0.0, 2.0, 0.0);
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_FROZEN);
    assert_non_null(strstr(gmmrrt_planner_escape_reason(t.p), "the map"));
    test_planner_free(&t);
    free(m.raster_mem);
}

/* A wall one cell thick at y = 0.45 with a room beyond it: a robot whose disc overlaps it (centre
 * 0.25 m below) and one whose centre is 0.05 m inside a thick wall both leave on their own side. */
static int below_thin_wall(double x, double y) { return (void)x, y < 0.45; }
static int below_thick_wall(double x, double y) { return (void)x, y < 0.4; }

static void test_start_against_or_inside_a_wall_leaves_on_its_side(void **state)
{
    (void)state;
    const wall_t thin[] = {{-2.5, 0.45, 2.5, 0.50}};
    map_t m;
    make_map(&m, thin, 1);
    gmmrrt_problem_t pr = map_problem(&m, 0.0, 0.2, 2.0, -0.5);
    double ex, ey;
    assert_escapes_on_its_side(&m, &pr, below_thin_wall, &ex, &ey);
    assert_true(fabs(ex) < 0.05 && ey < 0.2); /* straight away from the wall (5 degree rays) */
    free(m.raster_mem);

    const wall_t thick[] = {{-2.5, 0.30, 2.5, 1.00}};
    make_map(&m, thick, 1);
    pr = map_problem(&m, 0.0, 0.35, 2.0, -0.5);
    assert_true(wall_clearance(&m, 0.0, 0.35) == -ROBOT_M);
    assert_escapes_on_its_side(&m, &pr, below_thick_wall, &ex, &ey);
    assert_true(ey < 0.0);
    free(m.raster_mem);
}

/* A wall that only a range scan marked (the map itself is free): the sensor at the origin sees a
 * wall at x = 0.5 across +-0.5 rad (the end cells straddle x = 0.5), and the robot at (0.3, 0)
 * touches the marked cells. It leaves on the sensor's side, the marks named as the map. The
 * oracle's walls are the marked cells. */
static int before_the_marks(double x, double y) { return (void)y, x < 0.5; }

static void test_start_against_a_wall_of_scan_marks_leaves_on_its_side(void **state)
{
    (void)state;
    map_t m;
    make_map(&m, NULL, 0);
    static float ranges[401];
    gmmrrt_scan_t scan = {-0.5, 1.0 / 400.0, 0.05, 8.0, 401, ranges};
    for (int k = 0; k < 401; ++k)
        ranges[k] = (float)(0.5 / cos(scan.rad0 + k * scan.radstep));
    const int64_t utime = 1700000000000000;
    int32_t marked = 0;
    assert_int_equal(gmmrrt_raster_apply_scan(&m.raster, &scan, 0.0, 0.0, 0.0, utime, &marked, NULL), GMMRRT_OK);
    assert_int_equal(gmmrrt_raster_update_distance(&m.raster, utime, 1000.0), GMMRRT_OK);
    static wall_t cells[64];
    int32_t n = 0;
    for (int32_t j = 0; j < HEIGHT; ++j)
        for (int32_t i = 0; i < WIDTH; ++i)
            if (m.raster.marks[j * WIDTH + i] != 0) {
                assert_true(n < 64);
                const double x0 = ORIGIN_X + i * RES_M, y0 = ORIGIN_Y + j * RES_M;
                cells[n++] = (wall_t){x0, y0, x0 + RES_M, y0 + RES_M};
            }
    assert_true(n >= 10 && n <= marked); /* a wall about 0.55 m long; beams share end cells */
    m.walls = cells;
    m.num_walls = n;
    const gmmrrt_problem_t pr = map_problem(&m, 0.3, 0.0, -2.0, 0.0);
    assert_true(wall_clearance(&m, 0.3, 0.0) < 0.0);
    double ex, ey;
    assert_escapes_on_its_side(&m, &pr, before_the_marks, &ex, &ey);
    assert_true(ex < 0.3);
    free(m.raster_mem);
}

/* A wall across the room, x in [-0.05, 0.05], from the bottom to y = 0.5, with a 1 m gap above
 * it; start and goal on either side below its top. A person walks along the top of the room. Every
 * point of the path, in 1 mm steps, keeps the robot off the wall (the oracle, not the raster). */
static void test_a_walking_person_leaves_the_map_a_wall(void **state)
{
    (void)state;
    const wall_t across[] = {{-0.05, -1.5, 0.05, 0.5}};
    map_t m;
    make_map(&m, across, 1);
    gmmrrt_problem_t pr = map_problem(&m, -1.5, -1.0, 1.5, -1.0);
    pr.obstacles.num_people = 1;
    pr.obstacles.people[0] = (gmmrrt_pose_t){-2.3, 1.3, 0.0};
    pr.person_vx[0] = 0.5; /* walking, above the standing speed */
    gmmrrt_planner_config_t cfg = robot_config();
    cfg.person_radius_m = 0.2;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    gmmrrt_budget_t b = {0.0, 4000, 0.0, 0};
    assert_int_equal(gmmrrt_planner_run(t.p, &b, NULL), GMMRRT_OK);
    gmmrrt_path_t path;
    assert_int_equal(gmmrrt_planner_best_path(t.p, &path), GMMRRT_OK);
    assert_true(path.num_points >= 2);
    double top = -INFINITY;
    for (int32_t k = 0; k + 1 < path.num_points; ++k) {
        const double len = hypot(path.x[k + 1] - path.x[k], path.y[k + 1] - path.y[k]);
        const int32_t steps = (int32_t)ceil(len / 0.001) + 1;
        for (int32_t q = 0; q <= steps; ++q) {
            const double s = (double)q / steps;
            const double x = path.x[k] + s * (path.x[k + 1] - path.x[k]), y = path.y[k] + s * (path.y[k + 1] - path.y[k]);
            if (wall_clearance(&m, x, y) < -1e-9)
                fail_msg("the path runs into the wall at (%.4f, %.4f)", x, y);
            top = fmax(top, y);
        }
    }
    assert_true(top > 0.5 + ROBOT_M - 1e-6); /* round the wall's end, not through it */
    test_planner_free(&t);
    free(m.raster_mem);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_start_in_a_narrow_corridor_leaves_by_its_open_end),
        cmocka_unit_test(test_start_in_a_closed_pocket_freezes_naming_the_map),
        cmocka_unit_test(test_start_against_or_inside_a_wall_leaves_on_its_side),
        cmocka_unit_test(test_start_against_a_wall_of_scan_marks_leaves_on_its_side),
        cmocka_unit_test(test_a_walking_person_leaves_the_map_a_wall),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
