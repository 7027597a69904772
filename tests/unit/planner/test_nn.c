/*
 * test_nn.c - planner.nn: the bucket-grid index (planner/src/nn.h) against a linear scan
 * (the nanoflann way): nearest and radius queries on random and clustered points, queries
 * on the bounds' edges, in the fixed and the adaptive (re-laid as the tree doubles) layout,
 * the overflow report of a radius query, the k-nearest near set, and the sorted re-layout
 * (nodes renumbered in bucket order, tree links and references rewritten).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "gmmrrt/rng.h"
#include "nn.h"

#define N 5000

static gmmrrt_xy_t xy[N];
static double cost[N];
static gmmrrt_links_t links[N];
static int32_t next_in_bucket[N];
static gmmrrt_pool_t pool = {xy, cost, links, next_in_bucket};
static int32_t heads[N];

static int32_t linear_nearest(int32_t n, double x, double y, double *d2_out)
{
    int32_t best = -1;
    double best_d2 = INFINITY;
    for (int32_t i = 0; i < n; ++i) {
        const double d2 = (xy[i].x - x) * (xy[i].x - x) + (xy[i].y - y) * (xy[i].y - y);
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
            xy[i].x = 1.0 + 0.2 * gmmrrt_rng_normal(&rng);
            xy[i].y = -2.0 + 0.2 * gmmrrt_rng_normal(&rng);
            if (i % 10 == 0) {
                xy[i].x = b.xmin + gmmrrt_rng_uniform(&rng) * 14.0;
                xy[i].y = b.ymin + gmmrrt_rng_uniform(&rng) * 10.0;
            }
        } else {
            xy[i].x = b.xmin + gmmrrt_rng_uniform(&rng) * 14.0;
            xy[i].y = b.ymin + gmmrrt_rng_uniform(&rng) * 10.0;
        }
        gmmrrt_nn_insert(&nn, &pool, i);
        if (min_cell <= 0.0)
            assert_true(nn.nx * nn.ny <= N);
        if (i % 97 != 0 && i > 20 && (i & (i - 1)) != 0 && ((i + 1) & i) != 0) /* and around re-layouts */
            continue;
        for (int q = 0; q < 20; ++q) {
            const double qx = q == 0 ? b.xmin : (q == 1 ? b.xmax : b.xmin + gmmrrt_rng_uniform(&rng) * 14.0);
            const double qy = q == 0 ? b.ymin : (q == 1 ? b.ymax : b.ymin + gmmrrt_rng_uniform(&rng) * 10.0);
            double d2;
            const int32_t lin = linear_nearest(i + 1, qx, qy, &d2);
            const int32_t idx = gmmrrt_nn_nearest(&nn, &pool, qx, qy);
            assert_true(idx >= 0);
            const double gd2 = (xy[idx].x - qx) * (xy[idx].x - qx) + (xy[idx].y - qy) * (xy[idx].y - qy);
            assert_true(gd2 == d2); /* same distance (ties may pick another index) */
            (void)lin;
            const double r = 0.05 + gmmrrt_rng_uniform(&rng) * 1.5;
            const int32_t n = gmmrrt_nn_near(&nn, &pool, qx, qy, r, got, N);
            assert_true(n >= 0);
            int32_t m = 0;
            for (int32_t k = 0; k <= i; ++k)
                if ((xy[k].x - qx) * (xy[k].x - qx) + (xy[k].y - qy) * (xy[k].y - qy) <= r * r)
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
        xy[i].x = 0.5 + 0.001 * i;
        xy[i].y = 0.5;
        gmmrrt_nn_insert(&nn, &pool, i);
    }
    int32_t out[4];
    assert_int_equal(gmmrrt_nn_near(&nn, &pool, 0.5, 0.5, 0.1, out, 4), -1);
    assert_int_equal(gmmrrt_nn_near(&nn, &pool, 0.5, 0.5, 0.0025, out, 4), 3);
}

/* gmmrrt_nn_nearest_k's contract against a linear scan over nodes 0..n-1, with M the nodes
 * within max_d: the true nearest first; the rest distinct and within max_d; when M >= k, at
 * least k of them (exactly k when more than kmax) forming a disc (every node left out is at
 * least as far as every node returned); when M < k, all M (the nearest alone when M = 0);
 * and the distances it reports are the true ones. */
static void near_k_against_scan(const gmmrrt_nn_t *nn, int32_t n, double qx, double qy, int32_t k, int32_t kmax,
                                double max_d)
{
    static int32_t buf[2048];
    static double buf_d2[2048];
    static unsigned char in_set[N];
    const int32_t got = gmmrrt_nn_nearest_k(nn, &pool, qx, qy, k, kmax, max_d, buf, buf_d2, 2048);
    int32_t m = 0;
    double true_min = INFINITY;
    for (int32_t i = 0; i < n; ++i) {
        const double dx = xy[i].x - qx, dy = xy[i].y - qy;
        m += dx * dx + dy * dy <= max_d * max_d;
        true_min = fmin(true_min, dx * dx + dy * dy);
    }
    assert_true(got >= 1);
    assert_true(buf_d2[0] == true_min);
    if (m >= k)
        assert_true((got >= k && got <= kmax) || got == k);
    else
        assert_int_equal(got, m > 0 ? m : 1);
    memset(in_set, 0, sizeof in_set);
    double max_in = -1.0;
    for (int32_t i = 0; i < got; ++i) {
        assert_true(buf[i] >= 0 && buf[i] < n);
        assert_false(in_set[buf[i]]); /* distinct */
        in_set[buf[i]] = 1;
        const double dx = xy[buf[i]].x - qx, dy = xy[buf[i]].y - qy;
        assert_true(buf_d2[i] == dx * dx + dy * dy);
        if (i > 0)
            assert_true(buf_d2[i] <= max_d * max_d);
        if (buf_d2[i] > max_in)
            max_in = buf_d2[i];
    }
    for (int32_t i = 0; i < n; ++i) {
        if (in_set[i])
            continue;
        const double dx = xy[i].x - qx, dy = xy[i].y - qy;
        assert_true(dx * dx + dy * dy >= max_in); /* nothing nearer was left out */
    }
}

static void test_nearest_k_matches_linear_scan(void **state)
{
    (void)state;
    for (int clustered = 0; clustered < 2; ++clustered) {
        gmmrrt_rng_t rng;
        gmmrrt_rng_seed(&rng, 11u + (uint64_t)clustered);
        const gmmrrt_bounds_t b = {-7.0, -5.0, 7.0, 5.0};
        gmmrrt_nn_t nn = {.heads = heads, .capacity = N};
        gmmrrt_nn_reset_adaptive(&nn, &b);
        for (int32_t i = 0; i < N; ++i) {
            const int blob = clustered && i % 10 != 0;
            xy[i].x = blob ? 1.0 + 0.05 * gmmrrt_rng_normal(&rng) : b.xmin + gmmrrt_rng_uniform(&rng) * 14.0;
            xy[i].y = blob ? -2.0 + 0.05 * gmmrrt_rng_normal(&rng) : b.ymin + gmmrrt_rng_uniform(&rng) * 10.0;
            gmmrrt_nn_insert(&nn, &pool, i);
            if (i != 0 && i != 5 && i % 499 != 0 && i != N - 1)
                continue;
            for (int q = 0; q < 25; ++q) {
                const double qx = q == 0 ? b.xmin : (q == 1 ? b.xmax + 3.0 : b.xmin + gmmrrt_rng_uniform(&rng) * 14.0);
                const double qy = q == 0 ? b.ymin : (q == 1 ? b.ymax : b.ymin + gmmrrt_rng_uniform(&rng) * 10.0);
                near_k_against_scan(&nn, i + 1, qx, qy, 1, 1, 100.0);
                near_k_against_scan(&nn, i + 1, qx, qy, 40, 256, 100.0);
                near_k_against_scan(&nn, i + 1, qx, qy, 40, 40, 100.0);     /* exactly k */
                near_k_against_scan(&nn, i + 1, qx, qy, 40, 256, 0.3);      /* cut to 0.3 m */
                near_k_against_scan(&nn, i + 1, qx, qy, 40, 40, 0.05);      /* often the nearest alone */
                near_k_against_scan(&nn, i + 1, 1.0, -2.0, 200, 256, 100.0); /* inside the blob */
                near_k_against_scan(&nn, i + 1, 1.0, -2.0, 200, 256, 0.02);
            }
        }
    }
    /* Bad arguments return 0. */
    gmmrrt_nn_t nn = {.heads = heads, .capacity = N};
    const gmmrrt_bounds_t b = {0.0, 0.0, 1.0, 1.0};
    gmmrrt_nn_reset_adaptive(&nn, &b);
    int32_t buf[8];
    double d2[8];
    assert_int_equal(gmmrrt_nn_nearest_k(&nn, &pool, 0.5, 0.5, 0, 4, 1.0, buf, d2, 8), 0);
    assert_int_equal(gmmrrt_nn_nearest_k(&nn, &pool, 0.5, 0.5, 4, 3, 1.0, buf, d2, 8), 0);
    assert_int_equal(gmmrrt_nn_nearest_k(&nn, &pool, 0.5, 0.5, 4, 5, 1.0, buf, d2, 8), 0); /* cap < 2 kmax */
    assert_int_equal(gmmrrt_nn_nearest_k(&nn, &pool, 0.5, 0.5, 4, 4, 0.0, buf, d2, 8), 0); /* max_d <= 0 */
}

/* The sorted re-layout renumbers nodes and rewrites every tree link and reference: the tree
 * read through the new numbers is the same tree (each node keeps its position, cost, parent
 * and children), each bucket's nodes are one run of the pool, and queries still agree with
 * a linear scan. */
static void test_sorted_relayout_keeps_the_tree(void **state)
{
    (void)state;
    enum { M = 3000 };
    static gmmrrt_xy_t old_xy[M];
    static double old_cost[M];
    static int32_t old_parent[M], old_children[M];
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, 21u);
    const gmmrrt_bounds_t b = {-7.0, -5.0, 7.0, 5.0};
    gmmrrt_nn_t nn = {.heads = heads, .capacity = N};
    gmmrrt_nn_reset_adaptive(&nn, &b);
    for (int32_t i = 0; i < M; ++i) { /* a random tree: each node's parent an earlier node */
        xy[i].x = b.xmin + gmmrrt_rng_uniform(&rng) * 14.0;
        xy[i].y = b.ymin + gmmrrt_rng_uniform(&rng) * 10.0;
        links[i].first_child = -1;
        links[i].parent = i == 0 ? -1 : (int32_t)(gmmrrt_rng_uniform(&rng) * (double)i);
        links[i].next_sibling = -1;
        if (i > 0) {
            links[i].next_sibling = links[links[i].parent].first_child;
            links[links[i].parent].first_child = i;
        }
        cost[i] = i == 0 ? 0.0 : cost[links[i].parent] + 1.0 + (double)i;
        gmmrrt_nn_insert(&nn, &pool, i);
    }
    for (int32_t i = 0; i < M; ++i) {
        old_xy[i] = xy[i];
        old_cost[i] = cost[i];
        old_parent[i] = links[i].parent;
        old_children[i] = 0;
    }
    for (int32_t i = 1; i < M; ++i)
        ++old_children[old_parent[i]];
    int32_t refs[4] = {0, M - 1, -1, 1234};
    gmmrrt_nn_relayout_sorted(&nn, &pool, M, refs, 4);
    /* Old index of each new node: the one with the same (unique) cost. */
    static int32_t old_of[M];
    for (int32_t i = 0; i < M; ++i) {
        const int32_t o = cost[i] == 0.0 ? 0 : (int32_t)(cost[i] - cost[links[i].parent] - 1.0);
        assert_true(o >= 0 && o < M);
        old_of[i] = o;
        assert_true(xy[i].x == old_xy[o].x && xy[i].y == old_xy[o].y);
        assert_true(cost[i] == old_cost[o]);
    }
    int32_t children_seen = 0;
    for (int32_t i = 0; i < M; ++i) {
        const int32_t o = old_of[i];
        if (links[i].parent < 0)
            assert_int_equal(old_parent[o], -1);
        else
            assert_int_equal(old_of[links[i].parent], old_parent[o]);
        int32_t nch = 0;
        for (int32_t c = links[i].first_child; c >= 0; c = links[c].next_sibling) {
            assert_int_equal(links[c].parent, i);
            ++nch;
        }
        assert_int_equal(nch, old_children[o]);
        children_seen += nch;
    }
    assert_int_equal(children_seen, M - 1);
    assert_int_equal(old_of[refs[0]], 0);
    assert_int_equal(old_of[refs[1]], M - 1);
    assert_int_equal(refs[2], -1);
    assert_int_equal(old_of[refs[3]], 1234);
    /* The root keeps index 0; each bucket's list is one run of consecutive indices (after
     * the root in its bucket). */
    assert_int_equal(old_of[0], 0);
    assert_int_equal(links[0].parent, -1);
    for (int32_t c = 0; c < nn.nx * nn.ny; ++c)
        for (int32_t i = nn.heads[c]; i >= 0 && next_in_bucket[i] >= 0; i = next_in_bucket[i])
            if (i != 0)
                assert_int_equal(next_in_bucket[i], i + 1);
    for (int q = 0; q < 50; ++q) {
        const double qx = b.xmin + gmmrrt_rng_uniform(&rng) * 14.0, qy = b.ymin + gmmrrt_rng_uniform(&rng) * 10.0;
        double d2;
        (void)linear_nearest(M, qx, qy, &d2);
        const int32_t idx = gmmrrt_nn_nearest(&nn, &pool, qx, qy);
        assert_true((xy[idx].x - qx) * (xy[idx].x - qx) + (xy[idx].y - qy) * (xy[idx].y - qy) == d2);
        near_k_against_scan(&nn, M, qx, qy, 30, 256, 100.0);
        near_k_against_scan(&nn, M, qx, qy, 30, 256, 0.4);
    }
    /* Inserting after a sorted re-layout keeps working. */
    xy[M].x = 0.25;
    xy[M].y = 0.25;
    gmmrrt_nn_insert(&nn, &pool, M);
    assert_int_equal(gmmrrt_nn_nearest(&nn, &pool, 0.25, 0.25), M);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nearest_and_near_match_linear_scan_uniform),
        cmocka_unit_test(test_nearest_and_near_match_linear_scan_clustered),
        cmocka_unit_test(test_adaptive_layout_matches_linear_scan),
        cmocka_unit_test(test_near_reports_overflow),
        cmocka_unit_test(test_nearest_k_matches_linear_scan),
        cmocka_unit_test(test_sorted_relayout_keeps_the_tree),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
