/*
 * test_raster.c - planner.raster: the occupancy raster (raster.h) against brute-force oracles.
 * The distance field at every cell corner equals the distance from that corner to the nearest
 * blocked cell's square found by scanning every cell (to float rounding, never above it), with
 * the outside blocking or not, scan marks active or decayed, whole or windowed; the bound the
 * collision world reads never exceeds the true distance to the squares and equals it at the
 * corners, nor does the union of the corners' discs, which is never below it and mostly much
 * nearer the distance; scans mark their end
 * cells, clear what the beams cross, ignore NaN / inf / out-of-range ranges, and their marks
 * decay; a collision world with a raster never calls a point free that is within the robot's
 * radius of a blocked cell (checked against the cells, not the field).
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
#include "gmmrrt/raster.h"
#include "gmmrrt/rng.h"
#include "planner_fixtures.h"
#include "planner_internal.h"

typedef struct {
    void *mem;
    gmmrrt_raster_t r;
} raster_block_t;

static void make_raster(raster_block_t *b, int32_t max_cells, int32_t max_side)
{
    const size_t size = gmmrrt_raster_mem_size(max_cells, max_side);
    assert_true(size > 0);
    b->mem = aligned_alloc(8, (size + 7u) & ~(size_t)7u);
    assert_non_null(b->mem);
    assert_int_equal(gmmrrt_raster_init(&b->r, b->mem, size, max_cells, max_side), GMMRRT_OK);
}

static double rnd(gmmrrt_rng_t *g, double lo, double hi) { return lo + (hi - lo) * gmmrrt_rng_uniform(g); }

/* The scan marks' clock the oracle judges marks by (ms since the first scan; decay ms), as
 * raster.h states the rule: a mark blocks while now - its time <= decay. */
static double g_now_ms = 0.0, g_decay_ms = 0.0;

static int blocked_cell(const gmmrrt_raster_t *r, int32_t i, int32_t j)
{
    if (i < 0 || j < 0 || i >= r->width || j >= r->height)
        return r->unknown_blocked;
    const size_t c = (size_t)j * (size_t)r->width + (size_t)i;
    const uint8_t v = r->cells[c];
    const uint32_t m = r->marks[c];
    return v == GMMRRT_RASTER_OCCUPIED || (v == GMMRRT_RASTER_UNKNOWN && r->unknown_blocked) ||
           (m != 0 && g_now_ms - (double)(m - 1u) <= g_decay_ms);
}

/* Distance (cells) from raster-frame point (u, v) (cells) to the closed square of cell (a, b). */
static double to_square(double u, double v, int32_t a, int32_t b)
{
    const double ex = u < a ? a - u : (u > a + 1.0 ? u - a - 1.0 : 0.0);
    const double ey = v < b ? b - v : (v > b + 1.0 ? v - b - 1.0 : 0.0);
    return hypot(ex, ey);
}

/* Distance (cells) from (u, v) to the nearest blocked cell's square, the outside (when it
 * blocks) as the ring of cells around the raster (its part nearest to any point). */
static double brute_squares(const gmmrrt_raster_t *r, double u, double v)
{
    double best = INFINITY;
    for (int32_t b = -1; b <= r->height; ++b)
        for (int32_t a = -1; a <= r->width; ++a)
            if (blocked_cell(r, a, b)) {
                const double d = to_square(u, v, a, b);
                best = d < best ? d : best;
            }
    return best;
}

/* The field at corner (i, j). */
static double field_at(const gmmrrt_raster_t *r, int32_t i, int32_t j)
{
    return (double)r->dist[(size_t)j * ((size_t)r->width + 1u) + (size_t)i];
}

/* Raster-frame point (u, v) (cells) to the world. */
static void to_world(const gmmrrt_raster_t *r, double u, double v, double *x, double *y)
{
    const double res = r->resolution_m;
    *x = r->origin_x + res * (u * r->cos_yaw - v * r->sin_yaw);
    *y = r->origin_y + res * (u * r->sin_yaw + v * r->cos_yaw);
}

/* Scans from random places inside the raster at utime t, each of `beams` random ranges. */
static void random_scans(gmmrrt_raster_t *r, gmmrrt_rng_t *g, int64_t utime, int beams)
{
    float ranges[64];
    assert_true(beams <= 64);
    for (int k = 0; k < beams; ++k)
        ranges[k] = (float)rnd(g, 0.0, 2.0);
    const gmmrrt_scan_t scan = {rnd(g, -3.0, 3.0), 2.0 * M_PI / beams, 0.05, 1.8, beams, ranges};
    double x, y;
    to_world(r, rnd(g, 0, r->width), rnd(g, 0, r->height), &x, &y);
    assert_int_equal(gmmrrt_raster_apply_scan(r, &scan, x, y, rnd(g, -3, 3), utime, NULL, NULL), GMMRRT_OK);
}

/* A random raster at a random pose; with `unrotated`, at yaw 0 (the maps' usual pose, which the
 * world-to-cell conversion takes without the rotation). */
static void random_raster_at(gmmrrt_raster_t *r, gmmrrt_rng_t *g, int32_t w, int32_t h, double fill,
                             int unknown_blocked, int unrotated)
{
    /* Drawn yaw first, then y, then x: the order the tests' seeds and counts were chosen with. */
    const double yaw = rnd(g, -3, 3), oy = rnd(g, -3, 3), ox = rnd(g, -3, 3);
    assert_int_equal(gmmrrt_raster_set_geometry(r, w, h, 0.1, ox, oy, unrotated ? 0.0 : yaw, unknown_blocked),
                     GMMRRT_OK);
    for (int32_t c = 0; c < w * h; ++c) {
        const double u = rnd(g, 0, 1);
        r->cells[c] = u < fill ? GMMRRT_RASTER_OCCUPIED : (u < fill * 1.3 ? GMMRRT_RASTER_UNKNOWN : GMMRRT_RASTER_FREE);
    }
}

static void random_raster(gmmrrt_raster_t *r, gmmrrt_rng_t *g, int32_t w, int32_t h, double fill, int unknown_blocked)
{
    random_raster_at(r, g, w, h, fill, unknown_blocked, 0);
}

static void test_distance_field_matches_brute_force(void **state)
{
    (void)state;
    raster_block_t b;
    make_raster(&b, 64 * 64, 64);
    gmmrrt_rng_t g;
    gmmrrt_rng_seed(&g, 5);
    for (int round = 0; round < 24; ++round) {
        const int32_t w = 1 + (int32_t)rnd(&g, 0, 40), h = 1 + (int32_t)rnd(&g, 0, 40);
        const double fill = round % 4 == 0 ? 0.0 : rnd(&g, 0.001, 0.2);
        random_raster(&b.r, &g, w, h, fill, round % 2);
        /* Every third round also has scan marks: two scans 0.3 s apart, the field taken 0.4 s
         * after the first with a 0.2 s decay, so the first scan's marks no longer block. */
        const int scans = round % 3 == 1;
        const int64_t t0 = 5000000;
        if (scans) {
            random_scans(&b.r, &g, t0, 24);
            random_scans(&b.r, &g, t0 + 300000, 24);
        }
        g_now_ms = scans ? 400.0 : 0.0;
        g_decay_ms = scans ? 200.0 : 0.0;
        assert_false(gmmrrt_raster_distance_ready(&b.r));
        assert_int_equal(gmmrrt_raster_update_distance(&b.r, scans ? t0 + 400000 : 0, g_decay_ms), GMMRRT_OK);
        assert_true(gmmrrt_raster_distance_ready(&b.r));
        for (int32_t j = 0; j <= h; ++j)
            for (int32_t i = 0; i <= w; ++i) {
                const double want = brute_squares(&b.r, i, j) * b.r.resolution_m;
                const double got = field_at(&b.r, i, j);
                if (isinf(want)) {
                    assert_true(got > 1e30);
                    continue;
                }
                if (!(got <= want && got >= want * (1.0 - 1e-5) - 1e-9))
                    fail_msg("round %d corner (%d, %d) of %d x %d: field %.9g, brute force %.9g", round, i, j, w,
                             h, got, want);
            }
    }
    g_now_ms = g_decay_ms = 0.0;
    free(b.mem);
}

static void test_clearance_bound_is_a_lower_bound(void **state)
{
    (void)state;
    raster_block_t b;
    make_raster(&b, 50 * 50, 50);
    gmmrrt_rng_t g;
    gmmrrt_rng_seed(&g, 9);
    for (int round = 0; round < 12; ++round) {
        random_raster_at(&b.r, &g, 30, 20, 0.03, round % 2, round >= 8); /* the last four unrotated */
        assert_int_equal(gmmrrt_raster_update_distance(&b.r, 0, 0.0), GMMRRT_OK);
        int loose = 0, tighter = 0;
        double gap_corners = 0.0, gap_union = 0.0;
        for (int q = 0; q < 3000; ++q) {
            /* Points in and around the raster, in the raster frame, then to the world; every
             * fourth a corner of the raster. */
            const int corner = q % 4 == 0;
            const double u = corner ? floor(rnd(&g, 0, 31)) : rnd(&g, -5, 35);
            const double v = corner ? floor(rnd(&g, 0, 21)) : rnd(&g, -5, 25);
            double x, y;
            to_world(&b.r, u, v, &x, &y);
            const double best = 0.1 * brute_squares(&b.r, u, v);
            const double lb = gmmrrt_raster_clearance_bound(&b.r, x, y);
            if (!(lb <= best + 1e-9))
                fail_msg("bound %.9g above the true distance %.9g at (%g, %g) cells", lb, best, u, v);
            /* At a corner the bound is the distance itself, to the rounding of the world point
             * and of the float field; elsewhere at most short by a cell's diagonal (twice the
             * distance to the nearest corner) on the raster. */
            if (corner && !(lb >= best * (1.0 - 1e-5) - 1e-9))
                fail_msg("bound %.9g below the distance %.9g at corner (%g, %g)", lb, best, u, v);
            if (u >= 0 && v >= 0 && u <= 30 && v <= 20 && !(lb >= best - 0.1 * M_SQRT2 - 1e-9))
                fail_msg("bound %.9g short of the distance %.9g by more than a diagonal at (%g, %g)", lb, best, u, v);
            loose += !corner && lb < best - 1e-6;
            /* The union of the corners' discs: a bound too, never below the four-corner one. */
            const double lu = gmmrrt_raster_clearance_union(&b.r, x, y);
            if (!(lu <= best + 1e-9))
                fail_msg("union bound %.12g above the true distance %.12g at (%g, %g) cells", lu, best, u, v);
            if (!(lu >= lb - 1e-8))
                fail_msg("union bound %.12g below the four-corner bound %.12g at (%g, %g) cells", lu, lb, u, v);
            if (u >= 0 && v >= 0 && u <= 30 && v <= 20 && isfinite(best) && lb > 0.0) {
                gap_corners += best - lb;
                gap_union += best - lu;
                tighter += lu > lb + 1e-6;
            }
        }
        assert_true(loose > 0); /* between the corners the bound is a bound, not the distance */
        /* The union is the tighter bound at many points, and its loss a fraction of the other's. */
        if (!(tighter > 300 && gap_union < 0.5 * gap_corners))
            fail_msg("round %d: union tighter at %d points, total loss %.6g against %.6g", round, tighter, gap_union,
                     gap_corners);
    }
    free(b.mem);
}

/* The windowed field: inside the window, the full field capped at the reach (to float
 * rounding, never above the full field); outside it the bound calls every point blocked. */
static void test_windowed_field_is_the_full_one_capped(void **state)
{
    (void)state;
    raster_block_t full, win;
    make_raster(&full, 120 * 90, 120);
    make_raster(&win, 120 * 90, 120);
    gmmrrt_rng_t g;
    gmmrrt_rng_seed(&g, 17);
    int rounds_with_cells = 0;
    for (int round = 0; round < 12; ++round) {
        random_raster(&full.r, &g, 120, 90, rnd(&g, 0.001, 0.02), round % 2);
        assert_int_equal(gmmrrt_raster_set_geometry(&win.r, 120, 90, full.r.resolution_m, full.r.origin_x,
                                                    full.r.origin_y, full.r.origin_yaw, full.r.unknown_blocked),
                         GMMRRT_OK);
        memcpy(win.r.cells, full.r.cells, 120 * 90);
        assert_int_equal(gmmrrt_raster_update_distance(&full.r, 0, 0.0), GMMRRT_OK);
        /* The full field itself against the brute force at every corner. */
        for (int32_t j = 0; j <= 90; ++j)
            for (int32_t i = 0; i <= 120; ++i) {
                const double want = 0.1 * brute_squares(&full.r, i, j), got = field_at(&full.r, i, j);
                if (!(isinf(want) ? got > 1e30 : (got <= want && got >= want * (1.0 - 1e-5) - 1e-9)))
                    fail_msg("round %d corner (%d, %d): field %.9g, brute force %.9g", round, i, j, got, want);
            }
        const double cx = rnd(&g, -8, 8), cy = rnd(&g, -8, 8), hw = rnd(&g, 0.2, 3), hh = rnd(&g, 0.2, 3);
        const double reach = rnd(&g, 0.2, 1.5);
        assert_int_equal(gmmrrt_raster_update_distance_window(&win.r, 0, 0.0, cx - hw, cy - hh, cx + hw, cy + hh, reach),
                         GMMRRT_OK);
        assert_true(gmmrrt_raster_distance_ready(&win.r));
        const double cap = (ceil(reach / 0.1) + 1.0) * 0.1;
        int inside = 0;
        for (int32_t j = win.r.valid_j0; j < win.r.valid_j1; ++j)
            for (int32_t i = win.r.valid_i0; i < win.r.valid_i1; ++i) {
                const double fu = field_at(&full.r, i, j), want = fmin(fu, cap), got = field_at(&win.r, i, j);
                if (!(got <= fu && got >= want * (1.0 - 1e-6) - 1e-9))
                    fail_msg("round %d corner (%d, %d): window %.9g, full %.9g, cap %.9g", round, i, j, got, fu, cap);
                ++inside;
            }
        /* Every point of the box is inside the window and bounded as with the full field, up to the cap. */
        for (int q = 0; q < 500; ++q) {
            const double x = cx + rnd(&g, -hw, hw), y = cy + rnd(&g, -hh, hh);
            const double bw = gmmrrt_raster_clearance_bound(&win.r, x, y), bf = gmmrrt_raster_clearance_bound(&full.r, x, y);
            assert_true(bw <= bf + 1e-9);
            const double dx = x - win.r.origin_x, dy = y - win.r.origin_y;
            const double u = (dx * win.r.cos_yaw + dy * win.r.sin_yaw) / 0.1, v = (-dx * win.r.sin_yaw + dy * win.r.cos_yaw) / 0.1;
            if (u >= 0.0 && v >= 0.0 && u <= 120.0 && v <= 90.0) /* on the raster: its corners are in the window */
                assert_true(isfinite(bw));
        }
        rounds_with_cells += inside > 0;
        /* Far outside the window: blocked. */
        if (inside > 0 && win.r.valid_i1 + 3 < 121) {
            const double u = (double)win.r.valid_i1 + 1.5, v = 0.5 * (win.r.valid_j0 + win.r.valid_j1);
            double x, y;
            to_world(&win.r, u, v, &x, &y);
            assert_true(gmmrrt_raster_clearance_bound(&win.r, x, y) == -INFINITY);
        }
    }
    assert_true(rounds_with_cells >= 6); /* most boxes meet the raster */
    free(full.mem);
    free(win.mem);
}

/* The four-corner bound as raster.h defines it, written out here: the point's cell's corners
 * (floor and the next, clamped to the lattice), each valid one's field less the point's distance
 * to it, the largest; -infinity when none is valid. */
static double four_corner_definition(const gmmrrt_raster_t *r, double x, double y)
{
    const double dx = x - r->origin_x, dy = y - r->origin_y;
    const double u = (dx * r->cos_yaw + dy * r->sin_yaw) * r->inv_resolution_m;
    const double v = (-dx * r->sin_yaw + dy * r->cos_yaw) * r->inv_resolution_m;
    double best = -INFINITY;
    for (int di = 0; di <= 1; ++di)
        for (int dj = 0; dj <= 1; ++dj) {
            int32_t i = (int32_t)fmin(fmax(floor(u) + di, 0.0), (double)r->width);
            int32_t j = (int32_t)fmin(fmax(floor(v) + dj, 0.0), (double)r->height);
            if (!(u >= 0.0))
                i = 0;
            if (!(v >= 0.0))
                j = 0;
            if (i < r->valid_i0 || i >= r->valid_i1 || j < r->valid_j0 || j >= r->valid_j1)
                continue;
            const double lb = field_at(r, i, j) - hypot(i - u, j - v) * r->resolution_m;
            best = lb > best ? lb : best;
        }
    return best;
}

/* The bound a search reads (inline where the four corners are all valid, raster_bound.h; the
 * general code elsewhere) is the definition above: at random points on and off the raster, on
 * its window's edges and on cell corners, rotated or not, with the whole field and a window. */
static void test_clearance_bound_is_its_definition_everywhere(void **state)
{
    (void)state;
    raster_block_t b;
    make_raster(&b, 60 * 40, 60);
    gmmrrt_rng_t g;
    gmmrrt_rng_seed(&g, 29);
    long interior = 0, other = 0;
    for (int round = 0; round < 8; ++round) {
        random_raster_at(&b.r, &g, 60, 40, 0.03, round % 2, round % 4 < 2);
        if (round < 4)
            assert_int_equal(gmmrrt_raster_update_distance(&b.r, 0, 0.0), GMMRRT_OK);
        else
            assert_int_equal(gmmrrt_raster_update_distance_window(&b.r, 0, 0.0, b.r.origin_x - 1.0, b.r.origin_y - 1.0,
                                                                  b.r.origin_x + 2.0, b.r.origin_y + 1.5, 0.6),
                             GMMRRT_OK);
        for (int q = 0; q < 20000; ++q) {
            double u = rnd(&g, -3, 63), v = rnd(&g, -3, 43);
            if (q % 5 == 0) { /* on a corner, or on the valid window's last corners */
                u = floor(u);
                v = floor(v);
            } else if (q % 5 == 1) {
                u = (double)b.r.valid_i1 - 1.0 + rnd(&g, -1e-9, 1e-9);
                v = (double)b.r.valid_j1 - 1.0 + rnd(&g, -1e-9, 1e-9);
            }
            double x, y;
            to_world(&b.r, u, v, &x, &y);
            const double got = gmmrrt_raster_clearance_bound(&b.r, x, y), want = four_corner_definition(&b.r, x, y);
            if (!(got == want || fabs(got - want) <= 1e-12 * (1.0 + fabs(want))))
                fail_msg("round %d at (%.12g, %.12g) cells: bound %.17g, definition %.17g", round, u, v, got, want);
            const int inside = u >= b.r.valid_i0 && u < b.r.valid_i1 - 1 && v >= b.r.valid_j0 && v < b.r.valid_j1 - 1;
            interior += inside;
            other += !inside;
        }
    }
    assert_true(interior > 10000 && other > 10000); /* both the inline case and the general one ran */
    free(b.mem);
}

static void test_scans_mark_clear_ignore_and_decay(void **state)
{
    (void)state;
    raster_block_t b;
    make_raster(&b, 100 * 100, 100);
    assert_int_equal(gmmrrt_raster_set_geometry(&b.r, 100, 100, 0.1, -5.0, -5.0, 0.0, 0), GMMRRT_OK);
    memset(b.r.cells, GMMRRT_RASTER_FREE, 100 * 100);
    /* Four beams along +x, +y, -x, -y of 2.05 m, then bad ones. */
    float ranges[8] = {2.05f, 2.05f, 2.05f, 2.05f, NAN, INFINITY, 0.01f, 30.0f};
    gmmrrt_scan_t scan = {0.0, M_PI / 2.0, 0.05, 10.0, 8, ranges};
    int32_t marked, cleared;
    const int64_t t0 = 1000000000;
    assert_int_equal(gmmrrt_raster_apply_scan(&b.r, &scan, 0.0, 0.0, 0.0, t0, &marked, &cleared), GMMRRT_OK);
    assert_int_equal(marked, 4);
    assert_int_equal(cleared, 0);
    assert_false(gmmrrt_raster_distance_ready(&b.r));
    assert_int_equal(gmmrrt_raster_update_distance(&b.r, t0, 500.0), GMMRRT_OK);
    /* The end cell of the +x beam: x = 2.05 -> cell 70, y = 0 -> cell 50; the field is 0 at its
     * four corners. */
    assert_true(field_at(&b.r, 70, 50) == 0.0 && field_at(&b.r, 71, 50) == 0.0 && field_at(&b.r, 70, 51) == 0.0 &&
                field_at(&b.r, 71, 51) == 0.0);
    assert_true(fabs(field_at(&b.r, 69, 50) - 0.1) < 1e-6);
    assert_true(fabs(gmmrrt_raster_distance_to_blocked(&b.r, 0.0, 0.0, 5.0) - 2.0) < 1e-9);
    /* A second scan whose +x beam reaches further clears the old end cell and marks the new. */
    float longer[1] = {3.05f};
    gmmrrt_scan_t one = {0.0, 0.0, 0.05, 10.0, 1, longer};
    assert_int_equal(gmmrrt_raster_apply_scan(&b.r, &one, 0.0, 0.0, 0.0, t0 + 100000, &marked, &cleared), GMMRRT_OK);
    assert_int_equal(marked, 1);
    assert_int_equal(cleared, 1);
    assert_int_equal(gmmrrt_raster_update_distance(&b.r, t0 + 100000, 500.0), GMMRRT_OK);
    assert_true(field_at(&b.r, 70, 50) > 0.0 && field_at(&b.r, 71, 51) > 0.0);
    assert_true(field_at(&b.r, 80, 50) == 0.0 && field_at(&b.r, 81, 51) == 0.0);
    /* 0.6 s after the first scan its marks have decayed (500 ms), the second scan's not. */
    assert_int_equal(gmmrrt_raster_update_distance(&b.r, t0 + 600000, 500.0), GMMRRT_OK);
    assert_true(field_at(&b.r, 50, 70) > 0.0 && field_at(&b.r, 51, 71) > 0.0); /* +y end cell of the first scan */
    assert_true(field_at(&b.r, 80, 50) == 0.0);
    assert_int_equal(gmmrrt_raster_update_distance(&b.r, t0 + 700000, 500.0), GMMRRT_OK);
    assert_true(field_at(&b.r, 80, 50) > 1e30); /* nothing blocks any more */
    /* Bad scans are refused and change nothing. */
    const uint32_t gen = b.r.generation;
    gmmrrt_scan_t bad = scan;
    bad.num_ranges = GMMRRT_MAX_SCAN_RANGES + 1;
    assert_int_equal(gmmrrt_raster_apply_scan(&b.r, &bad, 0, 0, 0, t0, NULL, NULL), GMMRRT_ERR_INVALID_ARGUMENT);
    bad = scan;
    bad.range_max_m = NAN;
    assert_int_equal(gmmrrt_raster_apply_scan(&b.r, &bad, 0, 0, 0, t0, NULL, NULL), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_int_equal(gmmrrt_raster_apply_scan(&b.r, &scan, NAN, 0, 0, t0, NULL, NULL), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_int_equal(gmmrrt_raster_apply_scan(&b.r, &scan, 0, 0, 0, t0 - 1, NULL, NULL), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_int_equal(b.r.generation, gen);
    free(b.mem);
}

static void test_geometry_beyond_capacity_is_refused(void **state)
{
    (void)state;
    raster_block_t b;
    make_raster(&b, 1000, 50);
    assert_int_equal(gmmrrt_raster_set_geometry(&b.r, 51, 10, 0.1, 0, 0, 0, 1), GMMRRT_ERR_BUFFER_TOO_SMALL);
    assert_int_equal(gmmrrt_raster_set_geometry(&b.r, 40, 26, 0.1, 0, 0, 0, 1), GMMRRT_ERR_BUFFER_TOO_SMALL);
    assert_int_equal(gmmrrt_raster_set_geometry(&b.r, 40, 25, -0.1, 0, 0, 0, 1), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_int_equal(gmmrrt_raster_set_geometry(&b.r, 40, 25, 0.1, 0, INFINITY, 0, 1), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_int_equal(gmmrrt_raster_set_geometry(&b.r, 40, 25, 0.1, 0, 0, 0, 1), GMMRRT_OK);
    assert_int_equal(gmmrrt_raster_mem_size(GMMRRT_MAX_RASTER_CELLS, GMMRRT_MAX_RASTER_SIDE + 1), 0);
    /* The block holds the field at every corner of the widest rasters the capacity admits: a
     * full 50 x 20, and a 1000 x 1 strip of a capacity 1000 cells with sides up to 1000. */
    assert_int_equal(gmmrrt_raster_set_geometry(&b.r, 50, 20, 0.1, 0, 0, 0, 1), GMMRRT_OK);
    memset(b.r.cells, GMMRRT_RASTER_FREE, 50 * 20);
    assert_int_equal(gmmrrt_raster_update_distance(&b.r, 0, 0.0), GMMRRT_OK);
    assert_true(fabs(field_at(&b.r, 50, 20)) < 1e-12 && fabs(field_at(&b.r, 25, 10) - 1.0) < 1e-5);
    raster_block_t strip;
    make_raster(&strip, 1000, 1000);
    assert_true(gmmrrt_raster_mem_size(1000, 1000) >= 1000u * 5u + 1001u * 2u * sizeof(float));
    assert_int_equal(gmmrrt_raster_set_geometry(&strip.r, 1000, 1, 0.1, 0, 0, 0, 0), GMMRRT_OK);
    memset(strip.r.cells, GMMRRT_RASTER_FREE, 1000);
    strip.r.cells[999] = GMMRRT_RASTER_OCCUPIED;
    assert_int_equal(gmmrrt_raster_update_distance(&strip.r, 0, 0.0), GMMRRT_OK);
    assert_true(fabs(field_at(&strip.r, 0, 1) - 99.9) < 99.9 * 1e-5 && field_at(&strip.r, 1000, 1) == 0.0);
    free(strip.mem);
    /* The figure an oversize map's refusal names: cells and marks, then a float per corner. */
    assert_true(gmmrrt_raster_bytes(100, 50) == 100.0 * 50.0 * 5.0 + 101.0 * 51.0 * 4.0);
    free(b.mem);
}

/* The world never calls a point free within the robot's radius of a blocked cell's square. */
static void test_world_with_raster_keeps_the_robot_radius(void **state)
{
    (void)state;
    raster_block_t b;
    make_raster(&b, 80 * 60, 80);
    gmmrrt_rng_t g;
    gmmrrt_rng_seed(&g, 13);
    random_raster(&b.r, &g, 80, 60, 0.01, 1);
    assert_int_equal(gmmrrt_raster_update_distance(&b.r, 0, 0.0), GMMRRT_OK);
    gmmrrt_obstacle_set_t o;
    memset(&o, 0, sizeof o);
    o.bounds = (gmmrrt_bounds_t){-15, -15, 15, 15};
    o.num_circles = 1;
    o.circles[0] = (gmmrrt_circle_t){1.0, 1.0, 0.5};
    o.raster = &b.r;
    const int32_t cells = 1 << 20;
    const size_t size = gmmrrt_world_mem_size(cells);
    void *mem = aligned_alloc(8, (size + 7u) & ~(size_t)7u);
    gmmrrt_world_t *w = NULL;
    const double robot = 0.25;
    assert_int_equal(gmmrrt_world_build(&w, mem, size, cells, 0.05, robot, 0.3, &o), GMMRRT_OK);
    int free_seen = 0, blocked_seen = 0;
    for (int q = 0; q < 20000; ++q) {
        /* Half the queries with the union of the corners' discs on (as the planner sets it once
         * it has a path). */
        gmmrrt_world_set_raster_union(w, q >= 10000);
        const double x = rnd(&g, -15, 15), y = rnd(&g, -15, 15);
        const int f = gmmrrt_world_point_free(w, x, y);
        const double exact = gmmrrt_world_exact_clearance(w, x, y);
        if (f && !(exact > 0.0))
            fail_msg("(%g, %g) called free with exact clearance %.9g", x, y, exact);
        /* Exact to the cell: free wherever the clearance exceeds a cell's diagonal. */
        if (exact > b.r.resolution_m * 1.5 + 0.05 * 1.5)
            assert_true(f);
        free_seen += f;
        blocked_seen += !f;
        if (q % 8 == 0) {
            const double x1 = fmin(fmax(x + rnd(&g, -1, 1), -15), 15), y1 = fmin(fmax(y + rnd(&g, -1, 1), -15), 15);
            if (gmmrrt_world_segment_free(w, x, y, x1, y1))
                for (int k = 0; k <= 200; ++k) {
                    const double t = k / 200.0;
                    assert_true(gmmrrt_world_exact_clearance(w, x + t * (x1 - x), y + t * (y1 - y)) > 0.0);
                }
        }
    }
    if (!(free_seen > 200 && blocked_seen > 1000)) /* the raster is 5 % of the bounds, its outside blocks */
        fail_msg("%d free, %d blocked", free_seen, blocked_seen);
    free(mem);
    free(b.mem);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_distance_field_matches_brute_force),
        cmocka_unit_test(test_clearance_bound_is_a_lower_bound),
        cmocka_unit_test(test_windowed_field_is_the_full_one_capped),
        cmocka_unit_test(test_clearance_bound_is_its_definition_everywhere),
        cmocka_unit_test(test_scans_mark_clear_ignore_and_decay),
        cmocka_unit_test(test_geometry_beyond_capacity_is_refused),
        cmocka_unit_test(test_world_with_raster_keeps_the_robot_radius),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
