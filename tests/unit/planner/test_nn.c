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

/* Bucket of (x, y) as nn.h defines it, computed here independently of nn.c. */
static int32_t ref_bucket(const gmmrrt_nn_t *nn, double x, double y)
{
    double fi = floor((x - nn->x0) / nn->cell_m), fj = floor((y - nn->y0) / nn->cell_m);
    fi = !(fi >= 0.0) ? 0.0 : (fi >= (double)nn->nx ? (double)(nn->nx - 1) : fi);
    fj = !(fj >= 0.0) ? 0.0 : (fj >= (double)nn->ny ? (double)(nn->ny - 1) : fj);
    return (int32_t)fj * nn->nx + (int32_t)fi;
}

/* After a sorted re-layout of n nodes: sorted_end = n, each bucket's list is at most the
 * root, and its run (the nodes of that bucket among 1..n-1) is one range of indices whose
 * every node holds the range's end; the runs follow the buckets' order and cover 1..n-1. */
static void check_runs(const gmmrrt_nn_t *nn, int32_t n)
{
    assert_int_equal(nn->sorted_end, n);
    int32_t expect_start = 1;
    for (int32_t c = 0; c < nn->nx * nn->ny; ++c) {
        int32_t h = nn->heads[c];
        if (h == 0) {
            assert_int_equal(ref_bucket(nn, xy[0].x, xy[0].y), c);
            h = next_in_bucket[0];
        }
        if (h < 0)
            continue;
        assert_int_equal(h, expect_start);
        const int32_t end = next_in_bucket[h];
        assert_true(end > h && end <= n);
        for (int32_t i = h; i < end; ++i) {
            assert_int_equal(ref_bucket(nn, xy[i].x, xy[i].y), c);
            assert_int_equal(next_in_bucket[i], end);
        }
        expect_start = end;
    }
    assert_int_equal(expect_start, n > 1 ? n : 1);
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
    /* The root keeps index 0; each bucket's nodes are one run of consecutive indices (after
     * the root in its bucket), the runs in bucket order. */
    assert_int_equal(old_of[0], 0);
    assert_int_equal(links[0].parent, -1);
    check_runs(&nn, M);
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

/* The order the index reports nodes in (nn.h), derived from positions and indices alone:
 * buckets in row-major order; in each, the nodes added since the last sorted re-layout
 * (index >= sorted_end) newest first, then the root, then the rest by index. */
static const gmmrrt_nn_t *order_nn;
static int32_t order_key(int32_t i)
{
    return i >= order_nn->sorted_end ? 0 : (i == 0 ? 1 : 2);
}
static int cmp_scan_order(const void *pa, const void *pb)
{
    const int32_t a = *(const int32_t *)pa, b = *(const int32_t *)pb;
    const int32_t ca = ref_bucket(order_nn, xy[a].x, xy[a].y), cb = ref_bucket(order_nn, xy[b].x, xy[b].y);
    if (ca != cb)
        return (ca > cb) - (ca < cb);
    const int32_t ka = order_key(a), kb = order_key(b);
    if (ka != kb)
        return (ka > kb) - (ka < kb);
    return ka == 0 ? (a < b) - (a > b) : (a > b) - (a < b);
}
static void ref_scan_order(const gmmrrt_nn_t *nn, int32_t n, int32_t *out)
{
    for (int32_t i = 0; i < n; ++i)
        out[i] = i;
    order_nn = nn;
    qsort(out, (size_t)n, sizeof out[0], cmp_scan_order);
}

/* A twin of the index over the same grid whose buckets are plain lists in the same order
 * (the layout before runs existed): every query must answer it with the same nodes in the
 * same order, which is what keeps the planner's trees the same. */
static int32_t twin_heads[N], twin_next[N];
static void make_list_twin(const gmmrrt_nn_t *nn, int32_t n, gmmrrt_nn_t *twin, gmmrrt_pool_t *twin_pool)
{
    static int32_t order[N];
    *twin = *nn;
    twin->heads = twin_heads;
    twin->sorted_end = 1; /* no runs */
    *twin_pool = pool;
    twin_pool->next_in_bucket = twin_next;
    for (int32_t c = 0; c < nn->nx * nn->ny; ++c)
        twin_heads[c] = -1;
    ref_scan_order(nn, n, order);
    for (int32_t k = n - 1; k >= 0; --k) {
        const int32_t c = ref_bucket(nn, xy[order[k]].x, xy[order[k]].y);
        twin_next[order[k]] = twin_heads[c];
        twin_heads[c] = order[k];
    }
}

/* Every query on nn (nodes 0..n-1) against its plain-list twin, result for result, and a
 * disc holding every node against the reference order. */
static void check_scan_order(const gmmrrt_nn_t *nn, int32_t n, gmmrrt_rng_t *rng, const gmmrrt_bounds_t *b)
{
    static int32_t want[N], got[N], got_twin[N];
    static double d2[2048], d2_twin[2048];
    gmmrrt_nn_t twin;
    gmmrrt_pool_t twin_pool;
    make_list_twin(nn, n, &twin, &twin_pool);
    ref_scan_order(nn, n, want);
    assert_int_equal(gmmrrt_nn_near(nn, &pool, 0.0, 0.0, 1e3, got, N), n);
    assert_memory_equal(got, want, sizeof(int32_t) * (size_t)n);
    static int32_t rank[N]; /* place in the reference order */
    for (int32_t i = 0; i < n; ++i)
        rank[want[i]] = i;
    const double w = b->xmax - b->xmin, h = b->ymax - b->ymin;
    for (int q = 0; q < 44; ++q) {
        const int at_root = q % 4 == 0; /* the root's bucket: list, root and run */
        double qx = at_root ? xy[0].x + 0.01 * gmmrrt_rng_normal(rng) : b->xmin - 0.5 + (w + 1.0) * gmmrrt_rng_uniform(rng);
        double qy = at_root ? xy[0].y + 0.01 * gmmrrt_rng_normal(rng) : b->ymin - 0.5 + (h + 1.0) * gmmrrt_rng_uniform(rng);
        if (q >= 40) { /* where several nodes share a position (the edge nodes below): ties */
            qx = q % 2 ? b->xmax : b->xmin - 1.0;
            qy = q < 42 ? b->ymax + 2.0 : b->ymin;
        }
        const int32_t nearest = gmmrrt_nn_nearest(nn, &pool, qx, qy);
        assert_int_equal(nearest, gmmrrt_nn_nearest(&twin, &twin_pool, qx, qy));
        for (int32_t i = 0; i < n; ++i) /* of nodes at the same place, the first in scan order */
            if (xy[i].x == xy[nearest].x && xy[i].y == xy[nearest].y)
                assert_true(rank[nearest] <= rank[i]);
        const double r = 0.02 + 0.6 * gmmrrt_rng_uniform(rng);
        const int32_t m = gmmrrt_nn_near(nn, &pool, qx, qy, r, got, N);
        assert_int_equal(m, gmmrrt_nn_near(&twin, &twin_pool, qx, qy, r, got_twin, N));
        assert_memory_equal(got, got_twin, sizeof(int32_t) * (size_t)(m > 0 ? m : 0));
        const int32_t ks[][3] = {{1, 1, 2048}, {30, 256, 2048}, {40, 40, 80}, {200, 256, 512}}; /* k, kmax, cap */
        for (size_t t = 0; t < sizeof ks / sizeof ks[0]; ++t) {
            const double max_d = t == 1 ? 0.3 : 100.0;
            const int32_t c1 = gmmrrt_nn_nearest_k(nn, &pool, qx, qy, ks[t][0], ks[t][1], max_d, got, d2, ks[t][2]);
            const int32_t c2 = gmmrrt_nn_nearest_k(&twin, &twin_pool, qx, qy, ks[t][0], ks[t][1], max_d, got_twin,
                                                   d2_twin, ks[t][2]);
            assert_int_equal(c1, c2);
            assert_true(c1 >= 1);
            assert_memory_equal(got, got_twin, sizeof(int32_t) * (size_t)c1);
            assert_memory_equal(d2, d2_twin, sizeof(double) * (size_t)c1);
            /* Unless the k nearest were selected (the count is then k), the first found of
             * equally near nodes comes first. */
            for (int32_t i = 1; i < c1 && c1 > ks[t][0]; ++i)
                if (xy[got[i]].x == xy[got[0]].x && xy[got[i]].y == xy[got[0]].y)
                    assert_true(rank[got[0]] < rank[got[i]]);
        }
    }
}

/* The index as the planner drives it (sorted re-layouts as the tree grows by a quarter,
 * nodes added in between go to the buckets' lists) answers every query as its plain-list
 * twin does, node for node and in the same order: right after each re-layout (runs only),
 * midway and just before the next (runs and lists), in the root's bucket, on buckets
 * clamped at the bounds' edges (nodes on and beyond them), among empty buckets, and with
 * the grid at its capacity (a clustered tree wants more buckets than it may have). Also
 * the fixed grid and the adaptive grid before any sorted re-layout (lists only). */
static void test_runs_and_lists_scan_in_the_list_order(void **state)
{
    (void)state;
    const gmmrrt_bounds_t b = {-7.0, -5.0, 7.0, 5.0};
    for (int variant = 0; variant < 4; ++variant) {
        gmmrrt_rng_t rng;
        gmmrrt_rng_seed(&rng, 31u + (uint64_t)variant);
        /* 0: uniform, fixed grid; 1: adaptive grid without sorted re-layouts (re-laid as the
         * tree doubles); 2: clustered around the root, sorted re-layouts; 3: the same with
         * capacity for 1000 buckets */
        const int sorting = variant >= 2;
        gmmrrt_nn_t nn = {.heads = heads, .capacity = variant == 3 ? 1000 : N};
        if (variant == 0)
            gmmrrt_nn_reset(&nn, &b, 0.1);
        else
            gmmrrt_nn_reset_adaptive(&nn, &b);
        const int32_t m = 4000;
        int32_t relayouts = 0, at_capacity = 0;
        for (int32_t i = 0; i < m; ++i) {
            if (sorting && i > 0 && gmmrrt_nn_relayout_due(&nn, i + 1)) {
                gmmrrt_nn_relayout_sorted(&nn, &pool, i, NULL, 0);
                check_runs(&nn, i);
                check_scan_order(&nn, i, &rng, &b); /* runs only */
                at_capacity |= nn.nx * nn.ny * 2 > nn.capacity;
                ++relayouts;
            }
            const int blob = variant >= 2 && i % 8 != 0;
            xy[i].x = blob ? 0.3 + 0.1 * gmmrrt_rng_normal(&rng) : b.xmin + gmmrrt_rng_uniform(&rng) * 14.0;
            xy[i].y = blob ? 0.2 + 0.1 * gmmrrt_rng_normal(&rng) : b.ymin + gmmrrt_rng_uniform(&rng) * 10.0;
            if (i % 97 == 5) { /* on and beyond the bounds' edges */
                xy[i].x = i % 2 ? b.xmax : b.xmin - 1.0;
                xy[i].y = i % 3 ? b.ymax + 2.0 : b.ymin;
            }
            if (i == 0) {
                xy[0].x = 0.3;
                xy[0].y = 0.2;
            }
            gmmrrt_nn_insert(&nn, &pool, i);
            /* midway between re-layouts and just before the next (runs and lists) */
            if (i + 2 == nn.relayout_at || i + 1 == m || i % 500 == 250)
                check_scan_order(&nn, i + 1, &rng, &b);
        }
        assert_true(sorting ? relayouts > 10 : relayouts == 0);
        if (variant == 3)
            assert_true(at_capacity);
    }
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
        cmocka_unit_test(test_runs_and_lists_scan_in_the_list_order),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
