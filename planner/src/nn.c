/*
 * nn.c - uniform bucket grid for nearest and radius queries over the tree (see nn.h).
 * Nearest grows square rings of buckets around the query's bucket until the ring is
 * farther than the best distance found; k-nearest (k-nearest RRT*, Karaman & Frazzoli 2011)
 * grows a box of rings the same way; radius queries visit the buckets overlapping the query
 * disc. Every query scans each bucket as its list, then its run (nn.h): the order nodes
 * are reported in, on which the planner's trees depend.
 */
#include "nn.h"

#include <math.h>

/* Adaptive layout: nodes per bucket right after a re-layout, and the first layout's count. */
#ifndef GMMRRT_NN_NODES_PER_CELL
#define GMMRRT_NN_NODES_PER_CELL 1.5
#endif
#define GMMRRT_NN_FIRST_LAYOUT 16
/* Sorted re-layouts happen each time the tree grows by 1/GMMRRT_NN_SORTED_GROWTH_DIV. */
#ifndef GMMRRT_NN_SORTED_GROWTH_DIV
#define GMMRRT_NN_SORTED_GROWTH_DIV 4
#endif

int32_t gmmrrt_nn_capacity(int32_t max_nodes)
{
    return max_nodes < 16 ? 16 : max_nodes;
}

/* Lays a grid of buckets of edge >= cell over bounds, within nn->capacity buckets, every
 * head set to fill (-1: empty lists; 0: zero counts for a sort). */
static void layout(gmmrrt_nn_t *nn, const gmmrrt_bounds_t *bounds, double cell, int32_t fill)
{
    const double w = bounds->xmax - bounds->xmin, h = bounds->ymax - bounds->ymin;
    int32_t nx, ny;
    for (;;) {
        const double fx = ceil(w / cell), fy = ceil(h / cell);
        if (fx * fy <= (double)nn->capacity) {
            nx = fx < 1.0 ? 1 : (int32_t)fx;
            ny = fy < 1.0 ? 1 : (int32_t)fy;
            break;
        }
        cell *= 1.05;
    }
    nn->nx = nx;
    nn->ny = ny;
    nn->x0 = bounds->xmin;
    nn->y0 = bounds->ymin;
    nn->cell_m = cell;
    nn->sorted_end = 1; /* no runs: every bucket a plain list */
    for (int32_t i = 0; i < nx * ny; ++i)
        nn->heads[i] = fill;
}

void gmmrrt_nn_reset(gmmrrt_nn_t *nn, const gmmrrt_bounds_t *bounds, double min_cell_m)
{
    const double w = bounds->xmax - bounds->xmin, h = bounds->ymax - bounds->ymin;
    double cell = sqrt(w * h / (double)nn->capacity);
    if (cell < min_cell_m)
        cell = min_cell_m;
    nn->adaptive = 0;
    nn->relayout_at = 0;
    nn->bounds = *bounds;
    layout(nn, bounds, cell, -1);
}

/* Bucket edge for n nodes at GMMRRT_NN_NODES_PER_CELL per bucket. */
static double cell_for(const gmmrrt_bounds_t *b, int32_t n)
{
    const double area = (b->xmax - b->xmin) * (b->ymax - b->ymin);
    const double cell = sqrt(area * GMMRRT_NN_NODES_PER_CELL / (double)n);
    return cell > 0.0 ? cell : 1.0; /* degenerate bounds: one row or column of buckets */
}

void gmmrrt_nn_reset_adaptive(gmmrrt_nn_t *nn, const gmmrrt_bounds_t *bounds)
{
    nn->adaptive = 1;
    nn->relayout_at = GMMRRT_NN_FIRST_LAYOUT;
    nn->bounds = *bounds;
    layout(nn, bounds, cell_for(bounds, GMMRRT_NN_FIRST_LAYOUT), -1);
}

static int32_t clampi(int32_t v, int32_t lo, int32_t hi) { return v < lo ? lo : (v > hi ? hi : v); }

static int32_t cell_of(double v, double v0, double cell, int32_t n)
{
    const double f = floor((v - v0) / cell);
    if (!(f >= 0.0))
        return 0;
    if (f >= (double)n)
        return n - 1;
    return (int32_t)f;
}

static void link(gmmrrt_nn_t *nn, gmmrrt_pool_t *pool, int32_t idx)
{
    const int32_t i = cell_of(pool->xy[idx].x, nn->x0, nn->cell_m, nn->nx);
    const int32_t j = cell_of(pool->xy[idx].y, nn->y0, nn->cell_m, nn->ny);
    int32_t *head = &nn->heads[j * nn->nx + i];
    pool->next_in_bucket[idx] = *head;
    *head = idx;
}

int gmmrrt_nn_relayout_due(const gmmrrt_nn_t *nn, int32_t n_next)
{
    return nn->adaptive && n_next >= nn->relayout_at;
}

static int32_t bucket_of(const gmmrrt_nn_t *nn, const gmmrrt_xy_t *node)
{
    return cell_of(node->y, nn->y0, nn->cell_m, nn->ny) * nn->nx + cell_of(node->x, nn->x0, nn->cell_m, nn->nx);
}

static int32_t renumbered(const gmmrrt_pool_t *pool, int32_t i) { return i < 0 ? i : pool->next_in_bucket[i]; }

void gmmrrt_nn_relayout_sorted(gmmrrt_nn_t *nn, gmmrrt_pool_t *pool, int32_t n, int32_t *refs, int32_t n_refs)
{
    nn->relayout_at = n > INT32_MAX / 2 ? INT32_MAX : n + n / GMMRRT_NN_SORTED_GROWTH_DIV + 1;
    /* Counting sort by bucket: heads[] counts, then running start offsets; each node's new
     * index goes to its next_in_bucket (scratch until the lists are rebuilt). The bucket edge
     * follows where the nodes are: when they crowd part of the bounds (informed or mixture
     * sampling), the mean bucket load seen from a node, sum(count^2) / n (1 + lambda for
     * Poisson buckets of mean lambda), says how much smaller buckets must be to hold
     * GMMRRT_NN_NODES_PER_CELL there; the capacity limits it (layout). */
    double cell = cell_for(&nn->bounds, n < 1 ? 1 : n);
    int32_t cells = 0;
    for (int pass = 0; pass < 2; ++pass) {
        layout(nn, &nn->bounds, cell, 0);
        cells = nn->nx * nn->ny;
        for (int32_t i = 1; i < n; ++i)
            ++nn->heads[bucket_of(nn, &pool->xy[i])];
        if (pass > 0 || n < GMMRRT_NN_FIRST_LAYOUT)
            break; /* (n - 1 >= 15 below) */
        double load2 = 0.0;
        for (int32_t c = 0; c < cells; ++c)
            load2 += (double)nn->heads[c] * (double)nn->heads[c];
        const double lambda = load2 / (double)(n - 1) - 1.0; /* mean load around a node */
        if (!(lambda > 2.0 * GMMRRT_NN_NODES_PER_CELL))
            break;
        cell = nn->cell_m * sqrt(GMMRRT_NN_NODES_PER_CELL / lambda);
    }
    int32_t start = 1; /* node 0, the root, keeps its index */
    for (int32_t c = 0; c < cells; ++c) {
        const int32_t count = nn->heads[c];
        nn->heads[c] = start;
        start += count;
    }
    if (n > 0)
        pool->next_in_bucket[0] = 0;
    for (int32_t i = 1; i < n; ++i)
        pool->next_in_bucket[i] = nn->heads[bucket_of(nn, &pool->xy[i])]++;
    /* Links to new indices, then the records to their places (cycles of the permutation). */
    for (int32_t i = 0; i < n; ++i) {
        pool->link[i].parent = renumbered(pool, pool->link[i].parent);
        pool->link[i].first_child = renumbered(pool, pool->link[i].first_child);
        pool->link[i].next_sibling = renumbered(pool, pool->link[i].next_sibling);
    }
    for (int32_t r = 0; r < n_refs; ++r)
        refs[r] = renumbered(pool, refs[r]);
    for (int32_t i = 1; i < n; ++i) {
        while (pool->next_in_bucket[i] != i) {
            const int32_t to = pool->next_in_bucket[i];
            const gmmrrt_xy_t txy = pool->xy[to];
            const double tcost = pool->cost[to];
            const gmmrrt_links_t tlink = pool->link[to];
            const int32_t tnext = pool->next_in_bucket[to];
            pool->xy[to] = pool->xy[i];
            pool->cost[to] = pool->cost[i];
            pool->link[to] = pool->link[i];
            pool->next_in_bucket[to] = to;
            pool->xy[i] = txy;
            pool->cost[i] = tcost;
            pool->link[i] = tlink;
            pool->next_in_bucket[i] = tnext;
        }
    }
    /* Each bucket's nodes are now one run of the pool, [end of the bucket before, heads[c])
     * (heads[] holds each bucket's end after the numbering above): heads[] to run starts
     * (-1 when empty), and every node of a run holds the run's end (one pass over the
     * buckets, fewer than nodes or many more when the nodes crowd). */
    int32_t prev_end = 1;
    for (int32_t c = 0; c < cells; ++c) {
        const int32_t run_end = nn->heads[c], run_start = prev_end;
        prev_end = run_end;
        if (run_start < run_end) {
            nn->heads[c] = run_start;
            for (int32_t i = run_start; i < run_end; ++i)
                pool->next_in_bucket[i] = run_end;
        } else {
            nn->heads[c] = -1;
        }
    }
    nn->sorted_end = n > 1 ? n : 1;
    if (n > 0)
        link(nn, pool, 0); /* the root is its bucket's list, ahead of the run */
}

/* Scans bucket c's nodes in the index's order (list, then run; nn.h), running the
 * statement after n (the visit) with the node index in variable n. */
#define GMMRRT_NN_FOR_BUCKET(nn, pool, c, n, ...)                                    \
    do {                                                                               \
        int32_t n = (nn)->heads[c];                                                    \
        while (n == 0 || n >= (nn)->sorted_end) {                                      \
            __VA_ARGS__;                                                               \
            n = (pool)->next_in_bucket[n];                                             \
        }                                                                              \
        if (n > 0)                                                                     \
            for (const int32_t run_end_ = (pool)->next_in_bucket[n]; n < run_end_; ++n) \
                __VA_ARGS__;                                                           \
    } while (0)

void gmmrrt_nn_insert(gmmrrt_nn_t *nn, gmmrrt_pool_t *pool, int32_t idx)
{
    if (nn->adaptive && idx + 1 >= nn->relayout_at) {
        const int32_t n = idx + 1;
        layout(nn, &nn->bounds, cell_for(&nn->bounds, n), -1);
        for (int32_t k = 0; k <= idx; ++k)
            link(nn, pool, k);
        nn->relayout_at = n > INT32_MAX / 2 ? INT32_MAX : 2 * n;
        return;
    }
    link(nn, pool, idx);
}

static void scan_bucket(const gmmrrt_nn_t *nn, const gmmrrt_pool_t *pool, int32_t i, int32_t j, double x,
                        double y, int32_t *best, double *best_d2)
{
    GMMRRT_NN_FOR_BUCKET(nn, pool, j * nn->nx + i, n, {
        const double dx = pool->xy[n].x - x, dy = pool->xy[n].y - y;
        const double d2 = dx * dx + dy * dy;
        if (d2 < *best_d2) {
            *best_d2 = d2;
            *best = n;
        }
    });
}

/* Distance from (x, y) to the nearest side of the bucket box [i0, i1] x [j0, j1] that is not
 * on the grid's edge (INFINITY when all are): every node outside the box is at least that
 * far, since nodes beyond the grid are clamped into its edge buckets. */
static double box_reach(const gmmrrt_nn_t *nn, double x, double y, int32_t i0, int32_t i1, int32_t j0, int32_t j1)
{
    double reach = INFINITY;
    if (i0 > 0)
        reach = fmin(reach, x - (nn->x0 + (double)i0 * nn->cell_m));
    if (i1 < nn->nx - 1)
        reach = fmin(reach, nn->x0 + (double)(i1 + 1) * nn->cell_m - x);
    if (j0 > 0)
        reach = fmin(reach, y - (nn->y0 + (double)j0 * nn->cell_m));
    if (j1 < nn->ny - 1)
        reach = fmin(reach, nn->y0 + (double)(j1 + 1) * nn->cell_m - y);
    return reach;
}

int32_t gmmrrt_nn_nearest(const gmmrrt_nn_t *nn, const gmmrrt_pool_t *pool, double x, double y)
{
    const int32_t ci = cell_of(x, nn->x0, nn->cell_m, nn->nx);
    const int32_t cj = cell_of(y, nn->y0, nn->cell_m, nn->ny);
    int32_t best = -1;
    double best_d2 = INFINITY;
    const int32_t max_ring = nn->nx > nn->ny ? nn->nx : nn->ny;
    for (int32_t k = 0; k <= max_ring; ++k) {
        const int32_t i0 = ci - k, i1 = ci + k, j0 = cj - k, j1 = cj + k;
        for (int32_t j = j0; j <= j1; ++j) {
            if (j < 0 || j >= nn->ny)
                continue;
            const int edge_row = (j == j0 || j == j1);
            for (int32_t i = i0; i <= i1; i += (edge_row ? 1 : (i1 - i0 > 0 ? i1 - i0 : 1))) {
                if (i >= 0 && i < nn->nx)
                    scan_bucket(nn, pool, i, j, x, y, &best, &best_d2);
            }
        }
        /* Every node not yet scanned lies outside the box of rings 0..k; on a side where
         * that box has reached the grid's edge there is none. */
        if (best >= 0) {
            const double reach = box_reach(nn, x, y, i0, i1, j0, j1);
            if (reach >= 0.0 && best_d2 <= reach * reach)
                break;
            if (i0 <= 0 && i1 >= nn->nx - 1 && j0 <= 0 && j1 >= nn->ny - 1)
                break;
        }
    }
    return best;
}

static void swap_entry(int32_t *idx, double *d2, int32_t i, int32_t j)
{
    const int32_t ti = idx[i];
    const double td = d2[i];
    idx[i] = idx[j];
    d2[i] = d2[j];
    idx[j] = ti;
    d2[j] = td;
}

/* Quickselect (median-of-three pivots, no randomness): afterwards entries [0, k) of (idx, d2)
 * hold the k smallest d2 of [0, n), in no set order. */
static void select_k(int32_t *idx, double *d2, int32_t n, int32_t k)
{
    int32_t lo = 0, hi = n - 1;
    while (hi > lo) {
        const int32_t mid = lo + (hi - lo) / 2;
        if (d2[mid] < d2[lo])
            swap_entry(idx, d2, mid, lo);
        if (d2[hi] < d2[lo])
            swap_entry(idx, d2, hi, lo);
        if (d2[hi] < d2[mid])
            swap_entry(idx, d2, hi, mid);
        const double pivot = d2[mid];
        int32_t i = lo, j = hi;
        while (i <= j) {
            while (d2[i] < pivot)
                ++i;
            while (d2[j] > pivot)
                --j;
            if (i <= j)
                swap_entry(idx, d2, i++, j--);
        }
        /* [lo, j] <= pivot <= [i, hi] */
        if (k - 1 <= j)
            hi = j;
        else if (k - 1 >= i)
            lo = i;
        else
            return;
    }
}

/* Number of d2[0..n) within lim2 (four sums: no chain of dependent additions). */
static int32_t count_within(const double *d2, int32_t n, double lim2)
{
    int32_t s0 = 0, s1 = 0, s2 = 0, s3 = 0, c = 0;
    for (; c + 4 <= n; c += 4) {
        s0 += d2[c] <= lim2;
        s1 += d2[c + 1] <= lim2;
        s2 += d2[c + 2] <= lim2;
        s3 += d2[c + 3] <= lim2;
    }
    for (; c < n; ++c)
        s0 += d2[c] <= lim2;
    return s0 + s1 + s2 + s3;
}

/* Index of the smallest of d2[0..n), n >= 1 (of equal ones the first): the even and the odd
 * entries are two independent minimum chains, merged at the end. */
static int32_t first_min(const double *d2, int32_t n)
{
    int32_t i0 = 0, i1 = n > 1 ? 1 : 0;
    double m0 = d2[0], m1 = d2[i1];
    int32_t c = 2;
    for (; c + 2 <= n; c += 2) {
        i0 = d2[c] < m0 ? c : i0;
        m0 = d2[c] < m0 ? d2[c] : m0;
        i1 = d2[c + 1] < m1 ? c + 1 : i1;
        m1 = d2[c + 1] < m1 ? d2[c + 1] : m1;
    }
    if (c < n) {
        i0 = d2[c] < m0 ? c : i0;
        m0 = d2[c] < m0 ? d2[c] : m0;
    }
    return (m1 < m0 || (m1 == m0 && i1 < i0)) ? i1 : i0;
}

/* Keeps the k nearest of the c entries of a full buffer (nothing farther can be in the
 * answer); returns the new count, k. */
static int32_t trim_to_k(int32_t *buf, double *buf_d2, int32_t c, int32_t k, int *trimmed)
{
    select_k(buf, buf_d2, c, k);
    *trimmed = 1;
    return k;
}

/* Appends the nodes of buckets [a, b] of row j to (buf, buf_d2) in the index's order (each
 * bucket's list, then its run; nn.h); when the buffer is full, keeps only its k nearest and
 * goes on. The runs of consecutive buckets are consecutive in the pool, so the runs of the
 * buckets between two list nodes are one plain loop over a range of pool indices (no links
 * followed, no branch per node): after a sorted re-layout most buckets have no list. */
static void gather_row(const gmmrrt_nn_t *nn, const gmmrrt_pool_t *pool, int32_t j, int32_t a, int32_t b,
                       double x, double y, int32_t k, int32_t *restrict buf, double *restrict buf_d2, int32_t cap,
                       int32_t *count, int *trimmed)
{
    if (j < 0 || j >= nn->ny || a > b)
        return;
    const int32_t *heads = nn->heads + (size_t)j * (size_t)nn->nx;
    const gmmrrt_xy_t *restrict xy = pool->xy;
    const int32_t *next = pool->next_in_bucket;
    const int32_t sorted_end = nn->sorted_end;
    for (int32_t i = a; i <= b; ++i)
        if (heads[i] >= 0) {
            __builtin_prefetch(&xy[heads[i]]);
            __builtin_prefetch(&next[heads[i]]);
        }
    int32_t c = *count;
    for (int32_t i = a; i <= b; ++i) {
        int32_t n = heads[i];
        while (n == 0 || n >= sorted_end) { /* the list */
            if (c == cap)
                c = trim_to_k(buf, buf_d2, c, k, trimmed);
            const double dx = xy[n].x - x, dy = xy[n].y - y;
            buf[c] = n;
            buf_d2[c++] = dx * dx + dy * dy;
            n = next[n];
        }
        if (n < 0)
            continue;
        /* A run from n: it goes on through the next buckets as long as they have no list. */
        int32_t last_start = n;
        while (i < b) {
            const int32_t h = heads[i + 1];
            if (h == 0 || h >= sorted_end)
                break;
            if (h > 0)
                last_start = h;
            ++i;
        }
        const int32_t end = next[last_start];
        while (n < end) {
            if (c == cap)
                c = trim_to_k(buf, buf_d2, c, k, trimmed);
            const int32_t stop = end - n < cap - c ? end : n + (cap - c);
            for (; n < stop; ++n) {
                const double dx = xy[n].x - x, dy = xy[n].y - y;
                buf[c] = n;
                buf_d2[c++] = dx * dx + dy * dy;
            }
        }
    }
    *count = c;
}

int32_t gmmrrt_nn_nearest_k(const gmmrrt_nn_t *nn, const gmmrrt_pool_t *pool, double x, double y, int32_t k,
                            int32_t kmax, double max_d, int32_t *buf, double *buf_d2, int32_t cap)
{
    if (k <= 0 || kmax < k || cap < 2 * kmax || !(max_d > 0.0))
        return 0;
    const double max_d2 = max_d * max_d;
    const int32_t ci = cell_of(x, nn->x0, nn->cell_m, nn->nx);
    const int32_t cj = cell_of(y, nn->y0, nn->cell_m, nn->ny);
    int32_t count = 0;
    int trimmed = 0; /* the buffer overflowed: it holds the k nearest so far, not a disc */
    /* First a box of rings 0..r0 that holds about k nodes at the layout's bucket load, row
     * by row (each row a contiguous run of buckets); then one ring more at a time. */
    int32_t r = (int32_t)floor(sqrt((double)k / (M_PI * GMMRRT_NN_NODES_PER_CELL)));
    for (int32_t j = cj - r; j <= cj + r; ++j)
        gather_row(nn, pool, j, clampi(ci - r, 0, nn->nx - 1), clampi(ci + r, 0, nn->nx - 1), x, y, k, buf,
                     buf_d2, cap, &count, &trimmed);
    const int32_t max_ring = nn->nx > nn->ny ? nn->nx : nn->ny;
    for (;;) {
        const int32_t i0 = ci - r, i1 = ci + r, j0 = cj - r, j1 = cj + r;
        if ((i0 <= 0 && i1 >= nn->nx - 1 && j0 <= 0 && j1 >= nn->ny - 1) || r > max_ring)
            break; /* the whole grid is scanned */
        if (count >= k) {
            /* Every node not yet scanned lies outside the box of rings 0..r, farther than
             * reach: done when k of those found are within it. */
            const double reach = box_reach(nn, x, y, i0, i1, j0, j1);
            if (reach >= 0.0) {
                const double reach2 = reach * reach;
                const int32_t within = count_within(buf_d2, count, reach2);
                if (within >= k && trimmed)
                    break; /* the k nearest are in the buffer: selected below */
                if (within >= k || (within > 0 && reach2 >= max_d2)) {
                    /* The answer: every node within reach and max_d (all of them are nearer
                     * than any node outside), or the nearest alone when none is within max_d.
                     * Compacted in scan order without branches; then the nearest kept goes
                     * first, or, when none is kept, the nearest of all alone (first_min: of
                     * equally near nodes the first found). */
                    const double lim2 = reach2 < max_d2 ? reach2 : max_d2;
                    const int32_t first = buf[0];
                    const double first_d2 = buf_d2[0];
                    int32_t w = 0;
                    for (int32_t c = 0; c < count; ++c) {
                        const double d2 = buf_d2[c];
                        buf[w] = buf[c];
                        buf_d2[w] = d2;
                        w += d2 <= lim2;
                    }
                    if (w == 0) { /* none within max_d: the nearest alone (only entry 0 was written) */
                        buf[0] = first;
                        buf_d2[0] = first_d2;
                        const int32_t nearest = first_min(buf_d2, count);
                        buf[0] = buf[nearest];
                        buf_d2[0] = buf_d2[nearest];
                        return 1;
                    }
                    count = w;
                    if (count > kmax)
                        break; /* too many: the k nearest, selected below */
                    const int32_t best = first_min(buf_d2, count);
                    if (best != 0)
                        swap_entry(buf, buf_d2, 0, best);
                    return count;
                }
            }
        }
        ++r; /* the next ring: its top and bottom rows, then its side columns */
        const int32_t a = clampi(ci - r, 0, nn->nx - 1), b = clampi(ci + r, 0, nn->nx - 1);
        gather_row(nn, pool, cj - r, a, b, x, y, k, buf, buf_d2, cap, &count, &trimmed);
        gather_row(nn, pool, cj + r, a, b, x, y, k, buf, buf_d2, cap, &count, &trimmed);
        for (int32_t j = cj - r + 1; j <= cj + r - 1; ++j) {
            if (ci - r >= 0)
                gather_row(nn, pool, j, ci - r, ci - r, x, y, k, buf, buf_d2, cap, &count, &trimmed);
            if (ci + r < nn->nx)
                gather_row(nn, pool, j, ci + r, ci + r, x, y, k, buf, buf_d2, cap, &count, &trimmed);
        }
    }
    if (count > kmax || (trimmed && count > k)) {
        select_k(buf, buf_d2, count, k);
        count = k;
    }
    /* Here the whole grid was scanned, or the k nearest were selected: the nearest first
     * (of equally near nodes the first found), then drop those beyond max_d but it. */
    {
        int32_t w = 0, best = 0;
        for (int32_t c = 0; c < count; ++c)
            best = buf_d2[c] < buf_d2[best] ? c : best;
        if (count > 0)
            swap_entry(buf, buf_d2, 0, best);
        for (int32_t c = 0; c < count; ++c) {
            const int32_t keep = c == 0 || buf_d2[c] <= max_d2;
            buf[w] = buf[c];
            buf_d2[w] = buf_d2[c];
            w += keep;
        }
        count = w;
    }
    return count;
}

int32_t gmmrrt_nn_near(const gmmrrt_nn_t *nn, const gmmrrt_pool_t *pool, double x, double y,
                       double radius_m, int32_t *out, int32_t cap)
{
    const int32_t i0 = clampi((int32_t)floor((x - radius_m - nn->x0) / nn->cell_m), 0, nn->nx - 1);
    const int32_t i1 = clampi((int32_t)floor((x + radius_m - nn->x0) / nn->cell_m), 0, nn->nx - 1);
    const int32_t j0 = clampi((int32_t)floor((y - radius_m - nn->y0) / nn->cell_m), 0, nn->ny - 1);
    const int32_t j1 = clampi((int32_t)floor((y + radius_m - nn->y0) / nn->cell_m), 0, nn->ny - 1);
    const double r2 = radius_m * radius_m;
    int32_t count = 0;
    for (int32_t j = j0; j <= j1; ++j) {
        /* Only the buckets of this row that the disc's chord over the row reaches. */
        const double row_lo = nn->y0 + (double)j * nn->cell_m, row_hi = row_lo + nn->cell_m;
        const double dy = y < row_lo ? row_lo - y : (y > row_hi ? y - row_hi : 0.0);
        int32_t a = i0, b = i1;
        if (dy > 0.0 && j > 0 && j < nn->ny - 1) { /* edge rows also hold clamped nodes */
            if (dy > radius_m)
                continue;
            const double half = sqrt(r2 - dy * dy);
            a = clampi((int32_t)floor((x - half - nn->x0) / nn->cell_m), i0, i1);
            b = clampi((int32_t)floor((x + half - nn->x0) / nn->cell_m), i0, i1);
        }
        for (int32_t i = a; i <= b; ++i)
            GMMRRT_NN_FOR_BUCKET(nn, pool, j * nn->nx + i, n, {
                const double dx = pool->xy[n].x - x, ddy = pool->xy[n].y - y;
                if (dx * dx + ddy * ddy <= r2) {
                    if (count >= cap)
                        return -1;
                    out[count++] = n;
                }
            });
    }
    return count;
}
