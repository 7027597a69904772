/*
 * moving_people.c - walking people for the planner (planner.h, gmmrrt_problem_t.person_vx/vy).
 *
 * A person whose speed is below GMMRRT_STANDING_SPEED_M_S is standing: they stay in the
 * collision world (collision.c) exactly as before, and the learned models apply to them as to
 * the demonstrations (people standing while the robot passes or approaches). Faster people are
 * walkers: taken out of the world and predicted with constant velocity,
 *     P(t) = P(0) + v t,  0 <= t <= horizon
 * (no prediction beyond it: a walker is not an obstacle to points the robot cannot reach before
 * the horizon; the daemon replans long before then, and holding them at the horizon would wall
 * off the map with phantom people in a crowd).
 *
 * When is the robot at a point q? Along a path it arrives at t(q) = s(q) / speed, s the arc
 * length, which only the finished path knows. In the search a tree point is tested against the
 * walker over the window
 *     t in [ |q - root| / speed,  GMMRRT_WALKER_SLACK |q - root| / speed + GMMRRT_WALKER_SLACK_S ]
 * (the straight distance bounds s from below; paths are rarely more than half again longer than
 * it), i.e. against the capsule the walker sweeps over that window (a segment in pieces of
 * GMMRRT_WALKER_PIECE_M, each with the window of its points), kept beyond contact by
 * GMMRRT_WALKER_COMFORT_M x min(1, t_lo / GMMRRT_WALKER_COMFORT_RAMP_S): the prediction is a guess
 * that grows less certain with time, while at t = 0 only contact is a collision (so passing close
 * to a walker right now is not taken for a start in collision).
 *
 * Social cost of a walker (gmmrrt_walkers_cost; added to the task cost term of the edge cost,
 * objective.c): the learned models are about standing people, so a walker's cost is geometry,
 * not learned. At a point x the walker is taken where they will be when the robot gets there,
 * P(t), t = |x - root| / speed (the search's earliest time), and x is placed in their motion
 * frame (along = ahead of P(t), lat = sideways); L = walker speed x GMMRRT_WALKER_LOOKAHEAD_S:
 *     ahead  (0 <= along <= L):  exp(-lat^2 / (2 GMMRRT_WALKER_LANE_M^2))
 *     beyond (along > L):        the same times exp(-(along - L)^2 / (2 GMMRRT_WALKER_LANE_M^2))
 *     behind (along < 0):        exp(-(along^2 + lat^2) / (2 GMMRRT_WALKER_WAKE_M^2))
 * so crossing the stretch they are about to walk costs up to 1 per metre (times w_task), and
 * passing behind them only close to their back. A segment uses the window of
 * its points together. The drivable path (drivable.h) then checks every waypoint against where
 * the walker is at the waypoint's exact time and reports any conflict.
 */
#include <math.h>
#include <string.h>

#include "planner_internal.h"

#define GMMRRT_WALKER_SLACK 1.5
#define GMMRRT_WALKER_SLACK_S 0.5
#define GMMRRT_WALKER_EDGE_MARGIN_M 1e-3 /* as collision.c's edge margin */
#define GMMRRT_WALKER_COMFORT_RAMP_S 1.0
#define GMMRRT_WALKER_PIECE_M 0.5 /* segments are tested in pieces this long */

gmmrrt_status_t gmmrrt_walkers_prepare(struct gmmrrt_planner *p, const gmmrrt_problem_t *pr,
                                       const gmmrrt_obstacle_set_t **world_set)
{
    gmmrrt_walkers_t *w = &p->walkers;
    const gmmrrt_obstacle_set_t *o = &pr->obstacles;
    w->count = 0;
    *world_set = o;
    if (!isfinite(pr->nominal_speed_m_s) || pr->nominal_speed_m_s < 0.0 || pr->nominal_speed_m_s > 10.0 ||
        !isfinite(pr->prediction_horizon_s) || pr->prediction_horizon_s < 0.0 || pr->prediction_horizon_s > 60.0)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    if (o->num_people < 0 || o->num_people > GMMRRT_MAX_PEOPLE)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    for (int32_t i = 0; i < o->num_people; ++i) {
        const double vx = pr->person_vx[i], vy = pr->person_vy[i];
        if (!isfinite(vx) || !isfinite(vy))
            return GMMRRT_ERR_INVALID_ARGUMENT;
        /* A standing person (the usual case) skips libm's hypot, whose code a cold set-up would fetch. */
        const double speed = (vx == 0.0 && vy == 0.0) ? 0.0 : hypot(vx, vy);
        if (speed > GMMRRT_MAX_PERSON_SPEED_M_S)
            return GMMRRT_ERR_INVALID_ARGUMENT;
        if (!(speed >= GMMRRT_STANDING_SPEED_M_S) || !(p->cfg.person_radius_m > 0.0))
            continue;
        w->person[w->count] = i;
        w->x[w->count] = o->people[i].x;
        w->y[w->count] = o->people[i].y;
        w->vx[w->count] = vx;
        w->vy[w->count] = vy;
        w->count++;
    }
    w->speed_m_s = pr->nominal_speed_m_s > 0.0 ? pr->nominal_speed_m_s : GMMRRT_DEFAULT_NOMINAL_SPEED_M_S;
    w->horizon_s = pr->prediction_horizon_s > 0.0 ? pr->prediction_horizon_s : GMMRRT_DEFAULT_PREDICTION_HORIZON_S;
    w->reach_m = p->cfg.robot_radius_m + p->cfg.person_radius_m + GMMRRT_WALKER_EDGE_MARGIN_M; /* + comfort(t) */
    w->root_x = pr->start_x;
    w->root_y = pr->start_y;
    if (w->count == 0)
        return GMMRRT_OK;
    /* The world without the walkers (standing people keep their indices' order). */
    gmmrrt_obstacle_set_t *ws = &p->world_obstacles;
    if (o->num_circles < 0 || o->num_circles > GMMRRT_MAX_CIRCLES || o->num_boxes < 0 || o->num_boxes > GMMRRT_MAX_BOXES)
        return GMMRRT_ERR_INVALID_ARGUMENT; /* checked here too: the copies below come before the world's checks */
    ws->bounds = o->bounds;
    ws->raster = o->raster; /* the map stays a wall while people walk */
    ws->num_circles = o->num_circles;
    memcpy(ws->circles, o->circles, (size_t)o->num_circles * sizeof o->circles[0]);
    ws->num_boxes = o->num_boxes;
    memcpy(ws->boxes, o->boxes, (size_t)o->num_boxes * sizeof o->boxes[0]);
    ws->num_people = 0;
    for (int32_t i = 0, k = 0; i < o->num_people; ++i) {
        if (k < w->count && w->person[k] == i) {
            ++k;
            continue;
        }
        ws->people[ws->num_people++] = o->people[i];
    }
    *world_set = ws;
    return GMMRRT_OK;
}

/* Squared distance between segments a0-a1 and b0-b1 (Ericson, Real-Time Collision Detection 5.1.9). */
static double segment_segment_d2(double ax, double ay, double bx, double by, double cx, double cy, double dx,
                                 double dy)
{
    const double d1x = bx - ax, d1y = by - ay, d2x = dx - cx, d2y = dy - cy, rx = ax - cx, ry = ay - cy;
    const double a = d1x * d1x + d1y * d1y, e = d2x * d2x + d2y * d2y, f = d2x * rx + d2y * ry;
    double s, t;
    if (a <= 1e-18 && e <= 1e-18)
        return rx * rx + ry * ry;
    if (a <= 1e-18) {
        s = 0.0;
        t = fmin(fmax(f / e, 0.0), 1.0);
    } else {
        const double c = d1x * rx + d1y * ry;
        if (e <= 1e-18) {
            t = 0.0;
            s = fmin(fmax(-c / a, 0.0), 1.0);
        } else {
            const double b = d1x * d2x + d1y * d2y, den = a * e - b * b;
            s = den > 0.0 ? fmin(fmax((b * f - c * e) / den, 0.0), 1.0) : 0.0;
            t = (b * s + f) / e;
            if (t < 0.0) {
                t = 0.0;
                s = fmin(fmax(-c / a, 0.0), 1.0);
            } else if (t > 1.0) {
                t = 1.0;
                s = fmin(fmax((b - c) / a, 0.0), 1.0);
            }
        }
    }
    const double ex = ax + d1x * s - (cx + d2x * t), ey = ay + d1y * s - (cy + d2y * t);
    return ex * ex + ey * ey;
}

/* 1 when the robot segment (x0, y0)-(x1, y1) keeps clear of every walker over the time window
 * [t_lo, t_hi] (s). */
static int clear_over(const gmmrrt_walkers_t *w, double x0, double y0, double x1, double y1, double t_lo,
                      double t_hi)
{
    if (t_lo > w->horizon_s)
        return 1; /* beyond the horizon nothing is known; the next cycle's plan will see them */
    const double a = t_lo, b = fmin(t_hi, w->horizon_s);
    const double r = w->reach_m + GMMRRT_WALKER_COMFORT_M * fmin(1.0, t_lo / GMMRRT_WALKER_COMFORT_RAMP_S);
    const double r2 = r * r;
    for (int32_t k = 0; k < w->count; ++k) {
        const double px0 = w->x[k] + w->vx[k] * a, py0 = w->y[k] + w->vy[k] * a;
        const double px1 = w->x[k] + w->vx[k] * b, py1 = w->y[k] + w->vy[k] * b;
        if (segment_segment_d2(x0, y0, x1, y1, px0, py0, px1, py1) <= r2)
            return 0;
    }
    return 1;
}

int gmmrrt_walkers_point_free(const gmmrrt_walkers_t *w, double x, double y)
{
    const double d = hypot(x - w->root_x, y - w->root_y);
    return clear_over(w, x, y, x, y, d / w->speed_m_s, GMMRRT_WALKER_SLACK * d / w->speed_m_s + GMMRRT_WALKER_SLACK_S);
}

/* One piece: the nearest point to the root bounds the earliest time, the farther end the latest. */
static int piece_free(const gmmrrt_walkers_t *w, double x0, double y0, double x1, double y1)
{
    const double vx = x1 - x0, vy = y1 - y0, l2 = vx * vx + vy * vy;
    double t = l2 > 0.0 ? ((w->root_x - x0) * vx + (w->root_y - y0) * vy) / l2 : 0.0;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    const double dmin = hypot(x0 + t * vx - w->root_x, y0 + t * vy - w->root_y);
    const double dmax = fmax(hypot(x0 - w->root_x, y0 - w->root_y), hypot(x1 - w->root_x, y1 - w->root_y));
    return clear_over(w, x0, y0, x1, y1, dmin / w->speed_m_s,
                      GMMRRT_WALKER_SLACK * dmax / w->speed_m_s + GMMRRT_WALKER_SLACK_S);
}

int gmmrrt_walkers_segment_free(const gmmrrt_walkers_t *w, double x0, double y0, double x1, double y1)
{
    /* In pieces of at most GMMRRT_WALKER_PIECE_M, each with its own (narrower) time window. */
    const double len = hypot(x1 - x0, y1 - y0);
    const int32_t n = len > GMMRRT_WALKER_PIECE_M ? (int32_t)ceil(len / GMMRRT_WALKER_PIECE_M) : 1;
    for (int32_t i = 0; i < n; ++i) {
        const double a = (double)i / n, b = (double)(i + 1) / n;
        if (!piece_free(w, x0 + a * (x1 - x0), y0 + a * (y1 - y0), x0 + b * (x1 - x0), y0 + b * (y1 - y0)))
            return 0;
    }
    return 1;
}

double gmmrrt_walkers_clearance_at(const gmmrrt_walkers_t *w, double x, double y, double t_s)
{
    if (t_s > w->horizon_s)
        return INFINITY; /* as the search: no prediction beyond the horizon */
    const double t = fmax(t_s, 0.0);
    double best = INFINITY;
    for (int32_t k = 0; k < w->count; ++k) {
        const double d = hypot(x - (w->x[k] + w->vx[k] * t), y - (w->y[k] + w->vy[k] * t));
        if (d < best)
            best = d;
    }
    return best - (w->reach_m - GMMRRT_WALKER_EDGE_MARGIN_M); /* to contact */
}

/* Width (sigma, m) of the lane ahead of a walker and of the small wake behind them. */
#define GMMRRT_WALKER_LANE_M 0.6
#define GMMRRT_WALKER_WAKE_M 0.3
/* How far ahead (s of walking) a walker's lane reaches. */
#define GMMRRT_WALKER_LOOKAHEAD_S 2.0

static double walker_cost_at(const gmmrrt_walkers_t *w, int32_t k, double x, double y)
{
    const double speed = hypot(w->vx[k], w->vy[k]);
    const double ux = w->vx[k] / speed, uy = w->vy[k] / speed;
    const double t = fmin(hypot(x - w->root_x, y - w->root_y) / w->speed_m_s, w->horizon_s);
    const double dx = x - (w->x[k] + w->vx[k] * t), dy = y - (w->y[k] + w->vy[k] * t);
    const double along = dx * ux + dy * uy, lat = -dx * uy + dy * ux;
    const double reach = speed * GMMRRT_WALKER_LOOKAHEAD_S;
    const double l2 = 2.0 * GMMRRT_WALKER_LANE_M * GMMRRT_WALKER_LANE_M;
    if (along < 0.0)
        return exp(-(along * along + lat * lat) / (2.0 * GMMRRT_WALKER_WAKE_M * GMMRRT_WALKER_WAKE_M));
    const double beyond = along > reach ? along - reach : 0.0;
    return exp(-(lat * lat + beyond * beyond) / l2);
}

double gmmrrt_walkers_cost(const gmmrrt_walkers_t *w, double x0, double y0, double x1, double y1, double resolution_m)
{
    const double len = hypot(x1 - x0, y1 - y0);
    if (w->count == 0 || len == 0.0)
        return 0.0;
    /* Composite midpoint rule, as the task cost's quadrature (objective.c). */
    double n = ceil(len / resolution_m);
    if (n < 1.0)
        n = 1.0;
    double sum = 0.0;
    for (int32_t i = 0; i < (int32_t)n; ++i) {
        const double t = ((double)i + 0.5) / n;
        const double x = x0 + t * (x1 - x0), y = y0 + t * (y1 - y0);
        double c = 0.0;
        for (int32_t k = 0; k < w->count; ++k) {
            const double ck = walker_cost_at(w, k, x, y);
            if (ck > c)
                c = ck;
        }
        sum += c;
    }
    return sum * len / n;
}
