/*
 * escape.c - the way out when the robot's start is inside a person's disc or an inflated
 * obstacle (planner.h, GMMRRT_ESCAPE): a person stepped close, or a follower cut a corner. The
 * planner is then not refused; the tree is rooted at the nearest free point that can be reached
 * by a straight motion along which the exact clearance never decreases, and the drivable path
 * (drivable.h) starts with that motion.
 *
 * Clearance here is the exact signed distance from the robot disc to each circle, box and
 * person (negative = penetration), written out analytically: FCL's penetration query allocates,
 * and set_problem must not (tests/unit/planner/test_alloc.c); and to the map's blocked cells, as
 * the collision world measures it (gmmrrt_world_map_clearance), so a ray never runs into or
 * through a wall of the map or of the scans. Walking people count where they are now (t = 0).
 * "Free" is the planner's own test (gmmrrt_world_point_free plus the walking people), so the exit
 * is a valid tree root under the same clearance rule as every node.
 *
 * Search: GMMRRT_ESCAPE_DIRECTIONS rays from the start, marched in GMMRRT_ESCAPE_STEP_M steps
 * up to GMMRRT_ESCAPE_MAX_M; a ray is usable while the clearance does not fall (or is already
 * positive: the grid's conservative margin is not a real contact); the shortest usable ray to a
 * free point wins (first direction on ties: deterministic). No usable ray: frozen, with the
 * reason.
 */
#include <math.h>
#include <stdio.h>

#include "planner_internal.h"

#define GMMRRT_ESCAPE_DIRECTIONS 72 /* 5 degrees apart */
#define GMMRRT_ESCAPE_STEP_M 0.01
#define GMMRRT_ESCAPE_MAX_M 5.0 /* deeper than this is a map or tracking error, not a step */
/* Past the first free point, so the root's first edges keep the edge margin of collision.c. */
#define GMMRRT_ESCAPE_MARGIN_M 0.03
/* How far past the robot's radius the map's clearance is measured exactly (above it the value is
 * capped, which decides nothing: a ray only stops on a clearance <= 0, and an exit this far from
 * the map keeps its margin). Bounds the brute-force cells per probe. */
#define GMMRRT_ESCAPE_MAP_REACH_M 0.1
/* The kind code of the map in gmmrrt_escape_signed_clearance's `what`. */
#define GMMRRT_ESCAPE_MAP 3000

/* Signed distance from point (x, y) to an oriented box (negative inside). */
static double box_signed_distance(const gmmrrt_box_t *b, double x, double y)
{
    const double c = cos(b->yaw), s = sin(b->yaw);
    const double dx = x - b->x, dy = y - b->y;
    const double lx = fabs(dx * c + dy * s) - 0.5 * b->width_m;
    const double ly = fabs(-dx * s + dy * c) - 0.5 * b->height_m;
    const double ox = lx > 0.0 ? lx : 0.0, oy = ly > 0.0 ? ly : 0.0;
    const double inside = lx > ly ? lx : ly;
    return sqrt(ox * ox + oy * oy) + (inside < 0.0 ? inside : 0.0);
}

double gmmrrt_escape_signed_clearance(const struct gmmrrt_planner *p, const gmmrrt_obstacle_set_t *o, double x,
                                      double y, double bound_m, int32_t *what)
{
    const double r = p->cfg.robot_radius_m;
    double best = INFINITY;
    int32_t kind = -1;
    for (int32_t k = 0; k < o->num_circles; ++k) {
        const double d = hypot(x - o->circles[k].x, y - o->circles[k].y) - o->circles[k].radius_m - r;
        if (d < best) {
            best = d;
            kind = k; /* circles 0.., boxes 1000.., people 2000.., the map 3000 */
        }
    }
    for (int32_t k = 0; k < o->num_boxes; ++k) {
        const double d = box_signed_distance(&o->boxes[k], x, y) - r;
        if (d < best) {
            best = d;
            kind = 1000 + k;
        }
    }
    if (p->cfg.person_radius_m > 0.0)
        for (int32_t k = 0; k < o->num_people; ++k) {
            const double d = hypot(x - o->people[k].x, y - o->people[k].y) - p->cfg.person_radius_m - r;
            if (d < best) {
                best = d;
                kind = 2000 + k;
            }
        }
    /* The map matters only below the shapes' clearance and the caller's bound: its brute-force
     * search looks no farther (inside a wall, a few cells instead of a disc of them). A map value
     * at or beyond that reach comes back capped there and cannot be the minimum; a reach <= 0
     * (deep in a shape: the map is never below -r) skips it. */
    const double reach = fmin(r + GMMRRT_ESCAPE_MAP_REACH_M, fmin(best, bound_m) + r + 1e-9);
    if (reach > 0.0) {
        const double dm = gmmrrt_world_map_clearance(p->world, x, y, reach);
        if (dm < best) { /* +inf without a map: never */
            best = dm;
            kind = GMMRRT_ESCAPE_MAP;
        }
    }
    if (what)
        *what = kind;
    return best;
}

static void name_shape(char *buf, size_t cap, int32_t what)
{
    if (what == GMMRRT_ESCAPE_MAP)
        snprintf(buf, cap, "the map");
    else if (what >= 2000)
        snprintf(buf, cap, "person %d", (int)(what - 2000));
    else if (what >= 1000)
        snprintf(buf, cap, "box obstacle %d", (int)(what - 1000));
    else if (what >= 0)
        snprintf(buf, cap, "circle obstacle %d", (int)what);
    else
        snprintf(buf, cap, "the grid's margin");
}

gmmrrt_status_t gmmrrt_escape_find(struct gmmrrt_planner *p, const gmmrrt_problem_t *pr, double *exit_x,
                                   double *exit_y)
{
    gmmrrt_escape_t *e = &p->escape;
    const gmmrrt_obstacle_set_t *o = &pr->obstacles;
    const double sx = pr->start_x, sy = pr->start_y;
    int32_t what;
    const double c0 = gmmrrt_escape_signed_clearance(p, o, sx, sy, INFINITY, &what);
    char shape[48];
    name_shape(shape, sizeof shape, what);
    e->start_x = sx;
    e->start_y = sy;
    e->start_clearance_m = c0;
    /* Shortest way out; among rays of the same length (the 1 cm steps make near neighbours tie)
     * the one that gains the most clearance, i.e. the steepest ascent. */
    double best_len = INFINITY, best_dir = 0.0, best_gain = -INFINITY;
    for (int32_t k = 0; k < GMMRRT_ESCAPE_DIRECTIONS; ++k) {
        const double a = 2.0 * M_PI * (double)k / GMMRRT_ESCAPE_DIRECTIONS;
        const double ux = cos(a), uy = sin(a);
        double prev = c0;
        for (double s = GMMRRT_ESCAPE_STEP_M; s <= GMMRRT_ESCAPE_MAX_M && s + GMMRRT_ESCAPE_MARGIN_M <= best_len + 1e-9;
             s += GMMRRT_ESCAPE_STEP_M) {
            const double x = sx + s * ux, y = sy + s * uy;
            /* Clearance is 1-Lipschitz: a probe is at most the last one plus the distance moved. */
            const double c = gmmrrt_escape_signed_clearance(p, o, x, y, prev + GMMRRT_ESCAPE_STEP_M, NULL);
            if (c < prev - 1e-12 && c <= 0.0)
                break; /* this way the robot would go deeper into something */
            prev = c;
            const double xm = sx + (s + GMMRRT_ESCAPE_MARGIN_M) * ux, ym = sy + (s + GMMRRT_ESCAPE_MARGIN_M) * uy;
            if (!gmmrrt_planner_point_free(p, x, y) || !gmmrrt_planner_point_free(p, xm, ym) ||
                !gmmrrt_world_point_leavable(p->world, xm, ym))
                continue;
            const double cm = gmmrrt_escape_signed_clearance(p, o, xm, ym, c + GMMRRT_ESCAPE_MARGIN_M, NULL);
            if (cm >= c) {
                const double len = s + GMMRRT_ESCAPE_MARGIN_M;
                if (len < best_len - 1e-9 || cm > best_gain) {
                    best_len = len;
                    best_dir = a;
                    best_gain = cm;
                }
                break;
            }
        }
    }
    /* A start outside every shape but within the edge margin of one (rrtstar.c) is said as such. */
    char where[96];
    if (c0 < 0.0)
        snprintf(where, sizeof where, "start %.3f m inside %s", -c0, shape);
    else
        snprintf(where, sizeof where, "start %.4f m from %s, within the edge margin", c0, shape);
    if (!isfinite(best_len)) {
        e->active = 0;
        snprintf(e->freeze_reason, sizeof e->freeze_reason,
                 "%s; no straight motion within %.1f m keeps raising the clearance to a free point",
                 where, GMMRRT_ESCAPE_MAX_M);
        return GMMRRT_ERR_FROZEN;
    }
    e->active = 1;
    e->exit_x = sx + best_len * cos(best_dir);
    e->exit_y = sy + best_len * sin(best_dir);
    e->length_m = best_len;
    snprintf(e->freeze_reason, sizeof e->freeze_reason, "%s: escaping %.2f m", where, best_len);
    *exit_x = e->exit_x;
    *exit_y = e->exit_y;
    return GMMRRT_ESCAPE;
}
