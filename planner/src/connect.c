/*
 * connect.c - the connect phase of the planner (config.h, connect_first): until a first path
 * exists, RRT-Connect (Kuffner & LaValle 2000, as OMPL's RRTConnect): a tree from the start and
 * one from the goal take turns; the one whose turn it is extends one step (at most step_m)
 * towards the iteration's sample, and the other then extends greedily towards that new node,
 * step after step, until it reaches it (the trees are joined) or an edge is blocked. A tree's
 * step starts from the first of its GMMRRT_CONNECT_TRIES nearest nodes whose step is free (not
 * the nearest alone; see that constant). Once
 * joined, the path start -> goal is inserted into the RRT* tree as a warm start
 * (gmmrrt_planner_seed_path: each edge re-checked, its cost-to-come from the planner's own edge
 * cost, the goal node a solution) and RRT* goes on from that tree, so the anytime search keeps
 * its sampling, cost and rewiring (Karaman & Frazzoli 2011; the paper, Sect. 4) and only the time
 * to the first path changes.
 *
 * Why: RRT*'s first path needs a sample near the goal side to join a tree that grows from the
 * start alone, each iteration paying for a near set; the greedy connection reaches across the
 * free space between two trees in a few collision checks, and a narrow passage is found from
 * whichever side reaches it first.
 *
 * The samples are the planner's own (gmmrrt_sample: the mixture, uniform or the goal, by the
 * configured biases), one per iteration as the RRT* loop counts them. Every edge of both trees
 * is checked with the tree's one predicate (gmmrrt_planner_edge_allowed); the goal tree's edges
 * are checked from the goal side, which gives the same answer (the segment test is symmetric,
 * and so is the preferred side's ray). Memory: one array of GMMRRT_CONNECT_MAX_NODES points with
 * parents for both trees (the start's from entry 0 up, the goal's from the last entry down) and
 * one for the joined path, inside the planner block; when it is full, or after
 * cfg.connect_max_iterations iterations without a path, the phase ends and RRT* searches alone
 * from the root (the cap bounds the phase's work, which grows with its trees). Nearest nodes by a linear scan: the trees stay small while no path exists on
 * the problems this phase is for, and the scan is a tight loop over 16-byte points.
 * Not used with walking people (gmmrrt_connect_reset says why) nor by gmm-rrt (a baseline whose
 * staged sampling is the point).
 *
 * Dynamic domains on the further tries (cfg.connect_domains; after Yershova, Jaillet, Simeon and
 * LaValle, "Dynamic-Domain RRTs", ICRA 2005): a node whose step was once blocked stands at the border of the free space
 * (a wall, or a room's side), and a target far from it mostly lies behind that border. Such a
 * node is tried for a target beyond one step (step_m) only when it is the tree's nearest node,
 * the try RRT-Connect itself makes; as a further try (GMMRRT_CONNECT_TRIES) it is skipped without
 * a collision test. Unlike their RRT the nearest node is never restricted, the domain's radius
 * is the step itself and does not adapt, and the flag is never cleared, so there is no constant to
 * set: a blocked node still takes every target its one unsteered edge reaches. Why: on a floor plan most
 * of the phase's time went to edges from nodes in a room towards targets behind its walls, and
 * tested again and again from the same nodes; docs/planner.md has the measurement.
 */
#include <math.h>
#include <stdint.h>

#include "block_layout.h"
#include "planner_internal.h"

enum { TRAPPED, ADVANCED, REACHED, FULL };

size_t gmmrrt_connect_mem_size(const gmmrrt_planner_config_t *cfg)
{
    if (!cfg || !cfg->connect_first || cfg->planner == GMMRRT_PLANNER_GMM_RRT)
        return 0;
    const size_t n = GMMRRT_CONNECT_MAX_NODES;
    return gmmrrt_align8(n * sizeof(gmmrrt_xy_t)) + gmmrrt_align8(n * sizeof(int32_t)) + gmmrrt_align8(n) +
           2 * gmmrrt_align8(n * sizeof(double));
}

void gmmrrt_connect_bind(struct gmmrrt_planner *p, void *mem)
{
    gmmrrt_connect_t *c = &p->connect;
    c->state = GMMRRT_CONNECT_OFF;
    c->n_start = c->n_goal = 0;
    c->turn = 0;
    if (gmmrrt_connect_mem_size(&p->cfg) == 0) {
        c->xy = NULL;
        c->parent = NULL;
        c->blocked_once = NULL;
        c->path_x = c->path_y = NULL;
        return;
    }
    const size_t n = GMMRRT_CONNECT_MAX_NODES;
    uint8_t *base = mem;
    size_t off = 0;
    c->xy = (gmmrrt_xy_t *)(void *)(base + gmmrrt_block_take(&off, n * sizeof(gmmrrt_xy_t)));
    c->parent = (int32_t *)(void *)(base + gmmrrt_block_take(&off, n * sizeof(int32_t)));
    c->blocked_once = base + gmmrrt_block_take(&off, n);
    c->path_x = (double *)(void *)(base + gmmrrt_block_take(&off, n * sizeof(double)));
    c->path_y = (double *)(void *)(base + gmmrrt_block_take(&off, n * sizeof(double)));
}

void gmmrrt_connect_reset(struct gmmrrt_planner *p)
{
    gmmrrt_connect_t *c = &p->connect;
    c->turn = 0;
    c->n_start = c->n_goal = 0;
    c->iterations = 0;
    c->edge_tests = 0;
    c->state = GMMRRT_CONNECT_OFF;
    /* Walking people are tested against a time window from each point's straight distance to
     * the root (moving_people.c), which holds for the near-straight paths RRT* converges to but
     * not for a connect path's detours: with walkers RRT* searches alone. */
    if (!c->xy || p->walkers.count > 0)
        return;
    const int32_t top = GMMRRT_CONNECT_MAX_NODES - 1;
    c->xy[0] = p->pool.xy[0]; /* the RRT* tree's root: the start, or the escape's exit */
    c->parent[0] = -1;
    c->blocked_once[0] = 0;
    c->xy[top].x = p->problem.goal_x;
    c->xy[top].y = p->problem.goal_y;
    c->parent[top] = -1;
    c->blocked_once[top] = 0;
    c->n_start = c->n_goal = 1;
    c->state = GMMRRT_CONNECT_GROWING;
}

/* A tree extends from the first of its GMMRRT_CONNECT_TRIES nearest nodes (nearest first)
 * whose step towards the target is free, as RRT*'s choose-parent looks through a near set
 * rather than at the nearest node alone. Why: in a building the nearest node is often behind a
 * wall (a room's node beside the corridor it cannot see), and one blocked nearest node spent the
 * whole sample; with four tries the floor plan's first path takes about 0.4x the iterations and
 * problem C's slowest seeds a tenth (docs/planner.md). */
#define GMMRRT_CONNECT_TRIES 4

/* The up to GMMRRT_CONNECT_TRIES nodes of entries [lo, hi) nearest to (x, y), nearest first
 * (of equally near ones the lower index first), into idx; returns how many. */
static int nearest_few(const gmmrrt_xy_t *xy, int32_t lo, int32_t hi, double x, double y, int32_t *idx)
{
    double d2s[GMMRRT_CONNECT_TRIES];
    int m = 0;
    for (int32_t i = lo; i < hi; ++i) {
        const double dx = xy[i].x - x, dy = xy[i].y - y;
        const double d2 = dx * dx + dy * dy;
        if (m == GMMRRT_CONNECT_TRIES && !(d2 < d2s[m - 1]))
            continue;
        int j = m < GMMRRT_CONNECT_TRIES ? m++ : m - 1;
        for (; j > 0 && d2s[j - 1] > d2; --j) {
            d2s[j] = d2s[j - 1];
            idx[j] = idx[j - 1];
        }
        d2s[j] = d2;
        idx[j] = i;
    }
    return m;
}

/* One step of the start tree (goal_tree 0) or the goal tree (1) from its node n towards
 * (x, y), a free point, at most step_m. REACHED with *out the node at (x, y) (added, or n when
 * it is there), ADVANCED with *out the node added short of it, TRAPPED when the step is
 * blocked, or when n is only a further try (nearest 0) outside its dynamic domain (the file
 * comment), FULL when the array has no room. */
static int extend_from(struct gmmrrt_planner *p, int goal_tree, int32_t n, double x, double y, int nearest,
                       int32_t *out)
{
    gmmrrt_connect_t *c = &p->connect;
    const double nx = c->xy[n].x, ny = c->xy[n].y;
    const double dx = x - nx, dy = y - ny;
    const double dist = sqrt(dx * dx + dy * dy); /* plain sqrt: map coordinates */
    if (dist <= GMMRRT_SAME_POINT_M) {
        *out = n;
        return REACHED;
    }
    if (c->n_start + c->n_goal >= GMMRRT_CONNECT_MAX_NODES)
        return FULL;
    const int steered = dist > p->cfg.step_m;
    if (steered && !nearest && c->blocked_once[n] && p->cfg.connect_domains)
        return TRAPPED;
    double qx = x, qy = y;
    if (steered) {
        qx = nx + dx * (p->cfg.step_m / dist);
        qy = ny + dy * (p->cfg.step_m / dist);
    }
    /* No separate point test of the steered end: the edge test refuses every edge whose end the
     * point test refuses (its test of the ends is the same clearance bound, or the closed forms and
     * the people with the edge margin added: stricter), so that test would only compute the end's
     * bound a second time. One exception, up to the exact test's margin (EXACT_MARGIN_M, 1e-9 m):
     * on a map with circles or boxes the edge's end bound stops at the map's, and the walk's
     * clearance proof then covers the end with exact clearance >= 0 where the point test asks
     * for > 1e-9 m. Within that nanometre the trees could differ; nowhere else. */
    ++c->edge_tests;
    if (!gmmrrt_planner_edge_allowed(p, nx, ny, qx, qy)) {
        c->blocked_once[n] = 1;
        return TRAPPED;
    }
    const int32_t i = goal_tree ? GMMRRT_CONNECT_MAX_NODES - 1 - c->n_goal++ : c->n_start++;
    c->xy[i].x = qx;
    c->xy[i].y = qy;
    c->parent[i] = n;
    c->blocked_once[i] = 0;
    *out = i;
    return steered ? ADVANCED : REACHED;
}

/* extend_from the first of the tree's nearest nodes to (x, y) whose step is free (TRAPPED
 * when none is). */
static int extend(struct gmmrrt_planner *p, int goal_tree, double x, double y, int32_t *out)
{
    const gmmrrt_connect_t *c = &p->connect;
    const int32_t lo = goal_tree ? GMMRRT_CONNECT_MAX_NODES - c->n_goal : 0;
    const int32_t hi = goal_tree ? GMMRRT_CONNECT_MAX_NODES : c->n_start;
    int32_t idx[GMMRRT_CONNECT_TRIES];
    const int m = nearest_few(c->xy, lo, hi, x, y, idx);
    int st = TRAPPED;
    for (int k = 0; k < m && st == TRAPPED; ++k)
        st = extend_from(p, goal_tree, idx[k], x, y, k == 0, out);
    return st;
}

/* The joined path, start first: the start tree's branch to node a, then the goal tree's branch
 * from node b (at the same point as a) to the goal; inserted into the RRT* tree. */
static void hand_over(struct gmmrrt_planner *p, int32_t a, int32_t b)
{
    gmmrrt_connect_t *c = &p->connect;
    int32_t len = 0;
    for (int32_t i = a; i >= 0; i = c->parent[i])
        ++len;
    for (int32_t i = a, k = len - 1; i >= 0; i = c->parent[i], --k) {
        c->path_x[k] = c->xy[i].x;
        c->path_y[k] = c->xy[i].y;
    }
    for (int32_t i = c->parent[b]; i >= 0; i = c->parent[i]) {
        c->path_x[len] = c->xy[i].x;
        c->path_y[len] = c->xy[i].y;
        ++len;
    }
    /* Its first point is the root, which seed_path skips (the same point). A pool too small for
     * the whole path keeps what fits; RRT* then goes on without a path. */
    (void)gmmrrt_planner_seed_path(p, c->path_x, c->path_y, len);
}

void gmmrrt_connect_iterate(struct gmmrrt_planner *p)
{
    gmmrrt_connect_t *c = &p->connect;
    if (isfinite(p->best_cost)) { /* a path exists already (a warm start): nothing to connect */
        c->state = GMMRRT_CONNECT_OFF;
        return;
    }
    if (c->iterations >= p->cfg.connect_max_iterations) {
        /* The cap: RRT* alone from the root from here (its tree is the root only), the same
         * search as with connect_first = 0 from this iteration on. */
        c->state = GMMRRT_CONNECT_OFF;
        return;
    }
    ++c->iterations;
    ++p->iterations;
    double sx, sy;
    if (!gmmrrt_sample(p, &sx, &sy) || !gmmrrt_planner_point_free(p, sx, sy))
        return;
    const int from_goal = c->turn;
    c->turn ^= 1;
    int32_t grown;
    int st = extend(p, from_goal, sx, sy, &grown);
    if (st == TRAPPED)
        return;
    int32_t other = -1;
    if (st != FULL) {
        /* After an ADVANCED step the greedy connection goes on from the node just added, as
         * RRT-Connect's CONNECT does (it is step_m closer to the target than the node it grew
         * from), so it scans the tree once. */
        const double tx = c->xy[grown].x, ty = c->xy[grown].y;
        st = extend(p, !from_goal, tx, ty, &other);
        while (st == ADVANCED) /* from the node just added: the nearest to the target */
            st = extend_from(p, !from_goal, other, tx, ty, 1, &other);
    }
    if (st == FULL) {
        c->state = GMMRRT_CONNECT_OFF; /* RRT* alone from here */
        return;
    }
    if (st == REACHED) {
        c->state = GMMRRT_CONNECT_OFF;
        hand_over(p, from_goal ? other : grown, from_goal ? grown : other);
    }
}
