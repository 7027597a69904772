/*
 * segment_exact.h - internal: the exact segment test against circles and oriented boxes that
 * collision.c uses while it answers with the closed forms (few static obstacles, or the first
 * queries of a world): one distance per shape instead of a sphere-tracing walk that evaluates
 * every shape at each probe; and the point test of the same. Not a public header.
 */
#ifndef GMMRRT_SEGMENT_EXACT_H
#define GMMRRT_SEGMENT_EXACT_H

#include "gmmrrt/collision.h"

/* 1 when every point of the segment (x0, y0)-(x1, y1) is farther than reach_m from each circle
 * and each box of o (reach_m: robot radius plus the edge margin), exactly: for a circle the
 * point-to-segment distance of its centre less its radius; for a box, 0 when the segment meets
 * it, else the least of the ends' distances to the box and the corners' distances to the
 * segment (the nearest points of two disjoint convex polygons include a vertex of one).
 * box_cos / box_sin: cos and sin of each box's yaw. */
int gmmrrt_segment_clear_of_shapes(const gmmrrt_obstacle_set_t *o, const double *box_cos, const double *box_sin,
                                   double reach_m, double x0, double y0, double x1, double y1);

/* 1 when the point (x, y) is farther than reach_m from each circle and each box of o (the same
 * distances, squared where that decides alone). */
int gmmrrt_point_clear_of_shapes(const gmmrrt_obstacle_set_t *o, const double *box_cos, const double *box_sin,
                                 double reach_m, double x, double y);

#endif /* GMMRRT_SEGMENT_EXACT_H */
