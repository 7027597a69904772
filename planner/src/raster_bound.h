/*
 * raster_bound.h - the raster's clearance bound where it is cheapest to read: the point's cell
 * in raster coordinates, and the four-corner bound of gmmrrt_raster_clearance_bound (raster.h)
 * for a point whose cell has all four corners inside the valid window. That is where nearly
 * every query of a search lands, and there the bound needs neither the clamps nor the validity
 * tests of the general case. Inline, because the collision world's sphere tracing reads it
 * several times per edge (collision.c) and the call itself was a fifth of its cost.
 */
#ifndef GMMRRT_RASTER_BOUND_H
#define GMMRRT_RASTER_BOUND_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "gmmrrt/raster.h"

/* World (x, y) in cells of the raster frame: (*u, *v), cell (i, j) spanning [i, i + 1) x
 * [j, j + 1). A product by 1 / resolution, and no rotation on a map whose yaw is 0 (the same
 * values as with it). */
static inline void gmmrrt_raster_to_cells(const gmmrrt_raster_t *r, double x, double y, double *u, double *v)
{
    const double dx = x - r->origin_x, dy = y - r->origin_y;
    if (r->sin_yaw == 0.0 && r->cos_yaw == 1.0) {
        *u = dx * r->inv_resolution_m;
        *v = dy * r->inv_resolution_m;
        return;
    }
    *u = (dx * r->cos_yaw + dy * r->sin_yaw) * r->inv_resolution_m;
    *v = (-dx * r->sin_yaw + dy * r->cos_yaw) * r->inv_resolution_m;
}

/* 1 and *lb = gmmrrt_raster_clearance_bound(r, x, y) when the point at cells (u, v) has its
 * cell's four corners in the valid window; 0 (and *lb untouched) otherwise, and for NaN. The
 * same operations as the general bound, so the same value: each corner's distance less the
 * point's distance to it, the largest of the four. */
static inline int gmmrrt_raster_interior_bound(const gmmrrt_raster_t *r, double u, double v, double *lb)
{
    if (!(u >= (double)r->valid_i0 && u < (double)(r->valid_i1 - 1) && v >= (double)r->valid_j0 &&
          v < (double)(r->valid_j1 - 1)))
        return 0;
    const int32_t i = (int32_t)u, j = (int32_t)v; /* u, v >= 0 here: truncation is floor */
    const double cua = (double)i - u, cub = (double)(i + 1) - u;
    const double cva = (double)j - v, cvb = (double)(j + 1) - v;
    const double ua2 = cua * cua, ub2 = cub * cub, va2 = cva * cva, vb2 = cvb * cvb;
    const size_t w = (size_t)r->width + 1u;
    const float *c = r->dist + (size_t)j * w + (size_t)i;
    const double l0 = (double)c[0] - sqrt(ua2 + va2) * r->resolution_m;
    const double l1 = (double)c[1] - sqrt(ub2 + va2) * r->resolution_m;
    const double l2 = (double)c[w] - sqrt(ua2 + vb2) * r->resolution_m;
    const double l3 = (double)c[w + 1] - sqrt(ub2 + vb2) * r->resolution_m;
    const double a = l1 > l0 ? l1 : l0, b = l3 > l2 ? l3 : l2;
    *lb = b > a ? b : a;
    return 1;
}

#endif
