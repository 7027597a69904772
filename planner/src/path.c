/*
 * path.c - output of the planner (rrtstar.h, gmmrrt_planner_best_path): the best path so
 * far, root ... best goal-region node ... goal, resampled by arc length at
 * cfg.waypoint_spacing_m (the spacing grows to fit GMMRRT_MAX_WAYPOINTS), yaw = direction
 * of travel of the segment each waypoint lies on. One walk up the parent links, no memory.
 */
#include <math.h>
#include <string.h>

#include "planner_internal.h"

gmmrrt_status_t gmmrrt_planner_best_path(const gmmrrt_planner_t *p, gmmrrt_path_t *out)
{
    if (!p || !out)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    out->num_points = 0;
    out->length_m = 0.0;
    out->cost = INFINITY;
    if (!p->has_problem || p->best_goal < 0)
        return GMMRRT_NO_PATH_YET;
    const gmmrrt_problem_t *pr = &p->problem;
    const int32_t leaf = p->goal_idx[p->best_goal];

    /* Total length: goal edge, then the tree edges up to the root. */
    double total = hypot(pr->goal_x - p->pool.xy[leaf].x, pr->goal_y - p->pool.xy[leaf].y);
    for (int32_t i = leaf; p->pool.link[i].parent >= 0; i = p->pool.link[i].parent) {
        const gmmrrt_xy_t *a = &p->pool.xy[p->pool.link[i].parent], *b = &p->pool.xy[i];
        total += hypot(b->x - a->x, b->y - a->y);
    }
    double spacing = p->cfg.waypoint_spacing_m;
    int32_t m = (int32_t)fmin(ceil(total / spacing) + 1.0, (double)GMMRRT_MAX_WAYPOINTS + 1.0);
    if (m > GMMRRT_MAX_WAYPOINTS) {
        m = GMMRRT_MAX_WAYPOINTS;
        spacing = total / (double)(m - 1);
    }
    if (m < 2)
        m = 2;
    /* Waypoint j (0 .. m-2) sits at arc length j * spacing from the start, the last one at
     * the goal. Walking from the goal back, distance from the goal t grows, so j falls. */
    out->num_points = m;
    out->x[m - 1] = pr->goal_x;
    out->y[m - 1] = pr->goal_y;
    int32_t j = m - 2;
    double t_end = 0.0; /* distance from the goal at the segment's far (goal-side) end */
    double bx = pr->goal_x, by = pr->goal_y;
    int32_t i = leaf;
    double last_yaw = 0.0;
    int have_yaw = 0, first = 1;
    for (;;) {
        double ax, ay;
        int32_t next;
        if (first) { /* the goal edge: leaf -> goal */
            ax = p->pool.xy[leaf].x;
            ay = p->pool.xy[leaf].y;
            next = leaf;
            first = 0;
        } else {
            next = p->pool.link[i].parent;
            if (next < 0)
                break;
            ax = p->pool.xy[next].x;
            ay = p->pool.xy[next].y;
        }
        const double len = hypot(bx - ax, by - ay);
        if (len > 0.0) {
            const double yaw = atan2(by - ay, bx - ax);
            if (!have_yaw) {
                out->yaw[m - 1] = yaw; /* arrival heading at the goal */
                have_yaw = 1;
            }
            last_yaw = yaw;
            while (j >= 0) {
                const double t = total - (double)j * spacing; /* distance from the goal */
                if (t > t_end + len + 1e-12)
                    break;
                const double u = (t - t_end) / len; /* 0 at b, 1 at a */
                out->x[j] = bx + u * (ax - bx);
                out->y[j] = by + u * (ay - by);
                out->yaw[j] = yaw;
                --j;
            }
            t_end += len;
        }
        bx = ax;
        by = ay;
        i = next;
    }
    /* Rounding may leave the first waypoints unset; they belong to the start. */
    for (; j >= 0; --j) {
        out->x[j] = pr->start_x;
        out->y[j] = pr->start_y;
        out->yaw[j] = last_yaw;
    }
    if (!have_yaw)
        out->yaw[m - 1] = last_yaw;
    out->x[0] = pr->start_x;
    out->y[0] = pr->start_y;
    out->length_m = total;
    out->cost = p->best_cost;
    return GMMRRT_OK;
}
