/*
 * nn.c - uniform bucket grid for nearest and radius queries over the tree (see nn.h).
 * Nearest grows square rings of buckets around the query's bucket until the ring is
 * farther than the best distance found; radius queries visit the buckets overlapping
 * the query disc's bounding box.
 */
#include "nn.h"

#include <math.h>

/* Adaptive layout: nodes per bucket right after a re-layout, and the first layout's count. */
#ifndef GMMRRT_NN_NODES_PER_CELL
#define GMMRRT_NN_NODES_PER_CELL 1.0
#endif
#define GMMRRT_NN_FIRST_LAYOUT 16

int32_t gmmrrt_nn_capacity(int32_t max_nodes)
{
    return max_nodes < 16 ? 16 : max_nodes;
}

/* Lays an empty grid of buckets of edge >= cell over bounds, within nn->capacity buckets. */
static void layout(gmmrrt_nn_t *nn, const gmmrrt_bounds_t *bounds, double cell)
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
    for (int32_t i = 0; i < nx * ny; ++i)
        nn->heads[i] = -1;
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
    layout(nn, bounds, cell);
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
    layout(nn, bounds, cell_for(bounds, GMMRRT_NN_FIRST_LAYOUT));
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

static void link(gmmrrt_nn_t *nn, gmmrrt_node_t *nodes, int32_t idx)
{
    const int32_t i = cell_of(nodes[idx].x, nn->x0, nn->cell_m, nn->nx);
    const int32_t j = cell_of(nodes[idx].y, nn->y0, nn->cell_m, nn->ny);
    int32_t *head = &nn->heads[j * nn->nx + i];
    nodes[idx].next_in_bucket = *head;
    *head = idx;
}

void gmmrrt_nn_insert(gmmrrt_nn_t *nn, gmmrrt_node_t *nodes, int32_t idx)
{
    if (nn->adaptive && idx + 1 >= nn->relayout_at) {
        const int32_t n = idx + 1;
        layout(nn, &nn->bounds, cell_for(&nn->bounds, n));
        for (int32_t k = 0; k <= idx; ++k)
            link(nn, nodes, k);
        nn->relayout_at = n > INT32_MAX / 2 ? INT32_MAX : 2 * n;
        return;
    }
    link(nn, nodes, idx);
}

static void scan_bucket(const gmmrrt_nn_t *nn, const gmmrrt_node_t *nodes, int32_t i, int32_t j, double x,
                        double y, int32_t *best, double *best_d2)
{
    for (int32_t n = nn->heads[j * nn->nx + i]; n >= 0; n = nodes[n].next_in_bucket) {
        const double dx = nodes[n].x - x, dy = nodes[n].y - y;
        const double d2 = dx * dx + dy * dy;
        if (d2 < *best_d2) {
            *best_d2 = d2;
            *best = n;
        }
    }
}

int32_t gmmrrt_nn_nearest(const gmmrrt_nn_t *nn, const gmmrrt_node_t *nodes, double x, double y)
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
                    scan_bucket(nn, nodes, i, j, x, y, &best, &best_d2);
            }
        }
        /* Every node not yet scanned lies outside the box of rings 0..k; on a side where
         * that box has reached the grid's edge there is none. */
        if (best >= 0) {
            double reach = INFINITY;
            if (i0 > 0)
                reach = fmin(reach, x - (nn->x0 + (double)i0 * nn->cell_m));
            if (i1 < nn->nx - 1)
                reach = fmin(reach, nn->x0 + (double)(i1 + 1) * nn->cell_m - x);
            if (j0 > 0)
                reach = fmin(reach, y - (nn->y0 + (double)j0 * nn->cell_m));
            if (j1 < nn->ny - 1)
                reach = fmin(reach, nn->y0 + (double)(j1 + 1) * nn->cell_m - y);
            if (reach >= 0.0 && best_d2 <= reach * reach)
                break;
            if (i0 <= 0 && i1 >= nn->nx - 1 && j0 <= 0 && j1 >= nn->ny - 1)
                break;
        }
    }
    return best;
}

int32_t gmmrrt_nn_near(const gmmrrt_nn_t *nn, const gmmrrt_node_t *nodes, double x, double y,
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
            for (int32_t n = nn->heads[j * nn->nx + i]; n >= 0; n = nodes[n].next_in_bucket) {
                const double dx = nodes[n].x - x, ddy = nodes[n].y - y;
                if (dx * dx + ddy * ddy <= r2) {
                    if (count >= cap)
                        return -1;
                    out[count++] = n;
                }
            }
    }
    return count;
}
