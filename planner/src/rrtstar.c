/*
 * rrtstar.c - the anytime planner of planner.h: RRT* (Karaman & Frazzoli 2011, Alg. 6:
 * extend, choose-parent, rewire) over one caller-owned block, with the paper's mixture
 * sampling and task cost (Sect. 4) and the GMM-RRT baseline (an RRT: parent = nearest,
 * no rewiring, length cost).
 *
 * Block layout (8-byte aligned pieces, in this order): planner struct, node pool
 * (max_nodes x 40 B), bucket heads (max_nodes x 4 B), history (capacity x 16 B),
 * connect phase (gmmrrt_connect_mem_size, connect.c), collision world
 * (gmmrrt_world_mem_size(grid_max_cells)). Nothing else is used:
 * set_problem, run, seed_path and best_path allocate nothing (tests/unit/planner/test_alloc.c).
 *
 * Iterations: one sample drawn, kept or not (as OMPL counts). Near radius:
 * r = min(step_m, rewire_gamma sqrt(log n / n)) for n nodes (the RRT* ball in 2-D),
 * halved while more than GMMRRT_NEAR_CAP nodes fall inside it. Rewiring a node shifts
 * the cost of its whole subtree by the same amount (walked through child/sibling links).
 */
#include "gmmrrt/planner.h"

#include <assert.h>
#include <math.h>
#include <stddef.h>
#include <string.h>
#include <time.h>

#include "block_layout.h"
#include "planner_internal.h"
#include "tree_check.h"


typedef struct {
    size_t xy, cost, link, next, heads, hist_iter, hist_cost, connect, world, total;
} layout_t;

static layout_t layout_of(const gmmrrt_planner_config_t *cfg)
{
    layout_t l;
    size_t off = gmmrrt_align8(sizeof(struct gmmrrt_planner));
    const size_t n = (size_t)cfg->max_nodes;
    l.xy = gmmrrt_block_take(&off, n * sizeof(gmmrrt_xy_t));
    l.cost = gmmrrt_block_take(&off, n * sizeof(double));
    l.link = gmmrrt_block_take(&off, n * sizeof(gmmrrt_links_t));
    l.next = gmmrrt_block_take(&off, n * sizeof(int32_t));
    l.heads = gmmrrt_block_take(&off, (size_t)gmmrrt_nn_capacity(cfg->max_nodes) * sizeof(int32_t));
    l.hist_iter = gmmrrt_block_take(&off, (size_t)cfg->history_capacity * sizeof(int64_t));
    l.hist_cost = gmmrrt_block_take(&off, (size_t)cfg->history_capacity * sizeof(double));
    l.connect = gmmrrt_block_take(&off, gmmrrt_connect_mem_size(cfg));
    l.world = off;
    off += gmmrrt_world_mem_size(cfg->grid_max_cells);
    l.total = off;
    return l;
}

size_t gmmrrt_planner_mem_size(const gmmrrt_planner_config_t *cfg)
{
    if (gmmrrt_planner_config_validate(cfg, NULL, 0) != GMMRRT_OK)
        return 0;
    return layout_of(cfg).total;
}

gmmrrt_status_t gmmrrt_planner_init(gmmrrt_planner_t **out, void *mem, size_t size,
                                    const gmmrrt_planner_config_t *cfg)
{
    if (!out || !mem || ((uintptr_t)mem & 7u) != 0)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    gmmrrt_status_t st = gmmrrt_planner_config_validate(cfg, NULL, 0);
    if (st != GMMRRT_OK)
        return st;
    const layout_t l = layout_of(cfg);
    if (size < l.total)
        return GMMRRT_ERR_BUFFER_TOO_SMALL;
    uint8_t *base = mem;
    struct gmmrrt_planner *p = mem;
    memset(p, 0, offsetof(struct gmmrrt_planner, walkers)); /* not the per-problem copies nor the scratch */
    p->cfg = *cfg;
    p->strategy = gmmrrt_strategy_of(cfg->planner);
    p->pool.xy = (gmmrrt_xy_t *)(void *)(base + l.xy);
    p->pool.cost = (double *)(void *)(base + l.cost);
    p->pool.link = (gmmrrt_links_t *)(void *)(base + l.link);
    p->pool.next_in_bucket = (int32_t *)(void *)(base + l.next);
    p->nn.heads = (int32_t *)(void *)(base + l.heads);
    p->nn.capacity = gmmrrt_nn_capacity(cfg->max_nodes);
    p->hist_iter = (int64_t *)(void *)(base + l.hist_iter);
    p->hist_cost = (double *)(void *)(base + l.hist_cost);
    gmmrrt_connect_bind(p, base + l.connect);
    p->world_mem = base + l.world;
    p->world_size = l.total - l.world;
    p->world = NULL;
    p->has_problem = 0;
    p->best_goal = -1;
    p->best_cost = INFINITY;
    *out = p;
    return GMMRRT_OK;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static int finite2(double a, double b) { return isfinite(a) && isfinite(b); }

static int inside(const gmmrrt_bounds_t *b, double x, double y)
{
    return x >= b->xmin && x <= b->xmax && y >= b->ymin && y <= b->ymax;
}

/* Distance from (px, py) to the segment a-b. */
static double point_segment_distance(double px, double py, double ax, double ay, double bx, double by)
{
    const double vx = bx - ax, vy = by - ay, l2 = vx * vx + vy * vy;
    double t = l2 > 0.0 ? ((px - ax) * vx + (py - ay) * vy) / l2 : 0.0;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    return hypot(px - (ax + t * vx), py - (ay + t * vy));
}

static void consider_goal(struct gmmrrt_planner *p, int32_t i);
static void update_best(struct gmmrrt_planner *p);

static void reset_tree(struct gmmrrt_planner *p)
{
    p->num_nodes = 1;
    p->pool.xy[0].x = p->problem.start_x;
    p->pool.xy[0].y = p->problem.start_y;
    p->pool.cost[0] = 0.0;
    p->pool.link[0].parent = p->pool.link[0].first_child = p->pool.link[0].next_sibling = -1;
    gmmrrt_nn_reset_adaptive(&p->nn, &p->problem.obstacles.bounds);
    gmmrrt_nn_insert(&p->nn, &p->pool, 0);
    p->num_goal = 0;
    p->best_goal = -1;
    p->best_cost = INFINITY;
    p->hist_count = 0;
    p->iterations = 0;
    p->first_solution_iteration = -1;
    p->first_solution_ms = -1.0;
    p->time_ms = 0.0;
    p->run_t0_ms = -1.0;
    p->run_base_ms = 0.0;
    p->conv_ref_cost = INFINITY;
    p->conv_ref_iter = 0;
    p->pruned = 0;
    gmmrrt_rng_seed(&p->rng, p->cfg.seed);
    gmmrrt_connect_reset(p);
}

gmmrrt_status_t gmmrrt_planner_model_fits(const gmmrrt_planner_config_t *cfg, const gmmrrt_model_t *m)
{
    if (!cfg)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    const gmmrrt_strategy_t s = gmmrrt_strategy_of(cfg->planner);
    if (s.model_kind == 0)
        return GMMRRT_OK; /* no model is used */
    if (!m)
        return GMMRRT_ERR_MODEL_MISMATCH;
    if (m->kind != s.model_kind || m->dim != s.model_dim)
        return GMMRRT_ERR_MODEL_MISMATCH;
    if (m->k < 1 || m->k > GMMRRT_MAX_K)
        return GMMRRT_ERR_MODEL_MISMATCH;
    if (cfg->delta == 0.0 && !(isfinite(m->delta) && m->delta > 0.0))
        return GMMRRT_ERR_MODEL_MISMATCH;
    return GMMRRT_OK;
}

/* The preferred side as a ray no edge may cross (planner.h, gmmrrt_side_t). Seen from the
 * person, the start and goal bearings split the circle into a counterclockwise arc from start
 * to goal (LEFT) and a clockwise one (RIGHT). A path of one side sweeps its arc and does not
 * cross a ray through the middle of the other arc; a path of the other side must cross it.
 * So blocking that ray keeps every path on the preferred side, and leaves every path of that
 * side that does not wind round the person open. */
static void prepare_side(struct gmmrrt_planner *p)
{
    const gmmrrt_problem_t *pr = &p->problem;
    const gmmrrt_obstacle_set_t *o = &pr->obstacles;
    p->side_active = 0;
    if (pr->side == GMMRRT_SIDE_EITHER || o->num_people == 0)
        return;
    int32_t who = pr->side_person;
    if (who < 0) {
        double best = INFINITY;
        for (int32_t i = 0; i < o->num_people; ++i) {
            const double d = point_segment_distance(o->people[i].x, o->people[i].y, pr->start_x, pr->start_y,
                                                    pr->goal_x, pr->goal_y);
            if (d < best) {
                best = d;
                who = i;
            }
        }
    }
    const double px = o->people[who].x, py = o->people[who].y;
    const double bs = atan2(pr->start_y - py, pr->start_x - px), bg = atan2(pr->goal_y - py, pr->goal_x - px);
    const double two_pi = 2.0 * M_PI;
    double ccw = fmod(bg - bs, two_pi); /* length of the counterclockwise arc start -> goal, [0, 2 pi) */
    if (ccw < 0.0)
        ccw += two_pi;
    /* LEFT blocks the middle of the clockwise arc, RIGHT the middle of the counterclockwise one. */
    const double alpha = pr->side == GMMRRT_SIDE_LEFT ? bs - 0.5 * (two_pi - ccw) : bs + 0.5 * ccw;
    p->side_px = px;
    p->side_py = py;
    p->side_ux = cos(alpha);
    p->side_uy = sin(alpha);
    p->side_active = 1;
}

/* 1 when the segment (x0, y0)-(x1, y1) does not cross the preferred side's ray. */
static int side_allows(const struct gmmrrt_planner *p, double x0, double y0, double x1, double y1)
{
    if (!p->side_active)
        return 1;
    /* Solve (x0, y0) + s (e) = P + t u with s in [0, 1], t >= 0 (e = segment direction). */
    const double ex = x1 - x0, ey = y1 - y0;
    const double wx = p->side_px - x0, wy = p->side_py - y0;
    const double den = ex * p->side_uy - ey * p->side_ux; /* cross(e, u) */
    if (den == 0.0)
        return 1; /* parallel: an edge along the ray would pass through the person, who blocks it */
    const double s = (wx * p->side_uy - wy * p->side_ux) / den;
    const double t = (wx * ey - wy * ex) / den;
    return !(s >= 0.0 && s <= 1.0 && t >= 0.0);
}

/* An edge the tree may use: collision-free (walkers included) and on the preferred side. */
static int edge_allowed(const struct gmmrrt_planner *p, double x0, double y0, double x1, double y1)
{
    return gmmrrt_planner_segment_free(p, x0, y0, x1, y1) && side_allows(p, x0, y0, x1, y1);
}

int gmmrrt_planner_edge_allowed(const struct gmmrrt_planner *p, double x0, double y0, double x1, double y1)
{
    return edge_allowed(p, x0, y0, x1, y1);
}

/* *dst = *src, less the unused capacity of the obstacle and velocity arrays (each is read only
 * below its count): 5 KB that a cold set-up would otherwise write. Everything between those
 * arrays is copied as a byte range, so a field added there is copied too. */
#define PR_OFF(f) offsetof(gmmrrt_problem_t, f)
static void copy_range(gmmrrt_problem_t *dst, const gmmrrt_problem_t *src, size_t from, size_t to)
{
    memcpy((uint8_t *)dst + from, (const uint8_t *)src + from, to - from);
}

static void copy_problem(gmmrrt_problem_t *dst, const gmmrrt_problem_t *src)
{
    const int32_t nc = src->obstacles.num_circles, nb = src->obstacles.num_boxes, np = src->obstacles.num_people;
    copy_range(dst, src, 0, PR_OFF(obstacles.circles));
    memcpy(dst->obstacles.circles, src->obstacles.circles, (size_t)nc * sizeof src->obstacles.circles[0]);
    copy_range(dst, src, PR_OFF(obstacles.num_boxes), PR_OFF(obstacles.boxes));
    memcpy(dst->obstacles.boxes, src->obstacles.boxes, (size_t)nb * sizeof src->obstacles.boxes[0]);
    copy_range(dst, src, PR_OFF(obstacles.num_people), PR_OFF(obstacles.people));
    memcpy(dst->obstacles.people, src->obstacles.people, (size_t)np * sizeof src->obstacles.people[0]);
    copy_range(dst, src, PR_OFF(obstacles.raster), PR_OFF(person_vx));
    memcpy(dst->person_vx, src->person_vx, (size_t)np * sizeof src->person_vx[0]);
    memcpy(dst->person_vy, src->person_vy, (size_t)np * sizeof src->person_vy[0]);
    copy_range(dst, src, PR_OFF(nominal_speed_m_s), sizeof *src);
}
#undef PR_OFF

gmmrrt_status_t gmmrrt_planner_set_problem(gmmrrt_planner_t *p, const gmmrrt_problem_t *pr)
{
    if (!p || !pr)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    const double setup_t0 = now_ms();
    p->has_problem = 0;
    if (!finite2(pr->start_x, pr->start_y) || !finite2(pr->goal_x, pr->goal_y) ||
        !isfinite(pr->goal_tolerance_m) || pr->goal_tolerance_m <= 0.0)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    if (pr->task != GMMRRT_TASK_NONE && pr->task != GMMRRT_TASK_AVOID && pr->task != GMMRRT_TASK_APPROACH)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    const gmmrrt_obstacle_set_t *o = &pr->obstacles;
    if (o->num_people < 0 || o->num_people > GMMRRT_MAX_PEOPLE)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    if (pr->task == GMMRRT_TASK_APPROACH && (pr->target_person < 0 || pr->target_person >= o->num_people))
        return GMMRRT_ERR_INVALID_ARGUMENT;
    if (pr->side != GMMRRT_SIDE_EITHER && pr->side != GMMRRT_SIDE_LEFT && pr->side != GMMRRT_SIDE_RIGHT)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    if (pr->side != GMMRRT_SIDE_EITHER && (pr->side_person < -1 || pr->side_person >= o->num_people))
        return GMMRRT_ERR_INVALID_ARGUMENT;

    /* Model kind against planner kind. */
    const gmmrrt_model_t *m = pr->model;
    const int wants_model = pr->task != GMMRRT_TASK_NONE && p->strategy.model_kind != 0;
    if (wants_model) {
        const gmmrrt_status_t fit = gmmrrt_planner_model_fits(&p->cfg, pr->model);
        if (fit != GMMRRT_OK)
            return fit;
        const gmmrrt_model_t *bg = pr->background_model;
        if (gmmrrt_planner_needs_background(&p->cfg) &&
            (!bg || bg->kind != GMMRRT_MODEL_KIND_FEATURES || bg->dim != 2 || bg->k < 1 || bg->k > GMMRRT_MAX_K))
            return GMMRRT_ERR_MODEL_MISMATCH;
    }

    /* Walking people are predicted (moving_people.c), not in the world. */
    p->escape.active = 0;
    p->escape.freeze_reason[0] = '\0';
    const gmmrrt_obstacle_set_t *world_set;
    gmmrrt_status_t st = gmmrrt_walkers_prepare(p, pr, &world_set);
    if (st != GMMRRT_OK)
        return st;
    /* Builds the world (validates every obstacle number and the bounds); keeps the last
     * problem's clearance grid where the static obstacles are the same (collision.h). */
    gmmrrt_world_t *w = p->world;
    st = gmmrrt_world_update(&w, p->world_mem, p->world_size, p->cfg.grid_max_cells, p->cfg.grid_resolution_m,
                             p->cfg.robot_radius_m, p->cfg.person_radius_m, world_set);
    if (st != GMMRRT_OK) {
        p->world = NULL;
        return st;
    }
    gmmrrt_world_set_edge_resolution(w, p->cfg.edge_resolution_m);
    p->world = w;
    if (!inside(&o->bounds, pr->start_x, pr->start_y))
        return GMMRRT_ERR_START_OUT_OF_BOUNDS;
    if (!inside(&o->bounds, pr->goal_x, pr->goal_y))
        return GMMRRT_ERR_GOAL_OUT_OF_BOUNDS;
    if (!gmmrrt_world_point_free(w, pr->goal_x, pr->goal_y))
        return GMMRRT_ERR_GOAL_IN_COLLISION;
    /* A start in collision is a state to leave, not a refusal (escape.c). So is a free start within
     * the edge margin of an obstacle or person (collision.h): every edge from it would be refused and
     * the tree could never grow (the robot would stand there, cycle after cycle). */
    double root_x = pr->start_x, root_y = pr->start_y;
    gmmrrt_status_t start_status = GMMRRT_OK;
    if (!gmmrrt_planner_point_free(p, pr->start_x, pr->start_y) ||
        !gmmrrt_world_point_leavable(w, pr->start_x, pr->start_y)) {
        start_status = gmmrrt_escape_find(p, pr, &root_x, &root_y);
        if (start_status != GMMRRT_ESCAPE)
            return start_status;
        p->walkers.root_x = root_x;
        p->walkers.root_y = root_y;
    }

    copy_problem(&p->problem, pr);
    p->problem.start_x = root_x;
    p->problem.start_y = root_y;
    pr = &p->problem;
    p->delta = (p->cfg.delta > 0.0) ? p->cfg.delta : (m ? m->delta : GMMRRT_MODEL_DEFAULT_DELTA);
    p->task_active = wants_model;
    p->num_active = 0;
    p->focus_person = -1;
    if (wants_model) {
        if (pr->task == GMMRRT_TASK_APPROACH) {
            p->active[p->num_active++] = pr->target_person;
            p->focus_person = pr->target_person;
        } else {
            double best = INFINITY;
            for (int32_t i = 0; i < o->num_people; ++i) {
                const double d = point_segment_distance(o->people[i].x, o->people[i].y, pr->start_x, pr->start_y,
                                                        pr->goal_x, pr->goal_y);
                if (d <= p->cfg.person_influence_m)
                    p->active[p->num_active++] = i;
                if (d < best) {
                    best = d;
                    p->focus_person = i;
                }
            }
            if (p->strategy.stages && best > p->cfg.person_influence_m)
                p->focus_person = -1;
        }
        if (p->num_active == 0 || p->focus_person < 0)
            p->task_active = 0; /* nobody the task is about: plain search */
        for (int32_t k = 0; k < p->num_active; ++k) {
            const double yaw = o->people[p->active[k]].yaw;
            p->active_cos[k] = cos(yaw);
            p->active_sin[k] = sin(yaw);
        }
    }
    prepare_side(p);
    gmmrrt_sampler_prepare(p);
    reset_tree(p);
    p->has_problem = 1;
    consider_goal(p, 0); /* a start already within the goal tolerance is a solution */
    update_best(p);
    p->setup_ms = now_ms() - setup_t0;
    return start_status == GMMRRT_ESCAPE ? GMMRRT_ESCAPE : GMMRRT_OK;
}

/* ---------------------------------------------------------------- tree edits */

static void attach(struct gmmrrt_planner *p, int32_t child, int32_t parent)
{
    gmmrrt_links_t *c = &p->pool.link[child];
    c->parent = parent;
    c->next_sibling = p->pool.link[parent].first_child;
    p->pool.link[parent].first_child = child;
}

static void detach(struct gmmrrt_planner *p, int32_t child)
{
    const int32_t parent = p->pool.link[child].parent;
    int32_t *link = &p->pool.link[parent].first_child;
    while (*link != child)
        link = &p->pool.link[*link].next_sibling;
    *link = p->pool.link[child].next_sibling;
    p->pool.link[child].next_sibling = -1;
    p->pool.link[child].parent = -1;
}

/* Adds delta to the cost of every descendant of `top` (not top itself). */
static void shift_subtree(struct gmmrrt_planner *p, int32_t top, double delta)
{
    int32_t cur = p->pool.link[top].first_child;
    while (cur >= 0) {
        p->pool.cost[cur] += delta;
        if (p->pool.link[cur].first_child >= 0) {
            cur = p->pool.link[cur].first_child;
            continue;
        }
        while (cur != top && p->pool.link[cur].next_sibling < 0)
            cur = p->pool.link[cur].parent;
        if (cur == top)
            break;
        cur = p->pool.link[cur].next_sibling;
    }
}

static void reparent(struct gmmrrt_planner *p, int32_t node, int32_t new_parent, double new_cost)
{
    const double delta = new_cost - p->pool.cost[node];
    detach(p, node);
    attach(p, node, new_parent);
    p->pool.cost[node] = new_cost;
    shift_subtree(p, node, delta);
}

static int32_t add_node(struct gmmrrt_planner *p, double x, double y, int32_t parent, double cost)
{
    const int32_t i = p->num_nodes++;
    p->pool.xy[i].x = x;
    p->pool.xy[i].y = y;
    p->pool.cost[i] = cost;
    p->pool.link[i].first_child = -1;
    attach(p, i, parent);
    gmmrrt_nn_insert(&p->nn, &p->pool, i);
    gmmrrt_gmm_rrt_node_added(p, x, y);
    return i;
}

/* Remembers node i as a solution candidate when it reaches the goal region by a free edge. */
static void consider_goal(struct gmmrrt_planner *p, int32_t i)
{
    const gmmrrt_problem_t *pr = &p->problem;
    const gmmrrt_xy_t *n = &p->pool.xy[i];
    const double n_cost = p->pool.cost[i];
    const double gx = n->x - pr->goal_x, gy = n->y - pr->goal_y;
    const double d = sqrt(gx * gx + gy * gy); /* plain sqrt: map coordinates */
    if (d > pr->goal_tolerance_m)
        return;
    if (d > GMMRRT_SAME_POINT_M && !edge_allowed(p, n->x, n->y, pr->goal_x, pr->goal_y))
        return;
    const double edge = d > GMMRRT_SAME_POINT_M ? gmmrrt_edge_cost(p, n->x, n->y, pr->goal_x, pr->goal_y) : 0.0;
    int32_t slot = p->num_goal;
    if (slot >= GMMRRT_GOAL_CAP) {
        int32_t worst = 0;
        for (int32_t s = 1; s < p->num_goal; ++s)
            if (p->pool.cost[p->goal_idx[s]] + p->goal_edge[s] >
                p->pool.cost[p->goal_idx[worst]] + p->goal_edge[worst])
                worst = s;
        if (worst == p->best_goal || p->pool.cost[p->goal_idx[worst]] + p->goal_edge[worst] <= n_cost + edge)
            return;
        slot = worst;
    } else {
        ++p->num_goal;
    }
    p->goal_idx[slot] = i;
    p->goal_edge[slot] = edge;
}

/* Re-evaluates the best solution; records history when it improved. */
static void update_best(struct gmmrrt_planner *p)
{
    int32_t best = -1;
    double best_cost = INFINITY;
    for (int32_t s = 0; s < p->num_goal; ++s) {
        const double c = p->pool.cost[p->goal_idx[s]] + p->goal_edge[s];
        if (c < best_cost) {
            best_cost = c;
            best = s;
        }
    }
    if (best < 0 || !(best_cost < p->best_cost))
        return;
    if (p->first_solution_iteration < 0) {
        p->first_solution_iteration = p->iterations;
        p->first_solution_ms = p->run_base_ms + (p->run_t0_ms >= 0.0 ? now_ms() - p->run_t0_ms : 0.0);
        /* Until the first path the search wants coverage, and the map's four-corner bound is the
         * cheapest test; from then on the cost depends on how close paths may pass walls, and the
         * union of the corners' discs (several times the arithmetic where the bound cannot
         * decide) lets them pass nearly at the true clearance. Outside the search's extensions
         * (the start and goal checks, a seeded path, the tree check) the union is always on, so
         * a pose reached along a published path is never judged by a looser rule than the path. */
        gmmrrt_world_set_raster_union(p->world, 1);
    }
    p->best_goal = best;
    p->best_cost = best_cost;
    const int32_t cap = p->cfg.history_capacity;
    const int32_t h = p->hist_count < cap ? p->hist_count++ : cap - 1; /* full: keep the latest last */
    p->hist_iter[h] = p->iterations;
    p->hist_cost[h] = best_cost;
}

/* ---------------------------------------------------------------- one iteration */

static int edge_free_cached(struct gmmrrt_planner *p, int32_t k, double x, double y)
{
    if (p->near_free[k] < 0) {
        const gmmrrt_xy_t *n = &p->pool.xy[p->near_idx[k]];
        p->near_free[k] = (int8_t)edge_allowed(p, n->x, n->y, x, y);
    }
    return p->near_free[k];
}

static void near_exact(struct gmmrrt_planner *p, int32_t k, double x, double y)
{
    const gmmrrt_xy_t *n = &p->pool.xy[p->near_idx[k]];
    p->near_edge[k] = gmmrrt_edge_cost(p, n->x, n->y, x, y);
}

/* Appends `nearest` (with its squared distance to (x, y)) to the near set of count nodes
 * unless it is in it: the extend step's parent is always a candidate. Returns the count. */
static int32_t with_nearest(struct gmmrrt_planner *p, int32_t count, int32_t nearest, double x, double y)
{
    for (int32_t k = 0; k < count; ++k)
        if (p->near_idx[k] == nearest)
            return count;
    const double dx = p->pool.xy[nearest].x - x, dy = p->pool.xy[nearest].y - y;
    p->near_idx[count] = nearest;
    p->near_d2[count] = dx * dx + dy * dy;
    return count + 1;
}

static int32_t near_set(struct gmmrrt_planner *p, double x, double y, int32_t nearest)
{
    double r = p->cfg.step_m;
    const double n = (double)p->num_nodes;
    if (n > 1.0) {
        const double ball = p->cfg.rewire_gamma * sqrt(log(n) / n);
        if (ball < r)
            r = ball;
    }
    int32_t count;
    while ((count = gmmrrt_nn_near(&p->nn, &p->pool, x, y, r, p->near_idx, GMMRRT_NEAR_CAP)) < 0)
        r *= 0.5;
    return with_nearest(p, count, nearest, x, y);
}

/* k of the k-nearest near set for the current tree: ceil(rewire_k_factor ln(n + 1)). */
static int32_t near_k(const struct gmmrrt_planner *p)
{
    const double k = ceil(p->cfg.rewire_k_factor * log((double)p->num_nodes + 1.0));
    return k < 1.0 ? 1 : (k > (double)GMMRRT_NEAR_CAP ? GMMRRT_NEAR_CAP : (int32_t)k);
}

static void iterate(struct gmmrrt_planner *p)
{
    double sx, sy;
    if (gmmrrt_nn_relayout_due(&p->nn, p->num_nodes + 1)) /* no node index is held here */
        gmmrrt_nn_relayout_sorted(&p->nn, &p->pool, p->num_nodes, p->goal_idx, p->num_goal);
    ++p->iterations;
    /* SampleFree (Karaman & Frazzoli 2011, Alg. 6): a sample in collision is dropped before
     * any tree query (the iteration is spent, as OMPL counts). */
    if (!gmmrrt_sample(p, &sx, &sy) || !gmmrrt_planner_point_free(p, sx, sy))
        return;
    /* k-nearest RRT*: one query at the sample gives the nearest node and, unless steering
     * moves the new point, the near set too: the k nearest within step_m (as the radius of
     * the radius mode is at most step_m), so early sparse trees do not get long edges whose
     * task-cost quadrature and collision checks are costly. */
    const int knn = p->cfg.rewire_k_factor > 0.0 && p->strategy.rewires;
    int32_t count = 0;
    int32_t nearest;
    if (knn) {
        count = gmmrrt_nn_nearest_k(&p->nn, &p->pool, sx, sy, near_k(p), GMMRRT_NEAR_CAP, p->cfg.step_m,
                                    p->near_idx, p->near_d2, GMMRRT_KNN_SCRATCH);
        nearest = p->near_idx[0];
    } else {
        nearest = gmmrrt_nn_nearest(&p->nn, &p->pool, sx, sy);
    }
    const gmmrrt_xy_t *nn = &p->pool.xy[nearest];
    double dx = sx - nn->x, dy = sy - nn->y;
    const double dist = sqrt(dx * dx + dy * dy); /* plain sqrt: hypot is far slower, no overflow here */
    if (dist <= GMMRRT_SAME_POINT_M)
        return;
    double x = sx, y = sy;
    const int steered = dist > p->cfg.step_m;
    if (steered) {
        x = nn->x + dx * (p->cfg.step_m / dist);
        y = nn->y + dy * (p->cfg.step_m / dist);
    }
    if (steered && !gmmrrt_planner_point_free(p, x, y))
        return;

    if (!p->strategy.rewires) { /* RRT's extend (the GMM-RRT baseline) */
        if (!edge_allowed(p, nn->x, nn->y, x, y))
            return;
        const double c = p->pool.cost[nearest] + gmmrrt_edge_cost(p, nn->x, nn->y, x, y);
        const int32_t i = add_node(p, x, y, nearest, c);
        consider_goal(p, i);
        update_best(p);
        return;
    }

    if (!knn) {
        count = near_set(p, x, y, nearest);
        for (int32_t k = 0; k < count; ++k) {
            const gmmrrt_xy_t *c = &p->pool.xy[p->near_idx[k]];
            const double ddx = c->x - x, ddy = c->y - y;
            p->near_d2[k] = ddx * ddx + ddy * ddy;
        }
    } else if (steered) {
        count = gmmrrt_nn_nearest_k(&p->nn, &p->pool, x, y, near_k(p), GMMRRT_NEAR_CAP, p->cfg.step_m,
                                    p->near_idx, p->near_d2, GMMRRT_KNN_SCRATCH);
        count = with_nearest(p, count, nearest, x, y);
    }

    /* Choose parent: cheapest candidate by cost-to-come + edge cost whose edge is free.
     * Candidates are ranked by a lower bound until their exact cost is needed (lazy, so
     * the quadrature runs only for candidates that can still win). */
    /* Without a task term (and without walkers' lane cost) the edge cost is a fixed multiple of
     * length: the lower bound is exact, so no candidate needs the quadrature. */
    const int cost_is_length = !p->strategy.task_cost ||
                               ((!p->task_active || p->num_active == 0) && p->walkers.count == 0);
    /* The lower bound is linear in length (objective.c): its slope once per iteration. */
    const double unit = gmmrrt_edge_cost_lower_bound(p, 1.0);
    /* Simple loops (the square roots vectorise). */
    for (int32_t k = 0; k < count; ++k)
        p->near_len[k] = sqrt(p->near_d2[k]);
    if (cost_is_length)
        for (int32_t k = 0; k < count; ++k)
            p->near_edge[k] = unit * p->near_len[k];
    else
        for (int32_t k = 0; k < count; ++k)
            p->near_edge[k] = NAN;
    for (int32_t k = 0; k < count; ++k)
        p->near_cost[k] = p->pool.cost[p->near_idx[k]];
    memset(p->near_free, -1, (size_t)count);
    int32_t parent_k = -1;
    for (;;) {
        int32_t pick = -1;
        double pick_cost = INFINITY;
        for (int32_t k = 0; k < count; ++k) {
            if (p->near_free[k] == 0)
                continue;
            const double edge = isnan(p->near_edge[k]) ? unit * p->near_len[k] : p->near_edge[k];
            const double c = p->near_cost[k] + edge;
            if (c < pick_cost) {
                pick_cost = c;
                pick = k;
            }
        }
        if (pick < 0)
            return; /* no free edge to the new point */
        if (isnan(p->near_edge[pick])) {
            near_exact(p, pick, x, y);
            continue; /* re-rank with the exact cost */
        }
        if (edge_free_cached(p, pick, x, y)) {
            parent_k = pick;
            break;
        }
    }
    const int32_t parent = p->near_idx[parent_k];
    const int32_t added = add_node(p, x, y, parent, p->pool.cost[parent] + p->near_edge[parent_k]);

    /* Rewire: near nodes that get cheaper through the new node. */
    for (int32_t k = 0; k < count; ++k) {
        const int32_t m = p->near_idx[k];
        if (m == parent)
            continue;
        const double base = p->pool.cost[added];
        if (!(base + unit * p->near_len[k] < p->pool.cost[m]))
            continue;
        if (isnan(p->near_edge[k]))
            near_exact(p, k, x, y);
        const double c = base + p->near_edge[k];
        if (c < p->pool.cost[m] && edge_free_cached(p, k, x, y))
            reparent(p, m, added, c);
    }
    consider_goal(p, added);
    update_best(p);
}

/* ---------------------------------------------------------------- pruning */

/* Informed pruning of a full pool (planner.h, gmmrrt_planner_run): keeps the root, the best
 * path and every node whose parent is kept and whose f = cost-to-come + unit x distance to
 * the goal is below the best cost (f never falls along an edge: the edge costs at least unit x
 * its length, and the distance to the goal falls by at most that length, so whole subtrees go).
 * This is OMPL's RRTstar pruning with the tree's cost-to-come (setAdmissibleCostToCome(false)):
 * no dropped node can reach the goal more cheaply than the best path through its current
 * branch. When that frees less than a quarter of the pool (the tree already lies where a
 * cheaper path may be), the threshold is lowered to drop the quarter of the nodes of largest
 * f (prune_threshold): the tree keeps its branches that promise most, around the best path.
 * Either way the best path and its cost stay, and the space a dropped branch covered is
 * sampled again. The kept nodes are packed to the front of the pool in their order, the
 * links and solution candidates renumbered, the spatial index rebuilt: O(nodes), no memory but
 * the pool (next_in_bucket is the scratch, as in gmmrrt_nn_relayout_sorted). Returns the number
 * of nodes dropped. */
/* f of node i: cost-to-come + the lower bound of the cost to the goal. */
static double node_f(const struct gmmrrt_planner *p, int32_t i, double unit)
{
    const gmmrrt_xy_t *q = &p->pool.xy[i];
    const double gx = q->x - p->problem.goal_x, gy = q->y - p->problem.goal_y;
    return p->pool.cost[i] + unit * sqrt(gx * gx + gy * gy);
}

/* The f below which nodes are kept: the best cost when at least a quarter of the pool has
 * f >= best cost; otherwise lower, so that about a quarter of the nodes (those of largest f)
 * have f >= it (a 256-bin histogram of f over [unit |start - goal|, best cost]: no memory). */
#define PRUNE_BINS 256
static double prune_threshold(const struct gmmrrt_planner *p, double unit)
{
    const int32_t n = p->num_nodes, want = n / 4;
    const double lo = unit * hypot(p->problem.goal_x - p->problem.start_x, p->problem.goal_y - p->problem.start_y);
    const double hi = p->best_cost;
    if (!(hi > lo))
        return hi;
    int32_t bins[PRUNE_BINS] = {0};
    int32_t above = 0;
    for (int32_t i = 0; i < n; ++i) {
        const double f = node_f(p, i, unit);
        if (f >= hi) {
            ++above;
            continue;
        }
        const double b = floor((f - lo) / (hi - lo) * PRUNE_BINS);
        bins[b < 0.0 ? 0 : (b >= PRUNE_BINS ? PRUNE_BINS - 1 : (int32_t)b)]++;
    }
    int32_t b = PRUNE_BINS;
    while (above < want && b > 0)
        above += bins[--b];
    return b == PRUNE_BINS ? hi : lo + (hi - lo) * (double)b / PRUNE_BINS;
}

static int32_t prune(struct gmmrrt_planner *p)
{
    if (!isfinite(p->best_cost) || p->best_goal < 0)
        return 0;
    const int32_t n = p->num_nodes;
    int32_t *keep = p->pool.next_in_bucket; /* 1 kept, 0 dropped; then the new index or -1 */
    const gmmrrt_problem_t *pr = &p->problem;
    const double unit = gmmrrt_edge_cost_lower_bound(p, 1.0);
    const double threshold = prune_threshold(p, unit);
    for (int32_t i = 0; i < n; ++i)
        keep[i] = 0;
    for (int32_t i = p->goal_idx[p->best_goal]; i >= 0; i = p->pool.link[i].parent)
        keep[i] = 2; /* the best path */
    /* Depth-first through the child / sibling links from the root. */
    keep[0] = 1;
    int32_t cur = p->pool.link[0].first_child;
    while (cur >= 0) {
        const int descend = keep[cur] == 2 || node_f(p, cur, unit) < threshold;
        keep[cur] = descend;
        if (descend && p->pool.link[cur].first_child >= 0) {
            cur = p->pool.link[cur].first_child;
            continue;
        }
        while (cur != 0 && p->pool.link[cur].next_sibling < 0)
            cur = p->pool.link[cur].parent;
        if (cur == 0)
            break;
        cur = p->pool.link[cur].next_sibling;
    }
    int32_t m = 0;
    for (int32_t i = 0; i < n; ++i)
        keep[i] = keep[i] ? m++ : -1;
    if (m == n)
        return 0;
    /* Pack (new index <= old index, so ascending order never overwrites a node still to move). */
    for (int32_t i = 0; i < n; ++i) {
        const int32_t k = keep[i];
        if (k < 0)
            continue;
        p->pool.xy[k] = p->pool.xy[i];
        p->pool.cost[k] = p->pool.cost[i];
        p->pool.link[k].parent = p->pool.link[i].parent >= 0 ? keep[p->pool.link[i].parent] : -1;
    }
    for (int32_t k = 0; k < m; ++k)
        p->pool.link[k].first_child = p->pool.link[k].next_sibling = -1;
    for (int32_t k = 1; k < m; ++k)
        attach(p, k, p->pool.link[k].parent);
    /* Solution candidates: every one of them that survived, in their order. */
    const int32_t best_node = keep[p->goal_idx[p->best_goal]];
    int32_t g = 0;
    for (int32_t s = 0; s < p->num_goal; ++s) {
        const int32_t k = keep[p->goal_idx[s]];
        if (k < 0)
            continue;
        if (k == best_node)
            p->best_goal = g;
        p->goal_idx[g] = k;
        p->goal_edge[g] = p->goal_edge[s];
        ++g;
    }
    p->num_goal = g;
    p->num_nodes = m;
    gmmrrt_nn_reset_adaptive(&p->nn, &pr->obstacles.bounds);
    for (int32_t k = 0; k < m; ++k)
        gmmrrt_nn_insert(&p->nn, &p->pool, k);
    gmmrrt_nn_relayout_sorted(&p->nn, &p->pool, m, p->goal_idx, p->num_goal);
    return n - m;
}

gmmrrt_status_t gmmrrt_planner_run(gmmrrt_planner_t *p, const gmmrrt_budget_t *budget, gmmrrt_plan_stats_t *stats)
{
    if (!p || !budget || !p->has_problem)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    if (isnan(budget->time_ms) || !isfinite(budget->converge_rel) || budget->converge_rel < 0.0 ||
        (budget->converge_rel > 0.0 && budget->converge_window <= 0))
        return GMMRRT_ERR_INVALID_ARGUMENT;
    const int timed = budget->time_ms > 0.0 && isfinite(budget->time_ms);
    if (!timed && budget->max_iterations <= 0 && budget->converge_rel <= 0.0)
        return GMMRRT_ERR_INVALID_ARGUMENT; /* no way to stop */

    const double t0 = now_ms();
    const double base_ms = p->time_ms;
    p->run_t0_ms = t0;
    p->run_base_ms = base_ms;
    const int64_t it0 = p->iterations;
    gmmrrt_status_t st = GMMRRT_OK;
    int timed_out = 0;
    /* The search's own extensions use the map's four-corner bound alone until the first path
     * (update_best turns the union on then); every other check, in and outside run(), has it. */
    gmmrrt_world_set_raster_union(p->world, p->first_solution_iteration >= 0);
    for (;;) {
        const int64_t done = p->iterations - it0;
        if (budget->max_iterations > 0 && done >= budget->max_iterations)
            break;
        if (timed && (done & 7) == 0) {
            if (now_ms() - t0 >= budget->time_ms) {
                timed_out = 1;
                break;
            }
        }
        if (budget->converge_rel > 0.0 && p->iterations - p->conv_ref_iter >= budget->converge_window) {
            const int converged = isfinite(p->best_cost) && isfinite(p->conv_ref_cost) &&
                                  p->conv_ref_cost - p->best_cost <= budget->converge_rel * p->best_cost;
            p->conv_ref_cost = p->best_cost;
            p->conv_ref_iter = p->iterations;
            if (converged)
                break;
        }
        if (p->num_nodes >= p->cfg.max_nodes) {
            const int32_t freed = prune(p);
            p->pruned += freed;
            if (freed <= p->cfg.max_nodes / 64) { /* too little to go on: a tree of the best path only */
                st = GMMRRT_POOL_FULL;
                break;
            }
        }
        if (p->connect.state == GMMRRT_CONNECT_GROWING) {
            gmmrrt_connect_iterate(p); /* no path yet: the connect phase (connect.c) */
            continue;
        }
        iterate(p);
    }
    gmmrrt_world_set_raster_union(p->world, 1);
#ifdef GMMRRT_TREE_CHECKS /* Debug builds (planner/CMakeLists.txt), where assert is on */
    assert(gmmrrt_tree_check(p, NULL, 0) && "a broken tree invariant (tree_check.h)");
#endif
    p->time_ms = base_ms + (now_ms() - t0);
    p->run_t0_ms = -1.0; /* outside run() (seed_path): time counts as before the run */
    p->run_base_ms = p->time_ms;
    if (st == GMMRRT_OK) {
        if (isfinite(p->best_cost))
            st = GMMRRT_OK;
        else if (timed_out && p->iterations == it0)
            st = GMMRRT_TIMEOUT;
        else
            st = p->side_active ? GMMRRT_NO_PATH_ON_SIDE : GMMRRT_NO_PATH_YET;
    }
    if (stats) {
        stats->iterations = p->iterations;
        stats->nodes = p->num_nodes;
        stats->first_solution_iteration = p->first_solution_iteration;
        stats->first_solution_ms = p->first_solution_ms;
        stats->best_cost = p->best_cost;
        stats->time_ms = p->time_ms;
        stats->setup_ms = p->setup_ms;
        stats->pruned = p->pruned;
    }
    return st;
}

gmmrrt_status_t gmmrrt_planner_seed_path(gmmrrt_planner_t *p, const double *x, const double *y, int32_t n)
{
    if (!p || !p->has_problem || n < 0 || (n > 0 && (!x || !y)))
        return GMMRRT_ERR_INVALID_ARGUMENT;
    for (int32_t i = 0; i < n; ++i)
        if (!finite2(x[i], y[i]))
            return GMMRRT_ERR_INVALID_ARGUMENT;
    int32_t prev = 0;
    for (int32_t i = 0; i < n; ++i) {
        const gmmrrt_xy_t *pn = &p->pool.xy[prev];
        const double pn_cost = p->pool.cost[prev];
        if (hypot(x[i] - pn->x, y[i] - pn->y) <= GMMRRT_SAME_POINT_M)
            continue;
        if (p->num_nodes >= p->cfg.max_nodes)
            return GMMRRT_POOL_FULL;
        if (!edge_allowed(p, pn->x, pn->y, x[i], y[i]))
            break; /* the rest of the old path starts from a blocked edge */
        const double c = pn_cost + gmmrrt_edge_cost(p, pn->x, pn->y, x[i], y[i]);
        prev = add_node(p, x[i], y[i], prev, c);
        consider_goal(p, prev);
    }
    update_best(p);
    return GMMRRT_OK;
}

int32_t gmmrrt_planner_cost_history(const gmmrrt_planner_t *p, int64_t *iterations, double *costs, int32_t cap)
{
    if (!p || cap <= 0 || !iterations || !costs)
        return 0;
    const int32_t n = p->hist_count < cap ? p->hist_count : cap;
    for (int32_t i = 0; i < n; ++i) {
        iterations[i] = p->hist_iter[i];
        costs[i] = p->hist_cost[i];
    }
    return n;
}

int32_t gmmrrt_planner_node_count(const gmmrrt_planner_t *p) { return p && p->has_problem ? p->num_nodes : 0; }

gmmrrt_status_t gmmrrt_planner_node(const gmmrrt_planner_t *p, int32_t i, double *x, double *y, int32_t *parent,
                                    double *cost)
{
    if (!p || !p->has_problem || i < 0 || i >= p->num_nodes)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    if (x)
        *x = p->pool.xy[i].x;
    if (y)
        *y = p->pool.xy[i].y;
    if (parent)
        *parent = p->pool.link[i].parent;
    if (cost)
        *cost = p->pool.cost[i];
    return GMMRRT_OK;
}

const gmmrrt_world_t *gmmrrt_planner_world(const gmmrrt_planner_t *p) { return p ? p->world : NULL; }

const char *gmmrrt_planner_escape_reason(const gmmrrt_planner_t *p) { return p ? p->escape.freeze_reason : ""; }
