/*
 * path.c - output of the planner (planner.h, gmmrrt_planner_best_path): the best path so
 * far, root ... best goal-region node ... goal, as waypoints at most cfg.waypoint_spacing_m
 * apart along it (the spacing grows to fit GMMRRT_MAX_WAYPOINTS), yaw = direction of travel
 * of the segment each waypoint starts (the goal: the arrival heading).
 *
 * Published paths are exactly as safe as the tree: every chord between two consecutive
 * waypoints passes gmmrrt_world_segment_free, the check every tree edge passed. First the
 * waypoints are placed at equal arc length (smooth, and what the warm start has always been
 * seeded with); that cuts each corner of the tree path by a chord the tree never checked (up
 * to 2.6 mm into an inflated obstacle or a person disc was seen), so every chord is checked,
 * and if any fails the path is made again keeping every tree vertex as a waypoint, with the
 * points added between two vertices on the tree edge joining them. Only when the tree path
 * has more vertices than GMMRRT_MAX_WAYPOINTS are vertices dropped, and then each replacing
 * chord is checked with the same gmmrrt_world_segment_free.
 * No memory beyond *out: the vertices are gathered into it, then spread out in place.
 */
#include <math.h>
#include <string.h>

#include "planner_internal.h"

/* The path's vertices from the goal back to the root: the goal, then the best goal-region
 * node and its ancestors. Consecutive equal points are skipped. */
typedef struct {
    const gmmrrt_planner_t *p;
    int32_t next; /* pool index of the next vertex; -1 when the root was visited */
    int at_goal;  /* the goal itself is next */
    double lx, ly;
    int have_last;
} walk_t;

static void walk_start(walk_t *w, const gmmrrt_planner_t *p)
{
    w->p = p;
    w->next = p->goal_idx[p->best_goal];
    w->at_goal = 1;
    w->have_last = 0;
    w->lx = w->ly = 0.0; /* read only once have_last is set; set for GCC's -Wmaybe-uninitialized */
}

static int walk_next(walk_t *w, double *x, double *y)
{
    for (;;) {
        if (w->at_goal) {
            w->at_goal = 0;
            *x = w->p->problem.goal_x;
            *y = w->p->problem.goal_y;
        } else {
            if (w->next < 0)
                return 0;
            *x = w->p->pool.xy[w->next].x;
            *y = w->p->pool.xy[w->next].y;
            w->next = w->p->pool.link[w->next].parent;
        }
        if (w->have_last && *x == w->lx && *y == w->ly)
            continue;
        w->lx = *x;
        w->ly = *y;
        w->have_last = 1;
        return 1;
    }
}

/* Gathers the vertices root-first into out->x/y[0 .. n-1] when `write` (the caller passes
 * n from a counting pass). shortcut: a vertex is kept only where the chord from the last kept
 * one to the next would not be free. Returns the number of vertices kept. */
static int32_t gather(const gmmrrt_planner_t *p, gmmrrt_path_t *out, int shortcut, int write, int32_t n)
{
    walk_t w;
    walk_start(&w, p);
    int32_t count = 0;
    double x, y, ax = 0.0, ay = 0.0, px = 0.0, py = 0.0;
    int have_prev = 0;
    while (walk_next(&w, &x, &y)) {
        if (count == 0) { /* the goal: always kept */
            if (write)
                out->x[n - 1] = x, out->y[n - 1] = y;
            count = 1;
            ax = x;
            ay = y;
            continue;
        }
        if (!shortcut) {
            if (write)
                out->x[n - 1 - count] = x, out->y[n - 1 - count] = y;
            ++count;
            continue;
        }
        if (have_prev && !gmmrrt_world_segment_free(p->world, ax, ay, x, y)) {
            if (write && count < n)
                out->x[n - 1 - count] = px, out->y[n - 1 - count] = py;
            ++count;
            ax = px;
            ay = py;
        }
        px = x;
        py = y;
        have_prev = 1;
    }
    if (shortcut && have_prev) { /* the root */
        if (write && count < n)
            out->x[n - 1 - count] = px, out->y[n - 1 - count] = py;
        ++count;
    }
    return count;
}

/* Pieces per edge at spacing s, summed over the n vertices' edges. */
static double pieces(const gmmrrt_path_t *v, int32_t n, double s)
{
    double total = 0.0;
    for (int32_t e = 0; e + 1 < n; ++e)
        total += fmax(1.0, ceil(hypot(v->x[e + 1] - v->x[e], v->y[e + 1] - v->y[e]) / s));
    return total;
}

int32_t gmmrrt_waypoint_count(double total_m, double *spacing_m)
{
    int32_t m = (int32_t)fmin(ceil(total_m / *spacing_m) + 1.0, (double)GMMRRT_MAX_WAYPOINTS + 1.0);
    if (m > GMMRRT_MAX_WAYPOINTS) {
        m = GMMRRT_MAX_WAYPOINTS;
        *spacing_m = total_m / (double)(m - 1);
    }
    return m < 2 ? 2 : m;
}

/* Waypoints at equal arc length along the tree path (corners are cut by the chords). */
static void resample_by_arc_length(const gmmrrt_planner_t *p, gmmrrt_path_t *out)
{
    const gmmrrt_problem_t *pr = &p->problem;
    const int32_t leaf = p->goal_idx[p->best_goal];

    /* Total length: goal edge, then the tree edges up to the root. */
    double total = hypot(pr->goal_x - p->pool.xy[leaf].x, pr->goal_y - p->pool.xy[leaf].y);
    for (int32_t i = leaf; p->pool.link[i].parent >= 0; i = p->pool.link[i].parent) {
        const gmmrrt_xy_t *a = &p->pool.xy[p->pool.link[i].parent], *b = &p->pool.xy[i];
        total += hypot(b->x - a->x, b->y - a->y);
    }
    double spacing = p->cfg.waypoint_spacing_m;
    const int32_t m = gmmrrt_waypoint_count(total, &spacing);
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
}

/* Waypoints keeping every tree vertex (module comment). */
static gmmrrt_status_t resample_keeping_vertices(const gmmrrt_planner_t *p, gmmrrt_path_t *out)
{
    const gmmrrt_problem_t *pr = &p->problem;

    int32_t n = gather(p, out, 0, 0, 0);
    int shortcut = 0;
    if (n > GMMRRT_MAX_WAYPOINTS) {
        shortcut = 1;
        n = gather(p, out, 1, 0, 0);
        if (n > GMMRRT_MAX_WAYPOINTS)
            return GMMRRT_ERR_BUFFER_TOO_SMALL; /* even checked chords cannot make it fit */
    }
    if (n < 2) { /* start at the goal: a path of one point, published as two */
        out->x[0] = out->x[1] = pr->start_x;
        out->y[0] = out->y[1] = pr->start_y;
        out->yaw[0] = out->yaw[1] = 0.0;
        out->num_points = 2;
        out->cost = p->best_cost;
        return GMMRRT_OK;
    }
    (void)gather(p, out, shortcut, 1, n);

    /* The spacing: cfg.waypoint_spacing_m, or the smallest larger one (bisection) whose pieces fit. */
    double s = p->cfg.waypoint_spacing_m;
    const double budget = (double)(GMMRRT_MAX_WAYPOINTS - 1);
    if (pieces(out, n, s) > budget) {
        double lo = s, hi = s;
        while (pieces(out, n, hi) > budget)
            hi *= 2.0;
        for (int it = 0; it < 60 && hi > lo * (1.0 + 1e-12); ++it) {
            const double mid = 0.5 * (lo + hi);
            if (pieces(out, n, mid) > budget)
                lo = mid;
            else
                hi = mid;
        }
        s = hi;
    }
    const int32_t m = (int32_t)pieces(out, n, s) + 1;

    /* Spread in place from the end: vertex e moves to index w >= e, so nothing unread is
     * overwritten. Edge e (vertex e -> e+1) gets k points: vertex e and k-1 inside it. */
    double total = 0.0;
    int32_t w = m - 1;
    const double gx = out->x[n - 1], gy = out->y[n - 1];
    double arrival = atan2(gy - out->y[n - 2], gx - out->x[n - 2]);
    for (int32_t e = n - 2; e >= 0; --e) {
        const double ax = out->x[e], ay = out->y[e], bx = out->x[e + 1], by = out->y[e + 1];
        const double len = hypot(bx - ax, by - ay);
        const int32_t k = (int32_t)fmax(1.0, ceil(len / s));
        const double yaw = atan2(by - ay, bx - ax);
        total += len;
        for (int32_t i = k - 1; i >= 0; --i) {
            const double u = (double)i / (double)k;
            --w;
            out->x[w] = ax + u * (bx - ax);
            out->y[w] = ay + u * (by - ay);
            out->yaw[w] = yaw;
        }
    }
    out->x[m - 1] = gx;
    out->y[m - 1] = gy;
    out->yaw[m - 1] = arrival;
    out->x[0] = pr->start_x;
    out->y[0] = pr->start_y;
    out->num_points = m;
    out->length_m = total;
    out->cost = p->best_cost;
    return GMMRRT_OK;
}

gmmrrt_status_t gmmrrt_planner_best_path(const gmmrrt_planner_t *p, gmmrrt_path_t *out)
{
    if (!p || !out)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    out->num_points = 0;
    out->length_m = 0.0;
    out->cost = INFINITY;
    if (!p->has_problem || p->best_goal < 0)
        return GMMRRT_NO_PATH_YET;
    resample_by_arc_length(p, out);
    for (int32_t i = 1; i < out->num_points; ++i)
        if (!gmmrrt_world_segment_free(p->world, out->x[i - 1], out->y[i - 1], out->x[i], out->y[i]))
            return resample_keeping_vertices(p, out);
    return GMMRRT_OK;
}
