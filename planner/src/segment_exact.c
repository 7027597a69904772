/*
 * segment_exact.c - the exact segment test of segment_exact.h: the clearance of a segment to
 * circles and oriented boxes in closed form (the same shapes and the same distances as the
 * closed forms of collision.c, which FCL's answers are tested against).
 */
#include "segment_exact.h"

#include <math.h>

/* Squared distance from (px, py) to the segment a + t d, t in [0, 1] (dd = |d|^2). */
static double point_segment_d2(double px, double py, double ax, double ay, double dx, double dy, double dd)
{
    double t = dd > 0.0 ? ((px - ax) * dx + (py - ay) * dy) / dd : 0.0;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    const double ex = ax + t * dx - px, ey = ay + t * dy - py;
    return ex * ex + ey * ey;
}

/* Squared distance from (px, py) to the box [-hx, hx] x [-hy, hy] (0 inside). */
static double point_box_d2(double px, double py, double hx, double hy)
{
    const double qx = fabs(px) - hx, qy = fabs(py) - hy;
    const double ox = qx > 0.0 ? qx : 0.0, oy = qy > 0.0 ? qy : 0.0;
    return ox * ox + oy * oy;
}

/* 1 when the segment a + t d, t in [0, 1], meets the box [-hx, hx] x [-hy, hy] (Liang-Barsky). */
static int segment_meets_box(double ax, double ay, double dx, double dy, double hx, double hy)
{
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {ax + hx, hx - ax, ay + hy, hy - ay};
    double t0 = 0.0, t1 = 1.0;
    for (int k = 0; k < 4; ++k) {
        if (p[k] == 0.0) {
            if (q[k] < 0.0)
                return 0;
            continue;
        }
        const double r = q[k] / p[k];
        if (p[k] < 0.0)
            t0 = r > t0 ? r : t0;
        else
            t1 = r < t1 ? r : t1;
        if (t0 > t1)
            return 0;
    }
    return 1;
}

int gmmrrt_segment_clear_of_shapes(const gmmrrt_obstacle_set_t *o, const double *box_cos, const double *box_sin,
                                   double reach_m, double x0, double y0, double x1, double y1)
{
    const double dx = x1 - x0, dy = y1 - y0, dd = dx * dx + dy * dy;
    for (int32_t k = 0; k < o->num_circles; ++k) {
        const gmmrrt_circle_t *c = &o->circles[k];
        const double r = c->radius_m + reach_m;
        if (point_segment_d2(c->x, c->y, x0, y0, dx, dy, dd) <= r * r)
            return 0;
    }
    const double reach2 = reach_m * reach_m;
    for (int32_t k = 0; k < o->num_boxes; ++k) {
        const gmmrrt_box_t *b = &o->boxes[k];
        const double cs = box_cos[k], sn = box_sin[k];
        const double hx = 0.5 * b->width_m, hy = 0.5 * b->height_m;
        /* The segment in the box's frame. */
        const double ax = (x0 - b->x) * cs + (y0 - b->y) * sn, ay = -(x0 - b->x) * sn + (y0 - b->y) * cs;
        const double ex = dx * cs + dy * sn, ey = -dx * sn + dy * cs;
        /* Far from the box's bounding circle: clear without the rest. */
        const double rb = sqrt(hx * hx + hy * hy) + reach_m;
        if (point_segment_d2(0.0, 0.0, ax, ay, ex, ey, dd) > rb * rb)
            continue;
        if (segment_meets_box(ax, ay, ex, ey, hx, hy))
            return 0;
        if (point_box_d2(ax, ay, hx, hy) <= reach2 || point_box_d2(ax + ex, ay + ey, hx, hy) <= reach2)
            return 0;
        for (int corner = 0; corner < 4; ++corner) {
            const double cx = (corner & 1) ? hx : -hx, cy = (corner & 2) ? hy : -hy;
            if (point_segment_d2(cx, cy, ax, ay, ex, ey, dd) <= reach2)
                return 0;
        }
    }
    return 1;
}

int gmmrrt_point_clear_of_shapes(const gmmrrt_obstacle_set_t *o, const double *box_cos, const double *box_sin,
                                 double reach_m, double x, double y)
{
    for (int32_t k = 0; k < o->num_circles; ++k) {
        const gmmrrt_circle_t *c = &o->circles[k];
        const double r = c->radius_m + reach_m, dx = x - c->x, dy = y - c->y;
        if (dx * dx + dy * dy <= r * r)
            return 0;
    }
    const double reach2 = reach_m * reach_m;
    for (int32_t k = 0; k < o->num_boxes; ++k) {
        const gmmrrt_box_t *b = &o->boxes[k];
        const double dx = x - b->x, dy = y - b->y;
        const double lx = dx * box_cos[k] + dy * box_sin[k], ly = -dx * box_sin[k] + dy * box_cos[k];
        if (point_box_d2(lx, ly, 0.5 * b->width_m, 0.5 * b->height_m) <= reach2)
            return 0;
    }
    return 1;
}
