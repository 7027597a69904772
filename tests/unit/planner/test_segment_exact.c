/*
 * test_segment_exact.c - planner.segment_exact: the exact segment and point tests of
 * segment_exact.h against an oracle, FCL's clearance (gmmrrt_world_exact_clearance) sampled
 * every millimetre along random segments among circles and rotated boxes: a segment called
 * clear keeps more than the reach everywhere, a segment called blocked comes within it
 * somewhere (up to the sampling's half step); and the world's segment test, which uses them
 * while the closed forms answer, refuses exactly the segments that come within the edge margin.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <cmocka.h>

#include "gmmrrt/rng.h"
#include "planner_fixtures.h"
#include "segment_exact.h"

#define STEP_M 2e-3

typedef struct {
    gmmrrt_obstacle_set_t o;
    double cs[GMMRRT_MAX_BOXES], sn[GMMRRT_MAX_BOXES];
    void *mem;
    gmmrrt_world_t *w; /* robot radius 0: its exact clearance is the shapes' distance */
} scene_t;

static void make_scene(scene_t *s, gmmrrt_rng_t *rng, int32_t circles, int32_t boxes)
{
    memset(&s->o, 0, sizeof s->o);
    s->o.bounds = (gmmrrt_bounds_t){-10.0, -10.0, 10.0, 10.0};
    s->o.num_circles = circles;
    s->o.num_boxes = boxes;
    for (int32_t k = 0; k < circles; ++k)
        s->o.circles[k] = (gmmrrt_circle_t){-9.0 + 18.0 * gmmrrt_rng_uniform(rng), -9.0 + 18.0 * gmmrrt_rng_uniform(rng),
                                            0.2 + 0.8 * gmmrrt_rng_uniform(rng)};
    for (int32_t k = 0; k < boxes; ++k) {
        s->o.boxes[k] = (gmmrrt_box_t){-9.0 + 18.0 * gmmrrt_rng_uniform(rng), -9.0 + 18.0 * gmmrrt_rng_uniform(rng),
                                       0.1 + 2.0 * gmmrrt_rng_uniform(rng), 0.1 + 2.0 * gmmrrt_rng_uniform(rng),
                                       -M_PI + 2.0 * M_PI * gmmrrt_rng_uniform(rng)};
        s->cs[k] = cos(s->o.boxes[k].yaw);
        s->sn[k] = sin(s->o.boxes[k].yaw);
    }
    const size_t size = gmmrrt_world_mem_size(1 << 18);
    s->mem = aligned_alloc(8, (size + 7u) & ~(size_t)7u);
    assert_non_null(s->mem);
    s->w = NULL;
    assert_int_equal(gmmrrt_world_build(&s->w, s->mem, size, 1 << 18, 0.05, 0.0, 0.25, &s->o), GMMRRT_OK);
}

/* Least exact clearance along the segment, sampled every STEP_M. */
static double sampled_min_clearance(const gmmrrt_world_t *w, double x0, double y0, double x1, double y1)
{
    const double len = hypot(x1 - x0, y1 - y0);
    const int steps = (int)ceil(len / STEP_M);
    double best = INFINITY;
    for (int k = 0; k <= steps; ++k) {
        const double u = steps ? (double)k / steps : 0.0;
        const double c = gmmrrt_world_exact_clearance(w, x0 + u * (x1 - x0), y0 + u * (y1 - y0));
        best = c < best ? c : best;
    }
    return best;
}

static void test_segments_against_sampled_fcl_clearance(void **state)
{
    (void)state;
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, 17);
    scene_t s;
    make_scene(&s, &rng, 12, 10);
    int clear = 0, blocked = 0;
    for (int trial = 0; trial < 600; ++trial) {
        const double x0 = -10.0 + 20.0 * gmmrrt_rng_uniform(&rng), y0 = -10.0 + 20.0 * gmmrrt_rng_uniform(&rng);
        const double len = 0.05 + 2.5 * gmmrrt_rng_uniform(&rng), a = 2.0 * M_PI * gmmrrt_rng_uniform(&rng);
        const double x1 = x0 + len * cos(a), y1 = y0 + len * sin(a);
        const double reach = trial % 3 == 0 ? 0.0 : 0.3 * gmmrrt_rng_uniform(&rng);
        const int ok = gmmrrt_segment_clear_of_shapes(&s.o, s.cs, s.sn, reach, x0, y0, x1, y1);
        const double m = sampled_min_clearance(s.w, x0, y0, x1, y1);
        if (ok) {
            assert_true(m > reach - 1e-9);
            ++clear;
        } else {
            assert_true(m <= reach + 0.5 * STEP_M + 1e-9);
            ++blocked;
        }
        const int pok = gmmrrt_point_clear_of_shapes(&s.o, s.cs, s.sn, reach, x0, y0);
        const double pc = gmmrrt_world_exact_clearance(s.w, x0, y0);
        assert_int_equal(pok, pc > reach);
    }
    printf("segments: %d clear, %d blocked\n", clear, blocked);
    assert_true(clear > 50 && blocked > 50); /* both answers were exercised */
    free(s.mem);
}

static void test_world_refuses_what_comes_within_the_edge_margin(void **state)
{
    (void)state;
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, 5);
    scene_t s;
    make_scene(&s, &rng, 4, 3); /* few shapes: the world answers with the closed forms */
    int clear = 0;
    for (int trial = 0; trial < 500; ++trial) {
        const double x0 = -9.5 + 19.0 * gmmrrt_rng_uniform(&rng), y0 = -9.5 + 19.0 * gmmrrt_rng_uniform(&rng);
        const double len = 0.05 + 2.0 * gmmrrt_rng_uniform(&rng), a = 2.0 * M_PI * gmmrrt_rng_uniform(&rng);
        const double x1 = fmin(fmax(x0 + len * cos(a), -10.0), 10.0), y1 = fmin(fmax(y0 + len * sin(a), -10.0), 10.0);
        const int ok = gmmrrt_world_segment_free(s.w, x0, y0, x1, y1);
        assert_int_equal(ok, gmmrrt_world_segment_free(s.w, x1, y1, x0, y0)); /* either way round */
        const double m = sampled_min_clearance(s.w, x0, y0, x1, y1);
        if (ok) {
            assert_true(m > 1e-3);
            ++clear;
        } else {
            assert_true(m <= 1e-3 + 0.5 * STEP_M + 1e-9);
        }
    }
    assert_true(clear > 50);
    free(s.mem);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_segments_against_sampled_fcl_clearance),
        cmocka_unit_test(test_world_refuses_what_comes_within_the_edge_margin),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
