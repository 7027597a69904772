/*
 * smooth.c - gmmrrt_planner_drivable_path (drivable.h): from the tree's best path to a path a
 * wheeled robot can follow.
 *
 *  1. The vertices: the real start and the escape's exit when escaping (escape.c), the tree's
 *     nodes from the root to the best goal node, the goal.
 *  2. Shortcut (greedy, from the root on): vertex i is joined to the farthest j reachable by one
 *     run of consecutive vertices such that the chord i-j is free by the planner's own tests and
 *     costs no more than the tree path it replaces (cost(i, j) <= C(j) - C(i), C the tree's
 *     cost-to-come; the objective includes the task cost, so a shortcut never trades the learned
 *     social shape for length) and passes every person on the tree path's side. The escape is
 *     kept as it is.
 *  3. Arrival: when the path must end on a heading and does not, a straight leg W -> goal on
 *     that heading (or, failing that, one within the tolerance) replaces the path's tail from the
 *     latest vertex that sees W (legs tried from arrival_leg_m up, preferring one whose corner arc
 *     fits), never one that passes a person on the other side than the tail it replaces.
 *  3b. A corner whose arc cannot fit its segments is dropped when the chord over it is free, costs
 *     at most 5 % more than the two segments and keeps the sides (relax_tight_corners).
 *  Sides: each person's side is the angle the bearing from them sweeps along the path; every
 *  replacement in 2, 3 and 3b sweeps the same angle as what it replaces (seg_sweep), so the
 *  drivable path stays in the tree path's homotopy class around every person, which is what the
 *  learned model chose (paper Sect. 4: the demonstrations' side of the person).
 *  4. Corners: each corner turning by phi gets the circular arc of radius R = min_turn_radius_m
 *     tangent to both segments (tangent length R tan(phi / 2)); when the segments are too short
 *     for it, or a chord of the arc is not free, the arc is made smaller and the corner counted
 *     as tight (reported, never hidden). R = 0: the robot turns in place at the corner. The arc
 *     is checked by its own chords of at most GMMRRT_ARC_CHORD_M with the planner's segment test;
 *     the straight pieces are parts of checked segments.
 *  5. Published: waypoints at equal arc length (the planner's waypoint spacing), yaw = the
 *     tangent. The robot drives the chords between them, and a chord of an arc cuts inside it by
 *     up to spacing^2 / 8r (2 mm at 0.1 m and r = 0.6 m), deeper than the arc's own chords: so
 *     every published chord is checked with the planner's segment test, and when one fails the
 *     waypoints are placed at the pieces' ends instead, each arc at exactly its own checked
 *     chords (and the straight pieces in equal parts). The corner keeps its radius; what is
 *     published is what was checked.
 *  6. Walking people: every waypoint is tested against where each walker is at the waypoint's
 *     time (arc length / nominal speed), the exact version of the search's time window.
 * All arrays are bounded (GMMRRT_DRIVE_MAX_VERTICES) and on the stack: no allocation.
 */
#include "gmmrrt/drivable.h"

#include <math.h>
#include <string.h>

#include "planner_internal.h"

#define GMMRRT_ARC_CHORD_M 0.05
#define GMMRRT_MIN_ARC_RADIUS_M 1e-3
#define GMMRRT_STRAIGHT_RAD 1e-6
#define GMMRRT_COLLINEAR_M 1e-6 /* a tree vertex this close to the chord over it is not a corner */
#define MAXV GMMRRT_DRIVE_MAX_VERTICES

void gmmrrt_drive_options_default(gmmrrt_drive_options_t *opt)
{
    if (!opt)
        return;
    opt->min_turn_radius_m = 0.3;
    opt->arrival = GMMRRT_ARRIVAL_ANY;
    opt->goal_yaw = 0.0;
    opt->goal_yaw_tolerance_rad = 15.0 * M_PI / 180.0;
    opt->arrival_leg_m = 0.4;
    opt->shortcut = 1;
}

typedef struct {
    int32_t n;
    double x[MAXV], y[MAXV], c[MAXV]; /* c: tree cost-to-come, NAN where none (escape start, leg) */
} polyline_t;

/* One output piece: a line from (x0, y0) of length len along yaw, or an arc (r > 0) centred at
 * (cx, cy) starting at angle a0 from the centre, turning dir (+1 left, -1 right). */
typedef struct {
    double x0, y0, yaw, len;
    double r, cx, cy, a0, dir;
} piece_t;

static int seg_free(const struct gmmrrt_planner *p, double x0, double y0, double x1, double y1)
{
    return gmmrrt_planner_segment_free(p, x0, y0, x1, y1);
}

/* Sides of the people. The signed angle the bearing from person q to the robot sweeps along a
 * straight segment (counter-clockwise positive) is the wrapped change of that bearing, exactly,
 * for a segment that does not pass through the person. Two paths between the same two points pass
 * q on the same side (are homotopic in the plane punctured at q) iff their swept angles are equal;
 * otherwise they differ by a multiple of 2 pi. So a piece of the path may be replaced by another
 * with the same ends only when, for every person, the two sweep the same angle: |difference| < pi
 * decides with all rounding to spare. The people are the problem's, where they are now. */
static double seg_sweep(const gmmrrt_pose_t *q, double ax, double ay, double bx, double by)
{
    return gmmrrt_wrap_angle(atan2(by - q->y, bx - q->x) - atan2(ay - q->y, ax - q->x));
}

static void sweep_clear(const struct gmmrrt_planner *p, double *acc)
{
    for (int32_t q = 0; q < p->problem.obstacles.num_people; ++q)
        acc[q] = 0.0;
}

/* acc[q] += the angle segment a-b sweeps around person q. */
static void sweep_add(const struct gmmrrt_planner *p, double *acc, double ax, double ay, double bx, double by)
{
    for (int32_t q = 0; q < p->problem.obstacles.num_people; ++q)
        acc[q] += seg_sweep(&p->problem.obstacles.people[q], ax, ay, bx, by);
}

/* 1 when the swept angles old[] and new_[] put every person on the same side. */
static int sweep_same_side(const struct gmmrrt_planner *p, const double *old, const double *new_)
{
    for (int32_t q = 0; q < p->problem.obstacles.num_people; ++q)
        if (!(fabs(old[q] - new_[q]) < M_PI))
            return 0;
    return 1;
}

/* Swept angles of the polyline x[0..n) around every person. */
static void sweep_polyline(const struct gmmrrt_planner *p, const double *x, const double *y, int32_t n, double *acc)
{
    sweep_clear(p, acc);
    for (int32_t i = 0; i + 1 < n; ++i)
        sweep_add(p, acc, x[i], y[i], x[i + 1], y[i + 1]);
}

/* Appends (x, y, c) to the leaf-first list r[0..*m); `merge`: when the last vertex lies on the
 * chord from the one before it to the new vertex (within GMMRRT_COLLINEAR_M) and that chord is
 * free, the new vertex replaces it. RRT*'s rewiring strings runs of nearly collinear nodes along
 * a straight stretch (each rewire saving only rounding), so a tree path can hold far more vertices
 * than corners; dropping them keeps the polyline (and the cost of every kept vertex) as it was. */
static int push_vertex(const struct gmmrrt_planner *p, polyline_t *r, int32_t *m, double x, double y, double c,
                       int merge)
{
    if (merge && *m >= 2) {
        const double ax = r->x[*m - 2], ay = r->y[*m - 2], bx = r->x[*m - 1], by = r->y[*m - 1];
        const double len = hypot(x - ax, y - ay);
        const double cross = fabs((x - ax) * (by - ay) - (y - ay) * (bx - ax));
        const double off = len > 0.0 ? cross / len : hypot(bx - ax, by - ay);
        const double along = (bx - ax) * (x - ax) + (by - ay) * (y - ay);
        if (off <= GMMRRT_COLLINEAR_M && along >= 0.0 && along <= len * len && seg_free(p, ax, ay, x, y)) {
            r->x[*m - 1] = x;
            r->y[*m - 1] = y;
            r->c[*m - 1] = c;
            return 1;
        }
    }
    if (*m >= MAXV - 2) /* two slots left for the arrival leg */
        return 0;
    r->x[*m] = x;
    r->y[*m] = y;
    r->c[*m] = c;
    ++*m;
    return 1;
}

static gmmrrt_status_t extract(const struct gmmrrt_planner *p, polyline_t *v, int32_t *first_free)
{
    const int32_t leaf = p->goal_idx[p->best_goal];
    const int esc = p->escape.active;
    const gmmrrt_problem_t *pr = &p->problem;
    const int goal_is_leaf = hypot(pr->goal_x - p->pool.xy[leaf].x, pr->goal_y - p->pool.xy[leaf].y) <= 1e-9;
    /* Leaf first, then reversed: [escape start,] root (the first free vertex), ..., leaf[, goal]. */
    int32_t m = 0;
    if (!goal_is_leaf && !push_vertex(p, v, &m, pr->goal_x, pr->goal_y, p->best_cost, 0))
        return GMMRRT_ERR_BUFFER_TOO_SMALL;
    for (int32_t i = leaf; i >= 0; i = p->pool.link[i].parent)
        if (!push_vertex(p, v, &m, p->pool.xy[i].x, p->pool.xy[i].y, i == leaf && goal_is_leaf ? p->best_cost
                                                                                             : p->pool.cost[i], 1))
            return GMMRRT_ERR_BUFFER_TOO_SMALL;
    if (esc && !push_vertex(p, v, &m, p->escape.start_x, p->escape.start_y, NAN, 0))
        return GMMRRT_ERR_BUFFER_TOO_SMALL;
    for (int32_t a = 0, b = m - 1; a < b; ++a, --b) {
        const double tx = v->x[a], ty = v->y[a], tc = v->c[a];
        v->x[a] = v->x[b];
        v->y[a] = v->y[b];
        v->c[a] = v->c[b];
        v->x[b] = tx;
        v->y[b] = ty;
        v->c[b] = tc;
    }
    v->n = m;
    *first_free = esc;
    return GMMRRT_OK;
}

static void shortcut(const struct gmmrrt_planner *p, polyline_t *v, int32_t first_free)
{
    int32_t out = first_free + 1, i = first_free;
    double tree[GMMRRT_MAX_PEOPLE], chord[GMMRRT_MAX_PEOPLE];
    while (i < v->n - 1) {
        int32_t j = i + 1;
        sweep_clear(p, tree);
        sweep_add(p, tree, v->x[i], v->y[i], v->x[j], v->y[j]);
        while (j + 1 <= v->n - 1) {
            const int32_t k = j + 1;
            const double saved = v->c[k] - v->c[i];
            if (!seg_free(p, v->x[i], v->y[i], v->x[k], v->y[k]))
                break;
            if (!(gmmrrt_edge_cost(p, v->x[i], v->y[i], v->x[k], v->y[k]) <= saved + 1e-9 * (1.0 + fabs(v->c[k]))))
                break;
            sweep_add(p, tree, v->x[j], v->y[j], v->x[k], v->y[k]);
            sweep_clear(p, chord);
            sweep_add(p, chord, v->x[i], v->y[i], v->x[k], v->y[k]);
            if (!sweep_same_side(p, tree, chord))
                break; /* the chord would pass a person on the other side than the tree */
            j = k;
        }
        v->x[out] = v->x[j];
        v->y[out] = v->y[j];
        v->c[out] = v->c[j];
        ++out;
        i = j;
    }
    v->n = out;
}

static double turn_angle(double ax, double ay, double bx, double by, double cx, double cy)
{
    return fabs(gmmrrt_wrap_angle(atan2(cy - by, cx - bx) - atan2(by - ay, bx - ax)));
}

/* Tangent length the corner at b needs for radius R (a -> b -> c). */
static double corner_need(double R, double ax, double ay, double bx, double by, double cx, double cy)
{
    return R * tan(0.5 * turn_angle(ax, ay, bx, by, cx, cy));
}

/* The arrival heading may be anything within the tolerance; this fraction of it is what the
 * fallback headings use, so that the resampled final tangent stays inside it. */
#define GMMRRT_ARRIVAL_RELAX_FRACTION 0.9

/* Replaces the tail so the path ends with a straight leg on a heading within the tolerance of h:
 * vertex k, then the tail points, then the goal. Tails: the leg's start W alone, or W preceded by
 * a point beside it (a U-turn in two corners of about 90 degrees, for a path that arrives from
 * the wrong side, as when approaching a person from behind). Strict pass: every new corner's arc
 * of radius R fits (half of each segment it shares with another corner); lax pass: any free tail.
 * In each pass the heading h itself is tried first, then h -+ GMMRRT_ARRIVAL_RELAX_FRACTION of
 * the tolerance (the one nearer the path's own arrival first). A tail is taken only when it
 * passes every person on the same side as the tail it replaces (sweep_same_side): the leg must
 * not swing the path around the person it approaches. Returns the number of tail points put
 * before the goal (0: the tail was not replaced). */
static int32_t arrival_leg(const struct gmmrrt_planner *p, const gmmrrt_drive_options_t *opt, polyline_t *v,
                           int32_t first_free, double h)
{
    const double gx = v->x[v->n - 1], gy = v->y[v->n - 1];
    const double R = opt->min_turn_radius_m;
    const double last = atan2(gy - v->y[v->n - 2], gx - v->x[v->n - 2]);
    const double d = GMMRRT_ARRIVAL_RELAX_FRACTION * opt->goal_yaw_tolerance_rad;
    const double toward = gmmrrt_wrap_angle(last - h) >= 0.0 ? 1.0 : -1.0;
    const double headings[3] = {h, h + toward * d, h - toward * d};
    static const double scale[] = {1.0, 1.5, 2.0, 3.0, 4.0, 0.75, 0.5};
    double old[GMMRRT_MAX_PEOPLE], tail[GMMRRT_MAX_PEOPLE];
    for (int strict = 1; strict >= 0; --strict) {
        for (int hi = 0; hi < 3; ++hi) {
            const double ux = cos(headings[hi]), uy = sin(headings[hi]);
            for (size_t s = 0; s < sizeof scale / sizeof scale[0]; ++s) {
                const double L = fmax(opt->arrival_leg_m * scale[s], strict ? 1.05 * R : 0.0);
                const double wx = gx - L * ux, wy = gy - L * uy;
                if (!gmmrrt_planner_point_free(p, wx, wy) || !seg_free(p, wx, wy, gx, gy))
                    continue;
                for (int variant = 0; variant < 3; ++variant) {
                    double tx[3], ty[3];
                    int32_t nt = 1;
                    if (variant == 0) {
                        tx[0] = wx;
                        ty[0] = wy;
                    } else { /* beside W: W - L2 u(h +- 90 deg), L2 leaves room for two arcs of 90 degrees */
                        const double side = variant == 1 ? 1.0 : -1.0, l2 = fmax(L, 2.2 * R);
                        tx[0] = wx + side * l2 * uy;
                        ty[0] = wy - side * l2 * ux;
                        tx[1] = wx;
                        ty[1] = wy;
                        nt = 2;
                        if (!gmmrrt_planner_point_free(p, tx[0], ty[0]) || !seg_free(p, tx[0], ty[0], wx, wy))
                            continue;
                    }
                    tx[nt] = gx;
                    ty[nt] = gy;
                    sweep_clear(p, old);
                    for (int32_t k = v->n - 2; k >= first_free; --k) {
                        sweep_add(p, old, v->x[k], v->y[k], v->x[k + 1], v->y[k + 1]); /* the tail from k */
                        const double in = hypot(tx[0] - v->x[k], ty[0] - v->y[k]);
                        if (in < 1e-6 || !seg_free(p, v->x[k], v->y[k], tx[0], ty[0]))
                            continue;
                        if (strict) {
                            /* corners at the tail points, and at vertex k when it is one */
                            const double nx0 = tx[1], ny0 = ty[1];
                            const double t0 = corner_need(R, v->x[k], v->y[k], tx[0], ty[0], nx0, ny0);
                            const double tk = k > first_free ? corner_need(R, v->x[k - 1], v->y[k - 1], v->x[k],
                                                                           v->y[k], tx[0], ty[0])
                                                             : 0.0;
                            if (!(tk + t0 <= in && tk <= 0.5 * hypot(v->x[k] - v->x[k - 1 < 0 ? 0 : k - 1],
                                                                     v->y[k] - v->y[k - 1 < 0 ? 0 : k - 1]) +
                                                             (k > first_free ? 0.0 : INFINITY)))
                                continue;
                            if (nt == 1 && !(t0 <= L))
                                continue;
                            if (nt == 2) {
                                const double t1 = corner_need(R, tx[0], ty[0], wx, wy, gx, gy);
                                if (!(t0 + t1 <= hypot(wx - tx[0], wy - ty[0]) && t1 <= L))
                                    continue;
                            }
                        }
                        sweep_clear(p, tail);
                        sweep_add(p, tail, v->x[k], v->y[k], tx[0], ty[0]);
                        for (int32_t q = 0; q < nt; ++q)
                            sweep_add(p, tail, tx[q], ty[q], tx[q + 1], ty[q + 1]);
                        if (!sweep_same_side(p, old, tail))
                            continue;
                        for (int32_t q = 0; q <= nt; ++q) {
                            v->x[k + 1 + q] = tx[q];
                            v->y[k + 1 + q] = ty[q];
                            v->c[k + 1 + q] = NAN;
                        }
                        v->n = k + 2 + nt;
                        return nt;
                    }
                }
            }
        }
    }
    return 0;
}

/* Corner i's arc of radius R fits its two segments (each shared in proportion to the needs). */
static int corner_fits(const polyline_t *v, int32_t i, double R, int32_t first_free)
{
    double need[3];
    for (int32_t d = -1; d <= 1; ++d) {
        const int32_t j = i + d;
        need[d + 1] = (j <= first_free || j >= v->n - 1)
                          ? 0.0
                          : corner_need(R, v->x[j - 1], v->y[j - 1], v->x[j], v->y[j], v->x[j + 1], v->y[j + 1]);
    }
    const double lin = hypot(v->x[i] - v->x[i - 1], v->y[i] - v->y[i - 1]);
    const double lout = hypot(v->x[i + 1] - v->x[i], v->y[i + 1] - v->y[i]);
    return need[0] + need[1] <= lin && need[1] + need[2] <= lout;
}

/* Corners whose arc cannot fit are removed when the chord over them is free and costs at most
 * GMMRRT_RELAX_COST_RATIO times the two segments it replaces (a small price in the objective for a
 * drivable turn) and passes every person on the same side; vertices from `keep_from` on (the arrival leg) and up to first_free stay. */
#define GMMRRT_RELAX_COST_RATIO 1.05
static void relax_tight_corners(const struct gmmrrt_planner *p, polyline_t *v, double R, int32_t first_free,
                                int32_t keep_from)
{
    if (!(R > 0.0))
        return;
    for (int32_t i = first_free + 1; i < v->n - 1 && i < keep_from;) {
        if (corner_fits(v, i, R, first_free)) {
            ++i;
            continue;
        }
        const double old = gmmrrt_edge_cost(p, v->x[i - 1], v->y[i - 1], v->x[i], v->y[i]) +
                           gmmrrt_edge_cost(p, v->x[i], v->y[i], v->x[i + 1], v->y[i + 1]);
        const double chord = gmmrrt_edge_cost(p, v->x[i - 1], v->y[i - 1], v->x[i + 1], v->y[i + 1]);
        double two[GMMRRT_MAX_PEOPLE], one[GMMRRT_MAX_PEOPLE];
        sweep_clear(p, two);
        sweep_add(p, two, v->x[i - 1], v->y[i - 1], v->x[i], v->y[i]);
        sweep_add(p, two, v->x[i], v->y[i], v->x[i + 1], v->y[i + 1]);
        sweep_clear(p, one);
        sweep_add(p, one, v->x[i - 1], v->y[i - 1], v->x[i + 1], v->y[i + 1]);
        if (!(chord <= GMMRRT_RELAX_COST_RATIO * old) ||
            !seg_free(p, v->x[i - 1], v->y[i - 1], v->x[i + 1], v->y[i + 1]) || !sweep_same_side(p, two, one)) {
            ++i;
            continue;
        }
        for (int32_t j = i; j + 1 < v->n; ++j) {
            v->x[j] = v->x[j + 1];
            v->y[j] = v->y[j + 1];
            v->c[j] = v->c[j + 1];
        }
        --v->n;
        --keep_from;
        if (i > first_free + 1)
            --i; /* the previous corner changed */
    }
}

/* The arc's own chords: n of equal sweep, each at most GMMRRT_ARC_CHORD_M of arc (or the
 * waypoint spacing, when that is finer). */
static int32_t arc_chords(const struct gmmrrt_planner *p, const piece_t *a)
{
    const int32_t n = (int32_t)ceil(a->len / fmin(GMMRRT_ARC_CHORD_M, p->cfg.waypoint_spacing_m));
    return n < 1 ? 1 : n;
}

/* Vertex k (0 .. n) of the arc's own chords and the tangent there. arc_free and the published
 * waypoints both take them from here, so a published chord of the arc is bit for bit one that
 * arc_free checked. */
static void arc_vertex(const piece_t *a, int32_t k, int32_t n, double *x, double *y, double *yaw)
{
    const double ang = a->a0 + a->dir * (a->len / a->r) * (double)k / (double)n;
    *x = a->cx + a->r * cos(ang);
    *y = a->cy + a->r * sin(ang);
    *yaw = gmmrrt_wrap_angle(ang + a->dir * 0.5 * M_PI);
}

/* 1 when every one of the arc's own chords is free. */
static int arc_free(const struct gmmrrt_planner *p, const piece_t *a)
{
    const int32_t n = arc_chords(p, a);
    double px, py, qx, qy, yaw;
    arc_vertex(a, 0, n, &px, &py, &yaw);
    for (int32_t k = 1; k <= n; ++k) {
        arc_vertex(a, k, n, &qx, &qy, &yaw);
        if (!seg_free(p, px, py, qx, qy))
            return 0;
        px = qx;
        py = qy;
    }
    return 1;
}

static void point_on(const piece_t *pc, double s, double *x, double *y, double *yaw)
{
    if (pc->r > 0.0) {
        const double ang = pc->a0 + pc->dir * s / pc->r;
        *x = pc->cx + pc->r * cos(ang);
        *y = pc->cy + pc->r * sin(ang);
        *yaw = gmmrrt_wrap_angle(ang + pc->dir * 0.5 * M_PI);
    } else {
        *x = pc->x0 + s * cos(pc->yaw);
        *y = pc->y0 + s * sin(pc->yaw);
        *yaw = pc->yaw;
    }
}

/* Waypoints at equal arc length along the pieces (at the planner's waypoint spacing, widened to
 * fit GMMRRT_MAX_WAYPOINTS), the first at the start, the last at the goal; s_at[j]: waypoint j's
 * arc length. Smooth, but a chord between two of them on an arc cuts inside it by up to
 * spacing^2 / 8r, deeper than the arc's own chords that arc_free checked. Returns the final yaw. */
static double publish_by_arc_length(const struct gmmrrt_planner *p, const piece_t *pieces, int32_t np,
                                    double total, const polyline_t *v, gmmrrt_path_t *out, double *s_at)
{
    double spacing = p->cfg.waypoint_spacing_m;
    const int32_t m = gmmrrt_waypoint_count(total, &spacing);
    double s0 = 0.0, yaw = np > 0 ? pieces[0].yaw : 0.0;
    int32_t k = 0;
    for (int32_t j = 0; j < m - 1; ++j) {
        const double s = (double)j * spacing;
        while (k < np - 1 && s > s0 + pieces[k].len) {
            s0 += pieces[k].len;
            ++k;
        }
        if (np > 0)
            point_on(&pieces[k], fmin(s - s0, pieces[k].len), &out->x[j], &out->y[j], &yaw);
        else {
            out->x[j] = v->x[0];
            out->y[j] = v->y[0];
        }
        out->yaw[j] = yaw;
        s_at[j] = s;
    }
    double gx_, gy_;
    if (np > 0)
        point_on(&pieces[np - 1], pieces[np - 1].len, &gx_, &gy_, &yaw);
    out->x[m - 1] = v->x[v->n - 1];
    out->y[m - 1] = v->y[v->n - 1];
    out->yaw[m - 1] = yaw;
    s_at[m - 1] = total;
    out->x[0] = v->x[0];
    out->y[0] = v->y[0];
    out->num_points = m;
    return yaw;
}

/* 1 when every published chord that ends past the escape (esc_len: its length, 0 without one)
 * passes the planner's segment test: what the robot drives is what must be free. The escape's own
 * chords leave a contact by design. */
static int chords_free(const struct gmmrrt_planner *p, const gmmrrt_path_t *out, const double *s_at, double esc_len)
{
    for (int32_t j = 0; j + 1 < out->num_points; ++j)
        if (s_at[j + 1] > esc_len && !seg_free(p, out->x[j], out->y[j], out->x[j + 1], out->y[j + 1]))
            return 0;
    return 1;
}

/* Waypoints at every piece's ends: a straight piece in equal parts of at most `spacing` (parts of
 * a segment the planner's test passed, so free), an arc at exactly its own chords, the ones
 * arc_free checked (arc_vertex). Every chord is then one the planner's test passed, and the corner
 * keeps its radius: consecutive chords of the arc turn by the arc length of one of them / r.
 * Returns the number of waypoints for `spacing`. */
static int32_t count_by_pieces(const struct gmmrrt_planner *p, const piece_t *pieces, int32_t np, double spacing)
{
    int32_t m = 1;
    for (int32_t k = 0; k < np; ++k)
        m += pieces[k].r > 0.0 ? arc_chords(p, &pieces[k]) : (int32_t)fmax(1.0, ceil(pieces[k].len / spacing));
    return m;
}

/* The waypoints of count_by_pieces, at the planner's spacing or the smallest wider one that fits
 * GMMRRT_MAX_WAYPOINTS (bisection, as gmmrrt_planner_best_path); out->num_points = 0 when the arcs'
 * chords alone do not fit. Returns the final yaw. */
static double publish_by_pieces(const struct gmmrrt_planner *p, const piece_t *pieces, int32_t np,
                                const polyline_t *v, gmmrrt_path_t *out, double *s_at)
{
    double spacing = p->cfg.waypoint_spacing_m;
    if (count_by_pieces(p, pieces, np, spacing) > GMMRRT_MAX_WAYPOINTS) {
        double total = 0.0;
        for (int32_t k = 0; k < np; ++k)
            total += pieces[k].len;
        if (count_by_pieces(p, pieces, np, 2.0 * total + 1.0) > GMMRRT_MAX_WAYPOINTS) {
            out->num_points = 0;
            return 0.0;
        }
        double lo = spacing, hi = 2.0 * total + 1.0;
        for (int it = 0; it < 60 && hi > lo * (1.0 + 1e-12); ++it) {
            const double mid = 0.5 * (lo + hi);
            if (count_by_pieces(p, pieces, np, mid) > GMMRRT_MAX_WAYPOINTS)
                lo = mid;
            else
                hi = mid;
        }
        spacing = hi;
    }
    int32_t m = 1;
    double s0 = 0.0, yaw = np > 0 ? pieces[0].yaw : 0.0;
    out->x[0] = v->x[0];
    out->y[0] = v->y[0];
    out->yaw[0] = yaw;
    s_at[0] = 0.0;
    for (int32_t k = 0; k < np; ++k) {
        const piece_t *pc = &pieces[k];
        if (pc->r > 0.0) {
            const int32_t n = arc_chords(p, pc);
            /* the arc's first vertex replaces the piece's start (equal to rounding) */
            arc_vertex(pc, 0, n, &out->x[m - 1], &out->y[m - 1], &out->yaw[m - 1]);
            for (int32_t i = 1; i <= n; ++i, ++m) {
                arc_vertex(pc, i, n, &out->x[m], &out->y[m], &out->yaw[m]);
                s_at[m] = s0 + pc->len * (double)i / (double)n;
            }
        } else {
            const int32_t n = (int32_t)fmax(1.0, ceil(pc->len / spacing));
            out->yaw[m - 1] = pc->yaw;
            for (int32_t i = 1; i <= n; ++i, ++m) {
                point_on(pc, pc->len * (double)i / (double)n, &out->x[m], &out->y[m], &out->yaw[m]);
                s_at[m] = s0 + pc->len * (double)i / (double)n;
            }
        }
        s0 += pc->len;
        yaw = out->yaw[m - 1];
    }
    if (m < 2) { /* no piece: start at the goal, published as two points */
        out->x[1] = v->x[0];
        out->y[1] = v->y[0];
        out->yaw[1] = yaw;
        s_at[1] = 0.0;
        m = 2;
    }
    out->x[m - 1] = v->x[v->n - 1];
    out->y[m - 1] = v->y[v->n - 1];
    out->x[0] = v->x[0];
    out->y[0] = v->y[0];
    out->num_points = m;
    return yaw;
}

/* The escape's end (vertex e, the exit E, reached along the ray u): rather than turning on the
 * spot at E, the robot drives on into the arc of radius R that leaves the pose (E, u) and ends
 * heading straight for the next vertex Q (a Dubins turn-then-straight). It is written as a corner
 * at the virtual vertex E' = E + R tan(alpha / 2) u (alpha the arc's sweep, < pi), whose rounded
 * arc starts exactly at E; E' itself is never driven. Taken when the arc (chords of at most
 * GMMRRT_ARC_CHORD_M) and the straight on to Q are free, every person stays on the same side as
 * E -> Q, and the corner at Q still has room on that straight; otherwise the robot turns on the
 * spot at E (counted in turns_in_place), which a differential drive can and which is the only way
 * out when the goal is behind the person it leaves. Returns 1 when E' was inserted. */
static int escape_exit_arc(const struct gmmrrt_planner *p, polyline_t *v, int32_t e, double R)
{
    if (!(R > 0.0) || e <= 0 || e + 1 >= v->n || v->n >= MAXV)
        return 0;
    const double ex = v->x[e], ey = v->y[e], qx = v->x[e + 1], qy = v->y[e + 1];
    if (turn_angle(v->x[e - 1], v->y[e - 1], ex, ey, qx, qy) <= GMMRRT_STRAIGHT_RAD)
        return 0;
    const double psi = atan2(ey - v->y[e - 1], ex - v->x[e - 1]);
    const double ux = cos(psi), uy = sin(psi);
    const double s = ux * (qy - ey) - uy * (qx - ex) >= 0.0 ? 1.0 : -1.0; /* +1: Q is on the left */
    const double cx = ex - s * R * uy, cy = ey + s * R * ux;                /* the arc's centre */
    const double d = hypot(qx - cx, qy - cy);
    if (!(d > R * (1.0 + 1e-9)))
        return 0; /* Q inside the turning circle: no arc of R heads for it */
    const double theta = atan2(qy - cy, qx - cx) - s * acos(R / d); /* the tangent point T's angle */
    const double a0 = atan2(ey - cy, ex - cx);
    double alpha = fmod(s * (theta - a0), 2.0 * M_PI);
    if (alpha < 0.0)
        alpha += 2.0 * M_PI;
    if (!(alpha > GMMRRT_STRAIGHT_RAD && alpha < M_PI - 1e-3))
        return 0;
    const double tx = cx + R * cos(theta), ty = cy + R * sin(theta);
    const piece_t arc = {ex, ey, psi, R * alpha, R, cx, cy, a0, s};
    if (!arc_free(p, &arc) || !seg_free(p, tx, ty, qx, qy))
        return 0;
    double direct[GMMRRT_MAX_PEOPLE], turned[GMMRRT_MAX_PEOPLE];
    sweep_clear(p, direct);
    sweep_add(p, direct, ex, ey, qx, qy);
    sweep_clear(p, turned);
    sweep_add(p, turned, ex, ey, tx, ty); /* the chord of an arc that keeps clear of every person */
    sweep_add(p, turned, tx, ty, qx, qy);
    if (!sweep_same_side(p, direct, turned))
        return 0;
    if (e + 2 < v->n) { /* Q is a corner: its arc must fit on the straight T -> Q */
        const double need_q = corner_need(R, tx, ty, qx, qy, v->x[e + 2], v->y[e + 2]);
        if (!(need_q <= hypot(qx - tx, qy - ty)))
            return 0;
    }
    /* A hair beyond the tangent length, so that rounding never makes the corner at E' look tight. */
    const double t = R * tan(0.5 * alpha) + 1e-9;
    for (int32_t j = v->n; j > e + 1; --j) {
        v->x[j] = v->x[j - 1];
        v->y[j] = v->y[j - 1];
        v->c[j] = v->c[j - 1];
    }
    v->x[e + 1] = ex + t * ux;
    v->y[e + 1] = ey + t * uy;
    v->c[e + 1] = NAN;
    ++v->n;
    return 1;
}

static int valid_options(const gmmrrt_drive_options_t *o)
{
    return isfinite(o->min_turn_radius_m) && o->min_turn_radius_m >= 0.0 && o->min_turn_radius_m <= 100.0 &&
           (o->arrival == GMMRRT_ARRIVAL_ANY || o->arrival == GMMRRT_ARRIVAL_YAW ||
            o->arrival == GMMRRT_ARRIVAL_FACE_TARGET) &&
           isfinite(o->goal_yaw) && isfinite(o->goal_yaw_tolerance_rad) && o->goal_yaw_tolerance_rad > 0.0 &&
           o->goal_yaw_tolerance_rad <= M_PI && isfinite(o->arrival_leg_m) && o->arrival_leg_m > 0.0 &&
           o->arrival_leg_m <= 100.0 && (o->shortcut == 0 || o->shortcut == 1);
}

gmmrrt_status_t gmmrrt_planner_drivable_path(const gmmrrt_planner_t *p, const gmmrrt_drive_options_t *opt,
                                             gmmrrt_path_t *out, gmmrrt_drive_report_t *report)
{
    if (!p || !opt || !out || !valid_options(opt))
        return GMMRRT_ERR_INVALID_ARGUMENT;
    out->num_points = 0;
    out->length_m = 0.0;
    out->cost = INFINITY;
    gmmrrt_drive_report_t rep;
    memset(&rep, 0, sizeof rep);
    rep.min_walker_clearance_m = INFINITY;
    rep.arrival_met = 1;
    const gmmrrt_problem_t *pr = &p->problem;
    if (opt->arrival == GMMRRT_ARRIVAL_FACE_TARGET && p->has_problem &&
        !(pr->task == GMMRRT_TASK_APPROACH && pr->target_person >= 0))
        return GMMRRT_ERR_INVALID_ARGUMENT;
    if (!p->has_problem || p->best_goal < 0)
        return GMMRRT_NO_PATH_YET;

    polyline_t v;
    int32_t first_free;
    gmmrrt_status_t st = extract(p, &v, &first_free);
    if (st != GMMRRT_OK)
        return st;
    rep.vertices_in = v.n;
    double tree_sweep[GMMRRT_MAX_PEOPLE];
    sweep_polyline(p, v.x, v.y, v.n, tree_sweep);
    if (opt->shortcut)
        shortcut(p, &v, first_free);

    /* Arrival heading. */
    int want = opt->arrival != GMMRRT_ARRIVAL_ANY;
    double h = opt->goal_yaw;
    if (opt->arrival == GMMRRT_ARRIVAL_FACE_TARGET) {
        const gmmrrt_pose_t *t = &pr->obstacles.people[pr->target_person];
        h = atan2(t->y - pr->goal_y, t->x - pr->goal_x);
    }
    int32_t keep_from = v.n - 1; /* the goal; or the arrival leg's first point */
    if (want && v.n >= 2) {
        const double last = atan2(v.y[v.n - 1] - v.y[v.n - 2], v.x[v.n - 1] - v.x[v.n - 2]);
        if (fabs(gmmrrt_wrap_angle(last - h)) > opt->goal_yaw_tolerance_rad)
            keep_from = v.n - 1 - arrival_leg(p, opt, &v, first_free, h);
    }
    relax_tight_corners(p, &v, opt->min_turn_radius_m, first_free, keep_from);
    rep.vertices_out = v.n;
    rep.cost = 0.0;
    for (int32_t i = first_free; i + 1 < v.n; ++i)
        rep.cost += gmmrrt_edge_cost(p, v.x[i], v.y[i], v.x[i + 1], v.y[i + 1]);
    if (p->escape.active)
        escape_exit_arc(p, &v, first_free, opt->min_turn_radius_m);

    /* Corners: what each needs (R tan(phi / 2)), what it may use of its two segments (all it
     * needs when both corners of a segment fit, else a share in proportion to the needs), then
     * the pieces. */
    double need[MAXV], phi_at[MAXV];
    const double R = opt->min_turn_radius_m;
    need[0] = need[v.n - 1] = 0.0;
    phi_at[0] = phi_at[v.n - 1] = 0.0;
    for (int32_t i = 1; i < v.n - 1; ++i) {
        phi_at[i] = turn_angle(v.x[i - 1], v.y[i - 1], v.x[i], v.y[i], v.x[i + 1], v.y[i + 1]);
        /* the escape's end, when escape_exit_arc found no arc after it: chords back into the
         * contact cannot be free, so it turns in place */
        const int no_arc = R <= 0.0 || phi_at[i] <= GMMRRT_STRAIGHT_RAD || (i == first_free && first_free > 0);
        need[i] = no_arc ? 0.0 : R * tan(0.5 * phi_at[i]);
    }
    piece_t pieces[2 * MAXV];
    int32_t np = 0;
    double px = v.x[0], py = v.y[0];
    for (int32_t i = 1; i < v.n; ++i) {
        double ex = v.x[i], ey = v.y[i]; /* the straight piece ends here */
        piece_t arc = {0};
        int has_arc = 0;
        if (i < v.n - 1 && phi_at[i] > GMMRRT_STRAIGHT_RAD) {
            double r = 0.0;
            if (need[i] > 0.0) {
                const double lin = hypot(v.x[i] - v.x[i - 1], v.y[i] - v.y[i - 1]);
                const double lout = hypot(v.x[i + 1] - v.x[i], v.y[i + 1] - v.y[i]);
                const double ain = need[i - 1] + need[i] <= lin ? need[i] : lin * need[i] / (need[i - 1] + need[i]);
                const double aout =
                    need[i + 1] + need[i] <= lout ? need[i] : lout * need[i] / (need[i + 1] + need[i]);
                const double allow = fmin(ain, aout);
                r = R;
                if (need[i] > allow) {
                    r = allow / tan(0.5 * phi_at[i]);
                    rep.tight_turns++;
                }
            }
            const double phi = phi_at[i];
            const double yin = atan2(v.y[i] - v.y[i - 1], v.x[i] - v.x[i - 1]);
            const double yout = atan2(v.y[i + 1] - v.y[i], v.x[i + 1] - v.x[i]);
            const double dir = gmmrrt_wrap_angle(yout - yin) > 0.0 ? 1.0 : -1.0;
            int counted_tight = r < R;
            while (r >= GMMRRT_MIN_ARC_RADIUS_M) {
                const double t = r * tan(0.5 * phi);
                const double ax = v.x[i] - t * cos(yin), ay = v.y[i] - t * sin(yin);
                arc = (piece_t){ax, ay, yin, r * phi, r, ax - dir * r * sin(yin), ay + dir * r * cos(yin), 0.0, dir};
                arc.a0 = atan2(ay - arc.cy, ax - arc.cx);
                if (arc_free(p, &arc)) {
                    has_arc = 1;
                    ex = ax;
                    ey = ay;
                    break;
                }
                r *= 0.5;
                if (!counted_tight) {
                    rep.tight_turns++;
                    counted_tight = 1;
                }
            }
            if (!has_arc)
                rep.turns_in_place++;
            else if (1.0 / r > rep.max_curvature)
                rep.max_curvature = 1.0 / r;
        }
        const double len = hypot(ex - px, ey - py);
        if (len > 1e-12)
            pieces[np++] = (piece_t){px, py, atan2(ey - py, ex - px), len, 0.0, 0.0, 0.0, 0.0, 0.0};
        if (has_arc) {
            pieces[np++] = arc;
            const double yout = atan2(v.y[i + 1] - v.y[i], v.x[i + 1] - v.x[i]);
            const double t = arc.r * tan(0.5 * arc.len / arc.r);
            px = v.x[i] + t * cos(yout);
            py = v.y[i] + t * sin(yout);
        } else {
            px = ex;
            py = ey;
        }
    }

    /* Waypoints: at equal arc length; when a chord of those is not free, at the pieces' own
     * chords (publish_by_pieces). */
    double s_at[GMMRRT_MAX_WAYPOINTS];
    double total = 0.0;
    for (int32_t k = 0; k < np; ++k)
        total += pieces[k].len;
    const double esc_len = p->escape.active ? p->escape.length_m : 0.0;
    double yaw = publish_by_arc_length(p, pieces, np, total, &v, out, s_at);
    if (!chords_free(p, out, s_at, esc_len)) {
        yaw = publish_by_pieces(p, pieces, np, &v, out, s_at);
        if (out->num_points == 0)
            return GMMRRT_ERR_BUFFER_TOO_SMALL;
    }
    const int32_t m = out->num_points;
    out->length_m = total;
    out->cost = rep.cost;

    /* The output against the tree path, person by person: every step above kept the sides, and the
     * arcs stay inside their corners' free chords; this states it for what is published. */
    double out_sweep[GMMRRT_MAX_PEOPLE];
    sweep_polyline(p, out->x, out->y, m, out_sweep);
    rep.side_kept = sweep_same_side(p, tree_sweep, out_sweep);
    rep.arrival_yaw = yaw;
    if (want) {
        rep.arrival_error_rad = fabs(gmmrrt_wrap_angle(yaw - h));
        rep.arrival_met = rep.arrival_error_rad <= opt->goal_yaw_tolerance_rad;
    }
    /* Walkers at each waypoint's own time (the escape's part is leaving a contact by design). */
    if (p->walkers.count > 0) {
        for (int32_t j = 0; j < m; ++j) {
            if (s_at[j] < esc_len)
                continue;
            const double c =
                gmmrrt_walkers_clearance_at(&p->walkers, out->x[j], out->y[j], s_at[j] / p->walkers.speed_m_s);
            if (c < rep.min_walker_clearance_m)
                rep.min_walker_clearance_m = c;
        }
        rep.walker_conflict = rep.min_walker_clearance_m <= 0.0;
    }
    /* An escape says so first (its end turns on the spot by design); otherwise a path with a corner
     * tighter than the radius is flagged, never passed off as drivable. R = 0 allows turning in place. */
    rep.status = p->escape.active                                         ? GMMRRT_ESCAPE
                 : R > 0.0 && (rep.tight_turns > 0 || rep.turns_in_place > 0) ? GMMRRT_TIGHT_TURNS
                                                                             : GMMRRT_OK;
    if (report)
        *report = rep;
    return rep.status;
}
