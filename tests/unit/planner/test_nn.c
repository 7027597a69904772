/*
 * test_nn.c - planner.nn: the bucket-grid index (planner/src/nn.h) against a linear scan
 * (the nanoflann way): nearest and radius queries on random and clustered points, queries
 * on the bounds' edges, in the fixed and the adaptive (re-laid as the tree doubles) layout,
 * and the overflow report of a radius query.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <stdlib.h>

#include <cmocka.h>

#include "gmmrrt/rng.h"
#include "nn.h"

#define N 5000

static gmmrrt_node_t nodes[N];
static int32_t heads[N];

static int32_t linear_nearest(int32_t n, double x, double y, double *d2_out)
{
    int32_t best = -1;
    double best_d2 = INFINITY;
    for (int32_t i = 0; i < n; ++i) {
        const double d2 = (nodes[i].x - x) * (nodes[i].x - x) + (nodes[i].y - y) * (nodes[i].y - y);
        if (d2 < best_d2) {
            best_d2 = d2;
            best = i;
        }
    }
    *d2_out = best_d2;
    return best;
}

static int cmp_i32(const void *a, const void *b)
{
    const int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

static void check_against_scan(int clustered, double min_cell)
{
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, clustered ? 5u : 3u);
    const gmmrrt_bounds_t b = {-7.0, -5.0, 7.0, 5.0};
    gmmrrt_nn_t nn = {.heads = heads, .capacity = N};
    if (min_cell > 0.0)
        gmmrrt_nn_reset(&nn, &b, min_cell);
    else /* min_cell <= 0: the adaptive layout the planner uses, re-laid as the tree doubles */
        gmmrrt_nn_reset_adaptive(&nn, &b);
    assert_true(nn.nx * nn.ny <= N);
    static int32_t got[N], want[N];
    for (int32_t i = 0; i < N; ++i) {
        if (clustered) { /* most points in a 0.5 m blob, as mixture sampling makes them */
            nodes[i].x = 1.0 + 0.2 * gmmrrt_rng_normal(&rng);
            nodes[i].y = -2.0 + 0.2 * gmmrrt_rng_normal(&rng);
            if (i % 10 == 0) {
                nodes[i].x = b.xmin + gmmrrt_rng_uniform(&rng) * 14.0;
                nodes[i].y = b.ymin + gmmrrt_rng_uniform(&rng) * 10.0;
            }
        } else {
            nodes[i].x = b.xmin + gmmrrt_rng_uniform(&rng) * 14.0;
            nodes[i].y = b.ymin + gmmrrt_rng_uniform(&rng) * 10.0;
        }
        gmmrrt_nn_insert(&nn, nodes, i);
        if (min_cell <= 0.0)
            assert_true(nn.nx * nn.ny <= N);
        if (i % 97 != 0 && i > 20 && (i & (i - 1)) != 0 && ((i + 1) & i) != 0) /* and around re-layouts */
            continue;
        for (int q = 0; q < 20; ++q) {
            const double qx = q == 0 ? b.xmin : (q == 1 ? b.xmax : b.xmin + gmmrrt_rng_uniform(&rng) * 14.0);
            const double qy = q == 0 ? b.ymin : (q == 1 ? b.ymax : b.ymin + gmmrrt_rng_uniform(&rng) * 10.0);
            double d2;
            const int32_t lin = linear_nearest(i + 1, qx, qy, &d2);
            const int32_t idx = gmmrrt_nn_nearest(&nn, nodes, qx, qy);
            assert_true(idx >= 0);
            const double gd2 = (nodes[idx].x - qx) * (nodes[idx].x - qx) + (nodes[idx].y - qy) * (nodes[idx].y - qy);
            assert_true(gd2 == d2); /* same distance (ties may pick another index) */
            (void)lin;
            const double r = 0.05 + gmmrrt_rng_uniform(&rng) * 1.5;
            const int32_t n = gmmrrt_nn_near(&nn, nodes, qx, qy, r, got, N);
            assert_true(n >= 0);
            int32_t m = 0;
            for (int32_t k = 0; k <= i; ++k)
                if ((nodes[k].x - qx) * (nodes[k].x - qx) + (nodes[k].y - qy) * (nodes[k].y - qy) <= r * r)
                    want[m++] = k;
            assert_int_equal(n, m);
            qsort(got, (size_t)n, sizeof got[0], cmp_i32);
            assert_memory_equal(got, want, sizeof(int32_t) * (size_t)m);
        }
    }
}

static void test_nearest_and_near_match_linear_scan_uniform(void **state)
{
    (void)state;
    check_against_scan(0, 0.125);
}

static void test_nearest_and_near_match_linear_scan_clustered(void **state)
{
    (void)state;
    check_against_scan(1, 0.125);
    check_against_scan(1, 2.0); /* coarse buckets */
}

static void test_adaptive_layout_matches_linear_scan(void **state)
{
    (void)state;
    check_against_scan(0, 0.0);
    check_against_scan(1, 0.0);
}

static void test_near_reports_overflow(void **state)
{
    (void)state;
    const gmmrrt_bounds_t b = {0.0, 0.0, 1.0, 1.0};
    gmmrrt_nn_t nn = {.heads = heads, .capacity = N};
    gmmrrt_nn_reset(&nn, &b, 0.1);
    for (int32_t i = 0; i < 10; ++i) {
        nodes[i].x = 0.5 + 0.001 * i;
        nodes[i].y = 0.5;
        gmmrrt_nn_insert(&nn, nodes, i);
    }
    int32_t out[4];
    assert_int_equal(gmmrrt_nn_near(&nn, nodes, 0.5, 0.5, 0.1, out, 4), -1);
    assert_int_equal(gmmrrt_nn_near(&nn, nodes, 0.5, 0.5, 0.0025, out, 4), 3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nearest_and_near_match_linear_scan_uniform),
        cmocka_unit_test(test_nearest_and_near_match_linear_scan_clustered),
        cmocka_unit_test(test_adaptive_layout_matches_linear_scan),
        cmocka_unit_test(test_near_reports_overflow),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
