/*
 * raster_exact.cpp - exact disc and swept-disc tests against a raster's blocked cells
 * (raster_exact.hpp). Work is in the raster frame (cell (i, j) = [i res, (i+1) res] x
 * [j res, (j+1) res]); only the cells within radius_m of the point or segment are visited,
 * column by column.
 */
#include "raster_exact.hpp"

#include <algorithm>
#include <cmath>

namespace gmmrrt_bench {

namespace {

double point_box_d2(double u, double v, double bx0, double by0, double bx1, double by1)
{
    const double du = u < bx0 ? bx0 - u : (u > bx1 ? u - bx1 : 0.0);
    const double dv = v < by0 ? by0 - v : (v > by1 ? v - by1 : 0.0);
    return du * du + dv * dv;
}

double point_segment_d2(double px, double py, double u0, double v0, double u1, double v1)
{
    const double du = u1 - u0, dv = v1 - v0, l2 = du * du + dv * dv;
    double t = l2 > 0.0 ? ((px - u0) * du + (py - v0) * dv) / l2 : 0.0;
    t = std::min(1.0, std::max(0.0, t));
    const double ex = u0 + t * du - px, ey = v0 + t * dv - py;
    return ex * ex + ey * ey;
}

bool segment_hits_box(double u0, double v0, double u1, double v1, double bx0, double by0, double bx1, double by1)
{
    const double du = u1 - u0, dv = v1 - v0;
    const double p[4] = {-du, du, -dv, dv};
    const double q[4] = {u0 - bx0, bx1 - u0, v0 - by0, by1 - v0};
    double t0 = 0.0, t1 = 1.0;
    for (int k = 0; k < 4; ++k) {
        if (p[k] == 0.0) {
            if (q[k] < 0.0)
                return false;
        } else {
            const double t = q[k] / p[k];
            if (p[k] < 0.0)
                t0 = std::max(t0, t);
            else
                t1 = std::min(t1, t);
            if (t0 > t1)
                return false;
        }
    }
    return true;
}

/* Distance^2 between a segment and a closed axis-aligned square: 0 when they meet, else the
 * least of the endpoints' distances to the square and the corners' distances to the segment
 * (two disjoint convex polygons are closest at a vertex of one of them). */
double segment_box_d2(double u0, double v0, double u1, double v1, double bx0, double by0, double bx1, double by1)
{
    if (segment_hits_box(u0, v0, u1, v1, bx0, by0, bx1, by1))
        return 0.0;
    double d2 = std::min(point_box_d2(u0, v0, bx0, by0, bx1, by1), point_box_d2(u1, v1, bx0, by0, bx1, by1));
    d2 = std::min(d2, point_segment_d2(bx0, by0, u0, v0, u1, v1));
    d2 = std::min(d2, point_segment_d2(bx1, by0, u0, v0, u1, v1));
    d2 = std::min(d2, point_segment_d2(bx0, by1, u0, v0, u1, v1));
    d2 = std::min(d2, point_segment_d2(bx1, by1, u0, v0, u1, v1));
    return d2;
}

void to_raster_frame(const gmmrrt_raster_t &r, double x, double y, double *u, double *v)
{
    const double dx = x - r.origin_x, dy = y - r.origin_y;
    *u = dx * r.cos_yaw + dy * r.sin_yaw;
    *v = -dx * r.sin_yaw + dy * r.cos_yaw;
}

} // namespace

bool raster_cell_blocks(const gmmrrt_raster_t &r, long i, long j)
{
    if (i < 0 || j < 0 || i >= r.width || j >= r.height)
        return r.unknown_blocked != 0;
    const uint8_t c = r.cells[static_cast<size_t>(j) * static_cast<size_t>(r.width) + static_cast<size_t>(i)];
    return c == GMMRRT_RASTER_OCCUPIED || (c == GMMRRT_RASTER_UNKNOWN && r.unknown_blocked);
}

bool raster_motion_free(const gmmrrt_raster_t &r, double radius_m, double x0, double y0, double x1, double y1)
{
    double u0, v0, u1, v1;
    to_raster_frame(r, x0, y0, &u0, &v0);
    to_raster_frame(r, x1, y1, &u1, &v1);
    const double res = r.resolution_m, r2 = radius_m * radius_m;
    const long i_lo = static_cast<long>(std::floor((std::min(u0, u1) - radius_m) / res));
    const long i_hi = static_cast<long>(std::floor((std::max(u0, u1) + radius_m) / res));
    for (long i = i_lo; i <= i_hi; ++i) {
        /* The part of the segment whose u lies within radius_m of this column, and its v span. */
        const double ua = i * res - radius_m, ub = (i + 1) * res + radius_m;
        double ta = 0.0, tb = 1.0;
        if (u1 != u0) {
            ta = (ua - u0) / (u1 - u0);
            tb = (ub - u0) / (u1 - u0);
            if (ta > tb)
                std::swap(ta, tb);
            ta = std::max(0.0, ta);
            tb = std::min(1.0, tb);
            if (ta > tb)
                continue;
        }
        const double va = v0 + ta * (v1 - v0), vb = v0 + tb * (v1 - v0);
        const long j_lo = static_cast<long>(std::floor((std::min(va, vb) - radius_m) / res));
        const long j_hi = static_cast<long>(std::floor((std::max(va, vb) + radius_m) / res));
        for (long j = j_lo; j <= j_hi; ++j)
            if (raster_cell_blocks(r, i, j) &&
                segment_box_d2(u0, v0, u1, v1, i * res, j * res, (i + 1) * res, (j + 1) * res) <= r2)
                return false;
    }
    return true;
}

bool raster_disc_free(const gmmrrt_raster_t &r, double radius_m, double x, double y)
{
    return raster_motion_free(r, radius_m, x, y, x, y);
}

} // namespace gmmrrt_bench
