/*
 * test_collision_update.c - planner.collision_update: gmmrrt_world_update (collision.h) keeps
 * or shifts the clearance grid of the static obstacles across problems, and the kept world
 * answers exactly as a fresh gmmrrt_world_build: same grid cell for cell (collision_internal.h),
 * same point, segment (both ways) and exact-clearance answers, with people moved, bounds kept,
 * moved, grown, shrunk, cut to the grid capacity or moved off the old grid. Any change to the
 * static obstacles, robot radius or grid settings rebuilds. People are tested exactly (no grid):
 * a point or an edge grazing a person just inside or just outside its radius. Paper Sect. 3
 * (RRT* needs only CollisionFree); docs/planner.md, "Collision checking".
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "collision_internal.h"
#include "gmmrrt/collision.h"
#include "gmmrrt/rng.h"
#include "planner_fixtures.h"

#define ROBOT_R 0.3
#define PERSON_R 0.35

static gmmrrt_obstacle_set_t statics(void)
{
    gmmrrt_obstacle_set_t o;
    memset(&o, 0, sizeof o);
    o.bounds = (gmmrrt_bounds_t){-5.0, -4.0, 5.0, 4.0};
    o.num_circles = 3;
    o.circles[0] = (gmmrrt_circle_t){0.0, 0.0, 1.0};
    o.circles[1] = (gmmrrt_circle_t){3.0, 2.0, 0.4};
    o.circles[2] = (gmmrrt_circle_t){-6.5, 1.0, 0.8}; /* outside the first bounds, inside later ones */
    o.num_boxes = 3;
    o.boxes[0] = (gmmrrt_box_t){-3.0, 1.0, 2.0, 0.5, 0.6};
    o.boxes[1] = (gmmrrt_box_t){2.5, -2.5, 1.0, 1.0, 0.0};
    o.boxes[2] = (gmmrrt_box_t){7.0, -1.0, 0.3, 3.0, -0.4};
    return o;
}

static double uniform(gmmrrt_rng_t *rng, double lo, double hi) { return lo + (hi - lo) * gmmrrt_rng_uniform(rng); }

static void random_people(gmmrrt_rng_t *rng, gmmrrt_obstacle_set_t *o)
{
    o->num_people = (int32_t)(gmmrrt_rng_uniform(rng) * (GMMRRT_MAX_PEOPLE + 1));
    if (o->num_people > GMMRRT_MAX_PEOPLE)
        o->num_people = GMMRRT_MAX_PEOPLE;
    const gmmrrt_bounds_t *b = &o->bounds;
    for (int32_t k = 0; k < o->num_people; ++k) {
        if (k % 7 == 6) /* some far outside the bounds */
            o->people[k] = (gmmrrt_pose_t){uniform(rng, 1e3, 1e9), uniform(rng, -1e9, 1e9), 0.0};
        else
            o->people[k] = (gmmrrt_pose_t){uniform(rng, b->xmin - 1.0, b->xmax + 1.0),
                                           uniform(rng, b->ymin - 1.0, b->ymax + 1.0), uniform(rng, -3.0, 3.0)};
    }
}

typedef struct {
    void *mem;
    size_t size;
    int32_t cells;
} block_t;

static block_t block(int32_t cells)
{
    block_t b = {NULL, gmmrrt_world_mem_size(cells), cells};
    b.mem = aligned_alloc(8, (b.size + 7u) & ~(size_t)7u);
    assert_non_null(b.mem);
    memset(b.mem, 0xa5, b.size); /* defined bytes everywhere: the error test compares the whole block */
    return b;
}

/* The kept world against a fresh build of the same problem: grid cell for cell, then answers. */
static void assert_same_as_fresh(const gmmrrt_world_t *kept, int32_t cells, double res, double robot_r,
                                 double person_r, const gmmrrt_obstacle_set_t *o, gmmrrt_rng_t *rng, int queries)
{
    block_t f = block(cells);
    gmmrrt_world_t *fresh = NULL;
    assert_int_equal(gmmrrt_world_build(&fresh, f.mem, f.size, cells, res, robot_r, person_r, o), GMMRRT_OK);
    int32_t nx_a, ny_a, nx_b, ny_b;
    double gi_a, gj_a, gi_b, gj_b;
    assert_true(gmmrrt_world_grid_layout(kept, &nx_a, &ny_a, &gi_a, &gj_a));
    assert_true(gmmrrt_world_grid_layout(fresh, &nx_b, &ny_b, &gi_b, &gj_b));
    assert_int_equal(nx_a, nx_b);
    assert_int_equal(ny_a, ny_b);
    assert_true(gi_a == gi_b && gj_a == gj_b);
    /* The grid covers at most the capacity plus the partial tiles at its sides. */
    assert_true((double)nx_a * ny_a <= (double)cells + 16.0 * sqrt((double)cells) + 4096.0);
    for (int32_t j = 0; j < ny_a; ++j)
        for (int32_t i = 0; i < nx_a; ++i) {
            const float a = gmmrrt_world_grid_cell(kept, i, j), b = gmmrrt_world_grid_cell(fresh, i, j);
            if (memcmp(&a, &b, sizeof(float)) != 0)
                fail_msg("cell (%d, %d): kept %.9g, fresh %.9g", (int)i, (int)j, (double)a, (double)b);
        }

    const gmmrrt_bounds_t *bd = &o->bounds;
    for (int q = 0; q < queries; ++q) {
        const double x = uniform(rng, bd->xmin, bd->xmax), y = uniform(rng, bd->ymin, bd->ymax);
        assert_int_equal(gmmrrt_world_point_free(kept, x, y), gmmrrt_world_point_free(fresh, x, y));
        if (q % 16 == 0) {
            const double ca = gmmrrt_world_exact_clearance(kept, x, y), cb = gmmrrt_world_exact_clearance(fresh, x, y);
            assert_true(ca == cb || (isinf(ca) && isinf(cb)));
            if (ca <= 0.0) /* and FCL, the oracle: never free when touching anything */
                assert_int_equal(gmmrrt_world_point_free(kept, x, y), 0);
        }
        /* Segments of all lengths, some from next to a person. */
        double x1 = uniform(rng, bd->xmin, bd->xmax), y1 = uniform(rng, bd->ymin, bd->ymax);
        if (q % 3 == 0) {
            x1 = fmin(fmax(x + uniform(rng, -0.5, 0.5), bd->xmin), bd->xmax);
            y1 = fmin(fmax(y + uniform(rng, -0.5, 0.5), bd->ymin), bd->ymax);
        }
        const int sa = gmmrrt_world_segment_free(kept, x, y, x1, y1);
        assert_int_equal(sa, gmmrrt_world_segment_free(fresh, x, y, x1, y1));
        assert_int_equal(sa, gmmrrt_world_segment_free(kept, x1, y1, x, y));
    }
    free(f.mem);
}

/* Rounds of moved people and bounds kept, moved, resized or jumped, at a roomy capacity and at
 * one that cuts the lattice's extra row / column. */
static void test_kept_world_answers_as_a_fresh_build(void **state)
{
    (void)state;
    const double res = 0.05;
    const int32_t capacities[] = {1 << 18, 0 /* tight, set below */};
    for (int c = 0; c < 2; ++c) {
        /* Tight: exactly ceil(w / res) * ceil(h / res) for the fixed-size bounds of this pass. */
        const double w = 8.03, h = 6.07;
        const int32_t cells = capacities[c] ? capacities[c] : (int32_t)(ceil(w / res) * ceil(h / res));
        block_t m = block(cells);
        gmmrrt_rng_t rng;
        gmmrrt_rng_seed(&rng, 21 + (uint64_t)c);
        gmmrrt_obstacle_set_t o = statics();
        o.bounds = (gmmrrt_bounds_t){-4.0, -3.0, -4.0 + w, -3.0 + h};
        random_people(&rng, &o);
        gmmrrt_world_t *world = NULL;
        assert_int_equal(gmmrrt_world_update(&world, m.mem, m.size, cells, res, ROBOT_R, PERSON_R, &o), GMMRRT_OK);
        assert_ptr_equal(world, m.mem);
        gmmrrt_world_grid_stats_t st;
        assert_int_equal(gmmrrt_world_grid_stats(world, &st), GMMRRT_OK);
        assert_int_equal(st.last, GMMRRT_GRID_BUILT);
        int seen[3] = {0, 0, 0};
        for (int round = 0; round < 60; ++round) {
            gmmrrt_grid_update_t expect;
            const int kind = round % 5;
            if (kind == 0 || kind == 1) { /* only people move (and the start, goal: not the world's) */
                expect = GMMRRT_GRID_KEPT;
            } else if (kind == 4 && round % 10 == 9) { /* off the old grid entirely */
                const double dx = 40.0 * (round % 20 < 10 ? 1.0 : -1.0);
                o.bounds.xmin += dx;
                o.bounds.xmax += dx;
                expect = GMMRRT_GRID_BUILT;
            } else { /* a robot's step, or more, any direction; resized in the roomy pass */
                const double sx = uniform(&rng, -1.5, 1.5), sy = uniform(&rng, -1.5, 1.5);
                o.bounds.xmin += sx;
                o.bounds.xmax += sx;
                o.bounds.ymin += sy;
                o.bounds.ymax += sy;
                if (capacities[c]) { /* resized, kept between 3 and 14 m */
                    o.bounds.xmax = o.bounds.xmin + fmin(fmax(o.bounds.xmax - o.bounds.xmin + uniform(&rng, -0.8, 0.8), 3.0), 14.0);
                    o.bounds.ymax = o.bounds.ymin + fmin(fmax(o.bounds.ymax - o.bounds.ymin + uniform(&rng, -0.8, 0.8), 3.0), 14.0);
                }
                expect = GMMRRT_GRID_SHIFTED;
            }
            random_people(&rng, &o);
            assert_int_equal(gmmrrt_world_update(&world, m.mem, m.size, cells, res, ROBOT_R, PERSON_R, &o),
                             GMMRRT_OK);
            assert_int_equal(gmmrrt_world_grid_stats(world, &st), GMMRRT_OK);
            if (expect == GMMRRT_GRID_SHIFTED && st.last == GMMRRT_GRID_KEPT)
                expect = GMMRRT_GRID_KEPT; /* a step that stayed on the same cells */
            assert_int_equal(st.last, expect);
            if (expect == GMMRRT_GRID_KEPT)
                assert_int_equal(st.last_cells, 0);
            seen[expect]++;
            assert_same_as_fresh(world, cells, res, ROBOT_R, PERSON_R, &o, &rng, 4000);
        }
        assert_true(seen[GMMRRT_GRID_KEPT] >= 20 && seen[GMMRRT_GRID_SHIFTED] >= 20 && seen[GMMRRT_GRID_BUILT] >= 3);
        assert_int_equal(gmmrrt_world_grid_stats(world, &st), GMMRRT_OK);
        assert_int_equal(st.built + st.kept + st.shifted, 61);
        free(m.mem);
    }
}

static gmmrrt_grid_update_t update_kind(gmmrrt_world_t **w, block_t *m, double res, double robot_r, double person_r,
                                        const gmmrrt_obstacle_set_t *o)
{
    assert_int_equal(gmmrrt_world_update(w, m->mem, m->size, m->cells, res, robot_r, person_r, o), GMMRRT_OK);
    gmmrrt_world_grid_stats_t st;
    assert_int_equal(gmmrrt_world_grid_stats(*w, &st), GMMRRT_OK);
    return st.last;
}

/* Every change to what the grid is built from rebuilds it; the person radius does not (people
 * are not in the grid). After each, the world is the fresh one. */
static void test_changed_statics_rebuild_the_grid(void **state)
{
    (void)state;
    block_t m = block(1 << 17);
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, 3);
    const gmmrrt_obstacle_set_t base = statics();
    gmmrrt_world_t *w = NULL;
    assert_int_equal(update_kind(&w, &m, 0.05, ROBOT_R, PERSON_R, &base), GMMRRT_GRID_BUILT);
    assert_int_equal(update_kind(&w, &m, 0.05, ROBOT_R, PERSON_R, &base), GMMRRT_GRID_KEPT);

    for (int change = 0; change < 8; ++change) {
        gmmrrt_obstacle_set_t o = base;
        double res = 0.05, robot_r = ROBOT_R;
        switch (change) {
        case 0: o.circles[1].x = nextafter(o.circles[1].x, 10.0); break; /* one ulp */
        case 1: o.circles[0].radius_m = 1.2; break;
        case 2: o.boxes[0].yaw += 0.1; break;
        case 3: o.boxes[1].height_m = 2.0; break;
        case 4: o.circles[o.num_circles++] = (gmmrrt_circle_t){-1.0, -3.0, 0.5}; break;
        case 5: o.num_boxes = 1; break;
        case 6: robot_r = 0.25; break;
        default: res = 0.04; break;
        }
        assert_int_equal(update_kind(&w, &m, res, robot_r, PERSON_R, &o), GMMRRT_GRID_BUILT);
        assert_same_as_fresh(w, m.cells, res, robot_r, PERSON_R, &o, &rng, 2000);
        /* back to the base world: rebuilt again, not the changed one kept */
        assert_int_equal(update_kind(&w, &m, 0.05, ROBOT_R, PERSON_R, &base), GMMRRT_GRID_BUILT);
    }
    /* A moved circle really moves: where it stood is free afterwards, where it went is blocked. */
    gmmrrt_obstacle_set_t moved = base;
    moved.circles[0] = (gmmrrt_circle_t){-1.0, -2.5, 1.0};
    assert_false(gmmrrt_world_point_free(w, 0.0, 1.2));
    assert_true(gmmrrt_world_point_free(w, -1.0, -1.25));
    assert_int_equal(update_kind(&w, &m, 0.05, ROBOT_R, PERSON_R, &moved), GMMRRT_GRID_BUILT);
    assert_true(gmmrrt_world_point_free(w, 0.0, 1.2));
    assert_false(gmmrrt_world_point_free(w, -1.0, -1.25));
    /* The person radius is not in the grid: kept, and the answers are the fresh ones. */
    gmmrrt_obstacle_set_t with_people = moved;
    with_people.num_people = 1;
    with_people.people[0] = (gmmrrt_pose_t){2.0, 2.0, 0.0};
    assert_int_equal(update_kind(&w, &m, 0.05, ROBOT_R, 0.5, &with_people), GMMRRT_GRID_KEPT);
    assert_false(gmmrrt_world_point_free(w, 2.0, 2.0 + 0.79));
    assert_int_equal(update_kind(&w, &m, 0.05, ROBOT_R, 0.2, &with_people), GMMRRT_GRID_KEPT);
    assert_true(gmmrrt_world_point_free(w, 2.0, 2.0 + 0.51));
    assert_same_as_fresh(w, m.cells, 0.05, ROBOT_R, 0.2, &with_people, &rng, 2000);
    free(m.mem);
}

/* People are exact: with a coarse 0.25 m grid, a point a micrometre outside robot + person
 * radius is free and one a micrometre inside is blocked; an edge passing 1 mm + 1 um from the
 * inflated disc is free, one at 1 mm - 1 um is refused, at any angle, both ways, whether the
 * closest point is inside the edge or its end. Edges called free keep positive FCL clearance. */
static void test_people_are_checked_exactly(void **state)
{
    (void)state;
    block_t m = block(4096);
    gmmrrt_obstacle_set_t o;
    memset(&o, 0, sizeof o);
    o.bounds = (gmmrrt_bounds_t){-4.0, -4.0, 4.0, 4.0};
    o.num_people = 1;
    o.people[0] = (gmmrrt_pose_t){0.3, -0.2, 1.0};
    gmmrrt_world_t *w = NULL;
    assert_int_equal(gmmrrt_world_build(&w, m.mem, m.size, m.cells, 0.25, ROBOT_R, PERSON_R, &o), GMMRRT_OK);
    const double reach = ROBOT_R + PERSON_R, edge = reach + 1e-3, eps = 1e-6;
    const double px = o.people[0].x, py = o.people[0].y;
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, 9);
    for (int i = 0; i < 2000; ++i) {
        const double a = uniform(&rng, -M_PI, M_PI), ca = cos(a), sa = sin(a);
        assert_true(gmmrrt_world_point_free(w, px + (reach + eps) * ca, py + (reach + eps) * sa));
        assert_false(gmmrrt_world_point_free(w, px + (reach - eps) * ca, py + (reach - eps) * sa));
        /* A tangent edge at distance d from the centre: its closest point is (px, py) + d (ca, sa). */
        const double before = uniform(&rng, 0.05, 2.0), after = uniform(&rng, 0.05, 2.0);
        for (int s = 0; s < 2; ++s) {
            const double d = s ? edge + eps : edge - eps;
            const double cx = px + d * ca, cy = py + d * sa;
            const double x0 = cx + before * sa, y0 = cy - before * ca, x1 = cx - after * sa, y1 = cy + after * ca;
            assert_int_equal(gmmrrt_world_segment_free(w, x0, y0, x1, y1), s);
            assert_int_equal(gmmrrt_world_segment_free(w, x1, y1, x0, y0), s);
            /* Pointing at the person and stopping at distance d: the closest point is the end. */
            const double fx = px + (d + before) * ca, fy = py + (d + before) * sa;
            assert_int_equal(gmmrrt_world_segment_free(w, fx, fy, cx, cy), s);
            assert_int_equal(gmmrrt_world_segment_free(w, cx, cy, fx, fy), s);
            if (s) {
                for (double t = 0.0; t <= 1.0; t += 1e-3)
                    assert_true(gmmrrt_world_exact_clearance(w, x0 + t * (x1 - x0), y0 + t * (y1 - y0)) > 0.0);
            }
        }
    }
    /* Through the person, and a zero-length edge inside or outside its disc. */
    assert_false(gmmrrt_world_segment_free(w, -2.0, -0.2, 2.0, -0.2));
    assert_false(gmmrrt_world_segment_free(w, px + 0.1, py, px + 0.1, py));
    assert_true(gmmrrt_world_segment_free(w, px + reach + eps, py, px + reach + eps, py));
    /* A person outside the bounds still blocks what is inside within its reach. */
    o.people[o.num_people++] = (gmmrrt_pose_t){4.0 + 0.5, 1.0, 0.0};
    assert_int_equal(gmmrrt_world_build(&w, m.mem, m.size, m.cells, 0.25, ROBOT_R, PERSON_R, &o), GMMRRT_OK);
    assert_false(gmmrrt_world_point_free(w, 3.9, 1.0));
    assert_true(gmmrrt_world_point_free(w, 3.9, 1.0 + 0.6));
    assert_false(gmmrrt_world_segment_free(w, 3.99, -1.0, 3.99, 3.0));
    /* Person radius 0: people are not obstacles (as before the split). */
    assert_int_equal(gmmrrt_world_build(&w, m.mem, m.size, m.cells, 0.25, ROBOT_R, 0.0, &o), GMMRRT_OK);
    assert_true(gmmrrt_world_point_free(w, px, py));
    free(m.mem);
}

static void test_update_errors_leave_the_memory_alone(void **state)
{
    (void)state;
    block_t m = block(1 << 16), other = block(1 << 16);
    gmmrrt_obstacle_set_t o = statics();
    gmmrrt_world_t *w = NULL;
    assert_int_equal(gmmrrt_world_update(&w, m.mem, m.size, m.cells, 0.05, ROBOT_R, PERSON_R, &o), GMMRRT_OK);
    unsigned char *snapshot = malloc(m.size);
    assert_non_null(snapshot);
    memcpy(snapshot, m.mem, m.size);

    gmmrrt_world_t *wrong = other.mem; /* a world that does not live in mem */
    assert_int_equal(gmmrrt_world_update(&wrong, m.mem, m.size, m.cells, 0.05, ROBOT_R, PERSON_R, &o),
                     GMMRRT_ERR_INVALID_ARGUMENT);
    assert_null(wrong);
    assert_int_equal(gmmrrt_world_update(NULL, m.mem, m.size, m.cells, 0.05, ROBOT_R, PERSON_R, &o),
                     GMMRRT_ERR_INVALID_ARGUMENT);
    gmmrrt_obstacle_set_t bad = o;
    bad.circles[1].radius_m = NAN;
    gmmrrt_world_t *w2 = w;
    assert_int_equal(gmmrrt_world_update(&w2, m.mem, m.size, m.cells, 0.05, ROBOT_R, PERSON_R, &bad),
                     GMMRRT_ERR_INVALID_ARGUMENT);
    assert_null(w2);
    w2 = w;
    assert_int_equal(gmmrrt_world_update(&w2, m.mem, m.size, m.cells, 0.05, -1.0, PERSON_R, &o),
                     GMMRRT_ERR_INVALID_ARGUMENT);
    /* Bounds too big for the capacity, or further from the origin than the lattice reaches. */
    bad = o;
    bad.bounds.xmax = 1000.0;
    w2 = w;
    assert_int_equal(gmmrrt_world_update(&w2, m.mem, m.size, m.cells, 0.05, ROBOT_R, PERSON_R, &bad),
                     GMMRRT_ERR_BUFFER_TOO_SMALL);
    bad = o;
    bad.bounds = (gmmrrt_bounds_t){1e14, 0.0, 1e14 + 5.0, 5.0};
    w2 = w;
    assert_int_equal(gmmrrt_world_update(&w2, m.mem, m.size, m.cells, 0.05, ROBOT_R, PERSON_R, &bad),
                     GMMRRT_ERR_INVALID_ARGUMENT);
    assert_memory_equal(snapshot, m.mem, m.size);
    free(snapshot);
    /* After an error the caller has no world: the next update starts from scratch. */
    w2 = NULL;
    assert_int_equal(update_kind(&w2, &m, 0.05, ROBOT_R, PERSON_R, &o), GMMRRT_GRID_BUILT);
    gmmrrt_world_grid_stats_t st;
    assert_int_equal(gmmrrt_world_grid_stats(NULL, &st), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_int_equal(gmmrrt_world_grid_stats(w2, NULL), GMMRRT_ERR_INVALID_ARGUMENT);
    free(m.mem);
    free(other.mem);
}

/* Far from the origin (map frames in UTM, say) the lattice still works and stays conservative. */
static void test_far_from_the_origin(void **state)
{
    (void)state;
    block_t m = block(1 << 16);
    gmmrrt_obstacle_set_t o;
    memset(&o, 0, sizeof o);
    const double X = 652345.25, Y = 5123456.75;
    o.bounds = (gmmrrt_bounds_t){X - 5.0, Y - 4.0, X + 5.0, Y + 4.0};
    o.num_circles = 1;
    o.circles[0] = (gmmrrt_circle_t){X, Y, 1.0};
    o.num_boxes = 1;
    o.boxes[0] = (gmmrrt_box_t){X + 3.0, Y - 2.0, 1.5, 0.7, 0.8};
    gmmrrt_world_t *w = NULL;
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, 4);
    for (int round = 0; round < 6; ++round) {
        assert_int_equal(gmmrrt_world_update(&w, m.mem, m.size, m.cells, 0.05, ROBOT_R, PERSON_R, &o), GMMRRT_OK);
        int blocked = 0;
        for (int i = 0; i < 20000; ++i) {
            const double x = uniform(&rng, o.bounds.xmin, o.bounds.xmax), y = uniform(&rng, o.bounds.ymin, o.bounds.ymax);
            const double exact = gmmrrt_world_exact_clearance(w, x, y);
            const int f = gmmrrt_world_point_free(w, x, y);
            if (exact <= 0.0)
                assert_int_equal(f, 0);
            if (exact > 0.1)
                assert_int_equal(f, 1);
            blocked += !f;
        }
        assert_true(blocked > 1000);
        assert_same_as_fresh(w, m.cells, 0.05, ROBOT_R, PERSON_R, &o, &rng, 1000);
        o.bounds.xmin += 0.37;
        o.bounds.xmax += 0.37;
        o.bounds.ymax -= 0.21;
    }
    free(m.mem);
}

/* Through the planner: set_problem with people, start and goal moved keeps the grid. */
static void test_planner_keeps_the_grid_across_problems(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    cfg.max_nodes = 2000;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = disc_problem();
    pr.obstacles.num_people = 1;
    pr.obstacles.people[0] = (gmmrrt_pose_t){0.0, 3.0, 0.0};
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    gmmrrt_world_grid_stats_t st;
    assert_int_equal(gmmrrt_world_grid_stats(gmmrrt_planner_world(t.p), &st), GMMRRT_OK);
    assert_int_equal(st.last, GMMRRT_GRID_BUILT);
    pr.obstacles.people[0].x = 1.0;
    pr.start_x = -4.5;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    assert_int_equal(gmmrrt_world_grid_stats(gmmrrt_planner_world(t.p), &st), GMMRRT_OK);
    assert_int_equal(st.last, GMMRRT_GRID_KEPT);
    pr.obstacles.bounds.xmin += 0.5;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    assert_int_equal(gmmrrt_world_grid_stats(gmmrrt_planner_world(t.p), &st), GMMRRT_OK);
    assert_int_equal(st.last, GMMRRT_GRID_SHIFTED);
    /* A failed set_problem drops the world; the next one builds. */
    pr.obstacles.circles[0].radius_m = -1.0;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_INVALID_ARGUMENT);
    pr.obstacles.circles[0].radius_m = 2.0;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    assert_int_equal(gmmrrt_world_grid_stats(gmmrrt_planner_world(t.p), &st), GMMRRT_OK);
    assert_int_equal(st.last, GMMRRT_GRID_BUILT);
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, 8);
    assert_same_as_fresh(gmmrrt_planner_world(t.p), cfg.grid_max_cells, cfg.grid_resolution_m, cfg.robot_radius_m,
                         cfg.person_radius_m, &pr.obstacles, &rng, 2000);
    test_planner_free(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_kept_world_answers_as_a_fresh_build),
        cmocka_unit_test(test_changed_statics_rebuild_the_grid),
        cmocka_unit_test(test_people_are_checked_exactly),
        cmocka_unit_test(test_update_errors_leave_the_memory_alone),
        cmocka_unit_test(test_far_from_the_origin),
        cmocka_unit_test(test_planner_keeps_the_grid_across_problems),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
