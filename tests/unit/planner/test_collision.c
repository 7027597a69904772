/*
 * test_collision.c - planner.collision: the world of collision.h against FCL's exact
 * clearance (the oracle): the point test never calls a colliding point free and calls
 * every point with more than 1e-6 m of clearance free (the grid decides far from obstacles,
 * the exact closed forms near them); edges keep 1 mm; segments through obstacles
 * are blocked whichever way they are walked; boxes rotate; people are discs; bad input
 * gets its status.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "gmmrrt/collision.h"
#include "gmmrrt/rng.h"

static gmmrrt_obstacle_set_t scene(void)
{
    gmmrrt_obstacle_set_t o;
    memset(&o, 0, sizeof o);
    o.bounds = (gmmrrt_bounds_t){-5.0, -4.0, 5.0, 4.0};
    o.num_circles = 2;
    o.circles[0] = (gmmrrt_circle_t){0.0, 0.0, 1.0};
    o.circles[1] = (gmmrrt_circle_t){3.0, 2.0, 0.4};
    o.num_boxes = 2;
    o.boxes[0] = (gmmrrt_box_t){-3.0, 1.0, 2.0, 0.5, 0.6};
    o.boxes[1] = (gmmrrt_box_t){2.5, -2.5, 1.0, 1.0, 0.0};
    o.num_people = 1;
    o.people[0] = (gmmrrt_pose_t){-2.0, -2.0, 1.0};
    return o;
}

/* One circle and one box in [-5, 5]^2, nothing else. */
static gmmrrt_obstacle_set_t circle_and_box(gmmrrt_circle_t circle, gmmrrt_box_t box)
{
    gmmrrt_obstacle_set_t o;
    memset(&o, 0, sizeof o);
    o.bounds = (gmmrrt_bounds_t){-5.0, -5.0, 5.0, 5.0};
    o.num_circles = 1;
    o.circles[0] = circle;
    o.num_boxes = 1;
    o.boxes[0] = box;
    return o;
}

typedef struct {
    void *mem;
    gmmrrt_world_t *w;
} world_t;

static gmmrrt_status_t build(world_t *t, double res, double robot_r, const gmmrrt_obstacle_set_t *o)
{
    const int32_t cells = 1 << 20;
    const size_t size = gmmrrt_world_mem_size(cells);
    t->mem = aligned_alloc(8, size);
    return gmmrrt_world_build(&t->w, t->mem, size, cells, res, robot_r, 0.3, o);
}

static void test_points_are_free_exactly_when_fcl_finds_clearance(void **state)
{
    (void)state;
    const double radii[] = {0.0, 0.3};
    for (int r = 0; r < 2; ++r) {
        gmmrrt_obstacle_set_t o = scene();
        world_t t;
        const double res = 0.05;
        assert_int_equal(build(&t, res, radii[r], &o), GMMRRT_OK);
        gmmrrt_rng_t rng;
        gmmrrt_rng_seed(&rng, 11);
        int free_n = 0, blocked_n = 0, near_free = 0;
        for (int i = 0; i < 200000; ++i) {
            const double x = -5.0 + 10.0 * gmmrrt_rng_uniform(&rng), y = -4.0 + 8.0 * gmmrrt_rng_uniform(&rng);
            const double exact = gmmrrt_world_exact_clearance(t.w, x, y);
            const int f = gmmrrt_world_point_free(t.w, x, y);
            if (exact <= 0.0 && f)
                fail_msg("(%g, %g) clearance %g called free", x, y, exact);
            if (exact > 1e-6 && !f)
                fail_msg("(%g, %g) clearance %g called blocked (radius %g)", x, y, exact, radii[r]);
            free_n += f;
            blocked_n += !f;
            near_free += f && exact < res; /* where the grid's bound alone says blocked */
        }
        assert_true(free_n > 1000 && blocked_n > 1000 && near_free > 100);
        free(t.mem);
    }
}

/* Near obstacles the grid's bound is not enough (it calls points up to about a cell away
 * blocked); the exact closed forms decide there. Points 1 um outside / inside a circle and a
 * rotated box's face and corner; edges tangent to the circle at 2 mm (free) and 0.5 mm
 * (refused: the 1 mm edge margin), both ways, and grazing the box's face at 2 mm. */
static void test_edges_may_pass_obstacles_at_a_millimetre(void **state)
{
    (void)state;
    const double yaw = 0.5, c = cos(yaw), sn = sin(yaw);
    const gmmrrt_obstacle_set_t o =
        circle_and_box((gmmrrt_circle_t){-2.0, 0.0, 1.0}, (gmmrrt_box_t){2.0, 0.0, 2.0, 1.0, yaw});
    const double radii[] = {0.0, 0.3};
    for (int r = 0; r < 2; ++r) {
        world_t t;
        const double rr = radii[r];
        assert_int_equal(build(&t, 0.05, rr, &o), GMMRRT_OK);
        const double reach = 1.0 + rr; /* circle: centre distance where the robot touches */
        for (int k = 0; k < 16; ++k) {
            const double a = 2.0 * M_PI * k / 16.0, ca = cos(a), sa = sin(a);
            assert_true(gmmrrt_world_point_free(t.w, -2.0 + (reach + 1e-6) * ca, (reach + 1e-6) * sa));
            assert_false(gmmrrt_world_point_free(t.w, -2.0 + (reach - 1e-6) * ca, (reach - 1e-6) * sa));
            assert_true(gmmrrt_world_point_free(t.w, -2.0 + (reach + 0.02) * ca, (reach + 0.02) * sa));
        }
        /* Box faces and a corner, in the box frame then rotated (+x face at 1 + rr, +y face at 0.5 + rr). */
        const double pts[][3] = {{1.0 + rr, 0.2, 1}, {-0.3, 0.5 + rr, 1}, {1.0 + rr * M_SQRT1_2, 0.5 + rr * M_SQRT1_2, 1}};
        for (int k = 0; k < 3; ++k)
            for (int side = -1; side <= 1; side += 2) {
                const double s = 1.0 + side * 1e-6 / hypot(pts[k][0], pts[k][1]);
                const double lx = pts[k][0] * s, ly = pts[k][1] * s;
                const double x = 2.0 + lx * c - ly * sn, y = lx * sn + ly * c;
                const double exact = gmmrrt_world_exact_clearance(t.w, x, y);
                if (!(fabs(exact) > 1e-7 && fabs(exact) < 2e-6))
                    fail_msg("test point %d side %d: FCL clearance %g (set-up)", k, side, exact);
                assert_int_equal(gmmrrt_world_point_free(t.w, x, y), exact > 0.0);
            }
        /* Tangent edges above the circle: y = reach + gap. */
        const double gaps[] = {0.002, 0.0005};
        for (int g = 0; g < 2; ++g) {
            const double y = reach + gaps[g];
            assert_int_equal(gmmrrt_world_segment_free(t.w, -2.4, y, -1.6, y), g == 0);
            assert_int_equal(gmmrrt_world_segment_free(t.w, -1.6, y, -2.4, y), g == 0);
        }
        /* Along the box's +y face (local y = 0.5 + rr + 2 mm), rotated into the world. */
        {
            const double ly = 0.5 + rr + 0.002, lx0 = -0.8, lx1 = 0.8;
            const double x0 = 2.0 + lx0 * c - ly * sn, y0 = lx0 * sn + ly * c;
            const double x1 = 2.0 + lx1 * c - ly * sn, y1 = lx1 * sn + ly * c;
            assert_true(gmmrrt_world_segment_free(t.w, x0, y0, x1, y1));
            assert_true(gmmrrt_world_segment_free(t.w, x1, y1, x0, y0));
        }
        free(t.mem);
    }
}

static void test_exact_clearance_matches_geometry(void **state)
{
    (void)state;
    /* The box rotated: 1 wide in x, 2 tall in y. */
    const gmmrrt_obstacle_set_t o =
        circle_and_box((gmmrrt_circle_t){0.0, 0.0, 1.0}, (gmmrrt_box_t){3.0, 0.0, 2.0, 1.0, M_PI / 2.0});
    world_t t;
    assert_int_equal(build(&t, 0.05, 0.25, &o), GMMRRT_OK);
    assert_true(fabs(gmmrrt_world_exact_clearance(t.w, 0.0, -2.0) - 0.75) < 1e-9);
    /* box spans x in [2.5, 3.5], y in [-1, 1] once rotated */
    assert_true(fabs(gmmrrt_world_exact_clearance(t.w, 3.0, 2.0) - 0.75) < 1e-9);
    assert_true(fabs(gmmrrt_world_exact_clearance(t.w, 2.0, 0.0) - 0.25) < 1e-9);
    /* penetration is negative */
    assert_true(gmmrrt_world_exact_clearance(t.w, 0.0, 0.5) < 0.0);
    assert_true(gmmrrt_world_exact_clearance(t.w, 3.0, 0.9) < 0.0);
    free(t.mem);
}

static void test_segments_through_obstacles_are_blocked_both_ways(void **state)
{
    (void)state;
    gmmrrt_obstacle_set_t o = scene();
    world_t t;
    assert_int_equal(build(&t, 0.05, 0.0, &o), GMMRRT_OK);
    assert_false(gmmrrt_world_segment_free(t.w, -1.5, 0.0, 1.5, 0.0));
    assert_false(gmmrrt_world_segment_free(t.w, 1.5, 0.0, -1.5, 0.0));
    assert_true(gmmrrt_world_segment_free(t.w, -1.5, 3.5, 1.5, 3.5));
    assert_false(gmmrrt_world_segment_free(t.w, -4.9, 3.9, 4.9, -3.9)); /* the big disc */
    /* thin: a 0.1 m box across a 4 m segment is found with 5 cm steps */
    gmmrrt_obstacle_set_t thin;
    memset(&thin, 0, sizeof thin);
    thin.bounds = o.bounds;
    thin.num_boxes = 1;
    thin.boxes[0] = (gmmrrt_box_t){0.0, 0.0, 0.1, 3.0, 0.0};
    free(t.mem);
    assert_int_equal(build(&t, 0.05, 0.0, &thin), GMMRRT_OK);
    assert_false(gmmrrt_world_segment_free(t.w, -2.0, 0.3, 2.0, -0.2));
    assert_true(gmmrrt_world_segment_free(t.w, -2.0, 2.0, 2.0, 2.0));
    /* out of bounds */
    assert_false(gmmrrt_world_point_free(t.w, 5.5, 0.0));
    assert_false(gmmrrt_world_segment_free(t.w, 0.5, 0.0, 6.0, 0.0));
    assert_false(gmmrrt_world_point_free(t.w, NAN, 0.0));
    free(t.mem);
}

/* A segment that cuts a box corner by less than a millimetre has most of its length far from
 * the box; only sphere tracing that never steps further than the proven clearance notices. Every
 * segment the world calls free must keep positive exact clearance (FCL) all along, probed every
 * 0.1 mm. Fails with fixed-size steps between probes. */
static void test_free_segments_never_cut_a_corner(void **state)
{
    (void)state;
    gmmrrt_obstacle_set_t o;
    memset(&o, 0, sizeof o);
    o.bounds = (gmmrrt_bounds_t){-4.0, -4.0, 4.0, 4.0};
    o.num_boxes = 1;
    o.boxes[0] = (gmmrrt_box_t){0.0, 0.0, 2.0, 2.0, 0.0}; /* corner at (1, 1) */
    const double radii[] = {0.0, 0.3};
    for (int r = 0; r < 2; ++r) {
        world_t t;
        assert_int_equal(build(&t, 0.05, radii[r], &o), GMMRRT_OK);
        gmmrrt_rng_t rng;
        gmmrrt_rng_seed(&rng, 5);
        int called_free = 0;
        for (int i = 0; i < 400; ++i) {
            /* Lines x + y = c through the corner region: the corner (of the robot-inflated box) is
             * at x + y = 2 + radius * sqrt(2); offsets from -2 mm (cutting it) to +15 cm (clear of it,
             * beyond the grid's one-cell conservatism). */
            const double u = gmmrrt_rng_uniform(&rng);
            const double c = 2.0 + radii[r] * sqrt(2.0) + (u < 0.5 ? (u - 0.25) * 8e-3 : (u - 0.5) * 0.3);
            const double half = 1.0 + gmmrrt_rng_uniform(&rng);
            const double shift = (gmmrrt_rng_uniform(&rng) - 0.5) * 0.2;
            const double mx = c / 2 + shift, my = c / 2 - shift;
            const double x0 = mx - half / sqrt(2.0), y0 = my + half / sqrt(2.0);
            const double x1 = mx + half / sqrt(2.0), y1 = my - half / sqrt(2.0);
            if (!gmmrrt_world_segment_free(t.w, x0, y0, x1, y1))
                continue;
            ++called_free;
            const double len = hypot(x1 - x0, y1 - y0);
            for (double s = 0.0; s <= len; s += 1e-4) {
                const double x = x0 + (x1 - x0) * s / len, y = y0 + (y1 - y0) * s / len;
                if (!(gmmrrt_world_exact_clearance(t.w, x, y) > 0.0))
                    fail_msg("segment (%g,%g)-(%g,%g) called free but touches the box at (%g,%g), radius %g", x0,
                             y0, x1, y1, x, y, radii[r]);
            }
        }
        assert_true(called_free > 20); /* the lines well outside the corner are free */
        free(t.mem);
    }
}

static void test_people_are_discs_of_person_radius(void **state)
{
    (void)state;
    gmmrrt_obstacle_set_t o;
    memset(&o, 0, sizeof o);
    o.bounds = (gmmrrt_bounds_t){-3.0, -3.0, 3.0, 3.0};
    o.num_people = 1;
    o.people[0] = (gmmrrt_pose_t){0.0, 0.0, 0.7};
    world_t t;
    assert_int_equal(build(&t, 0.02, 0.2, &o), GMMRRT_OK); /* person radius 0.3 */
    assert_false(gmmrrt_world_point_free(t.w, 0.45, 0.0));
    assert_true(gmmrrt_world_point_free(t.w, 0.6, 0.0));
    assert_true(fabs(gmmrrt_world_exact_clearance(t.w, 1.0, 0.0) - 0.5) < 1e-9);
    free(t.mem);
}

static void test_bad_worlds_get_their_status(void **state)
{
    (void)state;
    gmmrrt_obstacle_set_t o = scene();
    const size_t size = gmmrrt_world_mem_size(1000);
    void *mem = aligned_alloc(8, size);
    gmmrrt_world_t *w;
    /* 10 x 8 m at 5 cm is 32000 cells > 1000 */
    assert_int_equal(gmmrrt_world_build(&w, mem, size, 1000, 0.05, 0.0, 0.3, &o), GMMRRT_ERR_BUFFER_TOO_SMALL);
    assert_int_equal(gmmrrt_world_build(&w, mem, size - 8, 1000, 0.5, 0.0, 0.3, &o), GMMRRT_ERR_BUFFER_TOO_SMALL);
    assert_int_equal(gmmrrt_world_build(&w, mem, size, 1000, 0.5, 0.0, 0.3, &o), GMMRRT_OK);
    assert_int_equal(gmmrrt_world_build(&w, mem, size, 1000, 0.5, -0.1, 0.3, &o), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_int_equal(gmmrrt_world_build(&w, mem, size, 1000, NAN, 0.0, 0.3, &o), GMMRRT_ERR_INVALID_ARGUMENT);
    o.boxes[1].width_m = 0.0;
    assert_int_equal(gmmrrt_world_build(&w, mem, size, 1000, 0.5, 0.0, 0.3, &o), GMMRRT_ERR_INVALID_ARGUMENT);
    o = scene();
    o.num_circles = GMMRRT_MAX_CIRCLES + 1;
    assert_int_equal(gmmrrt_world_build(&w, mem, size, 1000, 0.5, 0.0, 0.3, &o), GMMRRT_ERR_INVALID_ARGUMENT);
    o = scene();
    o.people[0].yaw = INFINITY;
    assert_int_equal(gmmrrt_world_build(&w, mem, size, 1000, 0.5, 0.0, 0.3, &o), GMMRRT_ERR_INVALID_ARGUMENT);
    o = scene();
    o.bounds.xmin = o.bounds.xmax;
    assert_int_equal(gmmrrt_world_build(&w, mem, size, 1000, 0.5, 0.0, 0.3, &o), GMMRRT_ERR_INVALID_ARGUMENT);
    free(mem);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_points_are_free_exactly_when_fcl_finds_clearance),
        cmocka_unit_test(test_edges_may_pass_obstacles_at_a_millimetre),
        cmocka_unit_test(test_exact_clearance_matches_geometry),
        cmocka_unit_test(test_segments_through_obstacles_are_blocked_both_ways),
        cmocka_unit_test(test_free_segments_never_cut_a_corner),
        cmocka_unit_test(test_people_are_discs_of_person_radius),
        cmocka_unit_test(test_bad_worlds_get_their_status),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
