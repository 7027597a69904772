/*
 * collision.c - the collision world of collision.h: a clearance grid of the static obstacles
 * built from FCL distance queries, kept or shifted while they stay the same, exact tests
 * against people, and the conservative point and segment tests the planning loop uses
 * (docs/planner.md, "Collision checking"; the paper's RRT* needs only a free/blocked answer,
 * Sect. 3 and Karaman & Frazzoli's CollisionFree).
 *
 * Grid: cell (i, j) is the world-frame lattice cell (gi0 + i, gj0 + j), centred at
 * ((gi0 + i + 0.5) res, (gj0 + j + 0.5) res), and stores min(C, clearance at its centre),
 * C = 4 cells, where clearance is the FCL distance from the robot disc centred there to the
 * nearest circle or box (0 when touching or overlapping). A cell's value depends only on its
 * place and the static obstacles, never on the bounds, which is what lets gmmrrt_world_update
 * keep it when only the bounds (and people, start, goal) move. Clearance is 1-Lipschitz, so
 * for any point q
 *     clearance(q) >= stored(c) - |q - c|
 * for every cell centre c; a point is declared free when that bound is positive for one
 * of the four centres around it. The test never calls a colliding point free; it may
 * call free points within about one cell of an obstacle blocked (the price of a query
 * that costs four loads). Segments are walked by sphere tracing on that bound.
 *
 * People (discs of person_radius_m) change every cycle in the daemon, so they are not in the
 * grid: a point is tested against each person's centre (distance > robot + person radius),
 * a segment by its exact point-to-segment distance to each centre.
 */
#include "gmmrrt/collision.h"

#include <math.h>
#include <string.h>

#include "block_layout.h"
#include "collision_internal.h"
#include "fcl_adapter.h"
#include "raster_bound.h"
#include "segment_exact.h"

#define GMMRRT_CLEARANCE_CAP_CELLS 4.0
/* Lattice indices are kept in doubles and must stay exact integers with room for + 0.5. */
#define GMMRRT_MAX_CELL_INDEX 1125899906842624.0 /* 2^50 */

/* Static obstacles up to which the queries use the closed forms over all of them instead of the
 * grid (chosen by measurement: docs/world.md). */
#ifndef GMMRRT_EXACT_MAX_OBSTACLES
#define GMMRRT_EXACT_MAX_OBSTACLES 8
#endif

/* With more statics, the first queries of each world use the closed forms too (a first path
 * needs few queries, and the tiles they would fill cost more than the queries), the rest the
 * grid (chosen by measurement: docs/world.md). */
#ifndef GMMRRT_EXACT_FIRST_QUERIES
#define GMMRRT_EXACT_FIRST_QUERIES 4096
#endif

/* Tiles: TILE x TILE cells, computed together on the first query that reads one of them. */
#define TILE_SHIFT 3
#define TILE (1 << TILE_SHIFT)
#define TILE_CELLS (TILE * TILE)

/* GMMRRT_EDGE_MIN_CLEARANCE_M (collision.h): edges closer than this are refused, which is what
 * keeps sphere tracing exact and finite (see gmmrrt_world_segment_free). */

struct gmmrrt_world {
    gmmrrt_obstacle_set_t obstacles; /* copy of the last problem's: the grid is built from its statics */
    double resolution_m;
    double inv_resolution;
    double robot_radius_m;
    double person_radius_m;
    double edge_resolution_m;
    double cap_m;
    double gi0, gj0; /* lattice index of cell (0, 0); integer-valued, a multiple of TILE */
    double gi0h, gj0h; /* gi0 + 0.5, gj0 + 0.5 (exact): cell (i, j) is centred at ((gi0h + i) res, (gj0h + j) res) */
    int32_t nx, ny;    /* cells: tnx * TILE, tny * TILE */
    int32_t tnx, tny;  /* tiles */
    int32_t max_cells;
    int32_t max_tiles;
    /* People that can come within reach of a point inside the bounds, for the exact tests. */
    int32_t num_near_people;
    double person_reach2;      /* (robot + person radius)^2, m^2: a point closer is blocked */
    double person_edge_reach;  /* robot + person radius + GMMRRT_EDGE_MIN_CLEARANCE_M, m */
    double person_edge_reach2;
    double near_px[GMMRRT_MAX_PEOPLE], near_py[GMMRRT_MAX_PEOPLE];
    double box_cos[GMMRRT_MAX_BOXES], box_sin[GMMRRT_MAX_BOXES]; /* of each box's yaw, for the closed forms */
    /* The occupancy raster of the problem (borrowed), its generation when the world was
     * updated, and the slack its bound gets for the rounding of a world point into cells (the
     * field itself is rounded down where it is stored). */
    const gmmrrt_raster_t *raster;
    uint32_t raster_generation;
    double raster_slack_m;
    /* 1 (the default): where the four-corner bound cannot decide, the union of the corners'
     * discs (gmmrrt_raster_clearance_union) may; the planner's search turns it off until its
     * first path (rrtstar.c, gmmrrt_planner_run), where coverage matters more than closeness. */
    int32_t raster_union;
    gmmrrt_world_grid_stats_t stats;
    int64_t lazy_cells; /* cells filled by queries since the last update */
    int32_t exact_only; /* at most GMMRRT_EXACT_MAX_OBSTACLES statics: no grid, closed forms */
    int64_t exact_queries_left; /* more statics: the first queries use the closed forms too */
    uint8_t *ready;    /* per tile, row-major (tj * tnx + ti): 1 once its cells are computed */
    float cells[];     /* per tile TILE_CELLS floats (tile-major, then row-major inside the tile) */
};

/* Compared with memcmp to decide whether the grid can be kept: no padding in them. */
_Static_assert(sizeof(gmmrrt_circle_t) == 3 * sizeof(double), "gmmrrt_circle_t has padding");
_Static_assert(sizeof(gmmrrt_box_t) == 5 * sizeof(double), "gmmrrt_box_t has padding");

/* Tiles a grid of grid_max_cells needs: every layout whose bounds fit the capacity as a
 * square fits in these tiles (the lattice's partial tiles at each side add at most one row
 * and one column of tiles, about sqrt(cells) / 4 cells of slack in all); a long thin one
 * may be cut (see layout_for). */
static int64_t max_tiles_for(int32_t grid_max_cells)
{
    const int64_t full = ((int64_t)grid_max_cells + TILE_CELLS - 1) / TILE_CELLS;
    return full + 2 * (int64_t)ceil(sqrt((double)full)) + 4;
}

size_t gmmrrt_world_mem_size(int32_t grid_max_cells)
{
    if (grid_max_cells < 1)
        return 0;
    const size_t tiles = (size_t)max_tiles_for(grid_max_cells);
    return gmmrrt_align8(sizeof(struct gmmrrt_world) + tiles * TILE_CELLS * sizeof(float)) + gmmrrt_align8(tiles);
}

static int finite_bounds(const gmmrrt_bounds_t *b)
{
    return isfinite(b->xmin) && isfinite(b->ymin) && isfinite(b->xmax) && isfinite(b->ymax) &&
           b->xmin < b->xmax && b->ymin < b->ymax;
}

static gmmrrt_status_t validate_obstacles(const gmmrrt_obstacle_set_t *o)
{
    if (!finite_bounds(&o->bounds))
        return GMMRRT_ERR_INVALID_ARGUMENT;
    if (o->num_circles < 0 || o->num_circles > GMMRRT_MAX_CIRCLES || o->num_boxes < 0 ||
        o->num_boxes > GMMRRT_MAX_BOXES || o->num_people < 0 || o->num_people > GMMRRT_MAX_PEOPLE)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    for (int32_t i = 0; i < o->num_circles; ++i) {
        const gmmrrt_circle_t *c = &o->circles[i];
        if (!isfinite(c->x) || !isfinite(c->y) || !isfinite(c->radius_m) || c->radius_m <= 0.0)
            return GMMRRT_ERR_INVALID_ARGUMENT;
    }
    for (int32_t i = 0; i < o->num_boxes; ++i) {
        const gmmrrt_box_t *b = &o->boxes[i];
        if (!isfinite(b->x) || !isfinite(b->y) || !isfinite(b->yaw) || !isfinite(b->width_m) ||
            !isfinite(b->height_m) || b->width_m <= 0.0 || b->height_m <= 0.0)
            return GMMRRT_ERR_INVALID_ARGUMENT;
    }
    for (int32_t i = 0; i < o->num_people; ++i) {
        const gmmrrt_pose_t *p = &o->people[i];
        if (!isfinite(p->x) || !isfinite(p->y) || !isfinite(p->yaw))
            return GMMRRT_ERR_INVALID_ARGUMENT;
    }
    if (o->raster && !gmmrrt_raster_distance_ready(o->raster))
        return GMMRRT_ERR_INVALID_ARGUMENT;
    return GMMRRT_OK;
}

/* The grid's tiles for the bounds: the lattice tiles that meet them, cut to the capacity. */
typedef struct {
    double gi0, gj0;
    int32_t tnx, tny;
} grid_layout_t;

static gmmrrt_status_t layout_for(const gmmrrt_bounds_t *b, double res, int32_t max_cells, int32_t max_tiles,
                                  grid_layout_t *out)
{
    /* The capacity check of the bounds' own extent, as it always was. */
    const double cw = ceil((b->xmax - b->xmin) / res), ch = ceil((b->ymax - b->ymin) / res);
    if (!(cw * ch <= (double)max_cells))
        return GMMRRT_ERR_BUFFER_TOO_SMALL;
    const double i0 = floor(b->xmin / res), i1 = ceil(b->xmax / res);
    const double j0 = floor(b->ymin / res), j1 = ceil(b->ymax / res);
    if (!(fabs(i0) <= GMMRRT_MAX_CELL_INDEX && fabs(i1) <= GMMRRT_MAX_CELL_INDEX &&
          fabs(j0) <= GMMRRT_MAX_CELL_INDEX && fabs(j1) <= GMMRRT_MAX_CELL_INDEX))
        return GMMRRT_ERR_INVALID_ARGUMENT;
    const double ti0 = floor(i0 / TILE), ti1 = ceil(i1 / TILE), tj0 = floor(j0 / TILE), tj1 = ceil(j1 / TILE);
    /* A long thin problem may need more tiles than the capacity holds; then the last columns or
     * rows are left out. Nothing depends on the grid covering the bounds: any cell's bound is
     * valid everywhere, only weaker further away (the exact test then decides). */
    double tnx = fmax(ti1 - ti0, 1.0), tny = fmax(tj1 - tj0, 1.0);
    if (tnx * tny > (double)max_tiles)
        tnx = fmax(floor((double)max_tiles / tny), 1.0);
    if (tnx * tny > (double)max_tiles)
        tny = fmax(floor((double)max_tiles / tnx), 1.0);
    out->gi0 = ti0 * TILE;
    out->gj0 = tj0 * TILE;
    out->tnx = (int32_t)tnx;
    out->tny = (int32_t)tny;
    return GMMRRT_OK;
}

/* Signed distance (m) from (x, y) to circle k / box k: negative inside (minus the depth). The
 * closed forms of what FCL computes (fcl_adapter.h); the grid and the exact tests use them. */
static double circle_distance(const gmmrrt_circle_t *c, double x, double y)
{
    const double dx = x - c->x, dy = y - c->y;
    return sqrt(dx * dx + dy * dy) - c->radius_m; /* plain sqrt: map coordinates */
}

static double box_distance(const struct gmmrrt_world *w, int32_t k, double x, double y)
{
    const gmmrrt_box_t *b = &w->obstacles.boxes[k];
    const double dx = x - b->x, dy = y - b->y;
    const double lx = dx * w->box_cos[k] + dy * w->box_sin[k], ly = -dx * w->box_sin[k] + dy * w->box_cos[k];
    const double qx = fabs(lx) - 0.5 * b->width_m, qy = fabs(ly) - 0.5 * b->height_m;
    const double ox = qx > 0.0 ? qx : 0.0, oy = qy > 0.0 ? qy : 0.0;
    const double in = qx > qy ? qx : qy; /* <= 0 inside: minus the depth */
    return (in > 0.0) ? sqrt(ox * ox + oy * oy) : in;
}

/* Computes tile t's cells: min(cap, clearance at the centre), clearance from the closed forms,
 * rounded down to float so a stored value stays a lower bound. Only the obstacles that come
 * within robot radius + cap of some cell of the tile are looked at; every other one is
 * farther than the cap from each cell. Cost: one distance per obstacle, then one per cell and
 * near obstacle: at most (circles + boxes) (1 + TILE_CELLS). */
static void fill_tile(struct gmmrrt_world *w, int32_t t)
{
    const int32_t ti = t % w->tnx, tj = t / w->tnx;
    const double res = w->resolution_m;
    const double x0 = (w->gi0h + (double)(ti * TILE)) * res, y0 = (w->gj0h + (double)(tj * TILE)) * res;
    const double half = 0.5 * (TILE - 1) * res;
    const double cx = x0 + half, cy = y0 + half;
    const double reach = w->robot_radius_m + w->cap_m + half * 1.4142135623730951 + 1e-9;
    const gmmrrt_obstacle_set_t *o = &w->obstacles;
    int32_t near_c[GMMRRT_MAX_CIRCLES], near_b[GMMRRT_MAX_BOXES], nc = 0, nb = 0;
    for (int32_t k = 0; k < o->num_circles; ++k)
        if (circle_distance(&o->circles[k], cx, cy) <= reach)
            near_c[nc++] = k;
    for (int32_t k = 0; k < o->num_boxes; ++k)
        if (box_distance(w, k, cx, cy) <= reach)
            near_b[nb++] = k;
    float *cell = w->cells + (size_t)t * TILE_CELLS;
    const double top = w->robot_radius_m + w->cap_m;
    for (int32_t j = 0; j < TILE; ++j) {
        const double y = (w->gj0h + (double)(tj * TILE + j)) * res; /* the same centres as clearance_lower_bound */
        for (int32_t i = 0; i < TILE; ++i) {
            const double x = (w->gi0h + (double)(ti * TILE + i)) * res;
            double best = top;
            for (int32_t q = 0; q < nc; ++q) {
                const double d = circle_distance(&o->circles[near_c[q]], x, y);
                best = d < best ? d : best;
            }
            for (int32_t q = 0; q < nb; ++q) {
                const double d = box_distance(w, near_b[q], x, y);
                best = d < best ? d : best;
            }
            const double d = best - w->robot_radius_m;
            float f = (float)d;
            if ((double)f > d)
                f = nextafterf(f, -INFINITY);
            cell[j * TILE + i] = f;
        }
    }
    w->ready[t] = 1;
    w->lazy_cells += TILE_CELLS;
}

/* Moves the tiles the old layout shares with the new one (cells and ready flags) to their new
 * places, in place. Row J moves by delta(J), which is linear in J: first the rows moving down
 * (delta <= 0) in ascending J, then those moving up in descending J; no row is overwritten
 * before it has moved (the destinations keep the rows' order). */
static void move_shared_tiles(struct gmmrrt_world *w, const grid_layout_t *old, const grid_layout_t *nw,
                              int32_t ai, int32_t bi, int32_t aj, int32_t bj)
{
    /* ai..bi, aj..bj: shared tile columns and rows as local indices of the new layout (exclusive). */
    const int32_t di = (int32_t)((nw->gi0 - old->gi0) / TILE), dj = (int32_t)((nw->gj0 - old->gj0) / TILE);
    const size_t n = (size_t)(bi - ai);
    for (int pass = 0; pass < 2; ++pass) {
        for (int32_t k = 0; k < bj - aj; ++k) {
            const int32_t j = pass == 0 ? aj + k : bj - 1 - k;
            const ptrdiff_t src = (ptrdiff_t)(j + dj) * old->tnx + (ai + di);
            const ptrdiff_t dst = (ptrdiff_t)j * nw->tnx + ai;
            if ((pass == 0) == (dst <= src)) {
                memmove(w->cells + dst * TILE_CELLS, w->cells + src * TILE_CELLS, n * TILE_CELLS * sizeof(float));
                memmove(w->ready + dst, w->ready + src, n);
            }
        }
    }
}

static int same_statics(const struct gmmrrt_world *w, int32_t grid_max_cells, double resolution_m,
                        double robot_radius_m, const gmmrrt_obstacle_set_t *o)
{
    const gmmrrt_obstacle_set_t *k = &w->obstacles;
    return w->max_cells == grid_max_cells && memcmp(&w->resolution_m, &resolution_m, sizeof(double)) == 0 &&
           memcmp(&w->robot_radius_m, &robot_radius_m, sizeof(double)) == 0 && k->num_circles == o->num_circles &&
           k->num_boxes == o->num_boxes &&
           memcmp(k->circles, o->circles, (size_t)o->num_circles * sizeof o->circles[0]) == 0 &&
           memcmp(k->boxes, o->boxes, (size_t)o->num_boxes * sizeof o->boxes[0]) == 0;
}

/* People whose disc (plus the edge margin) can reach a point inside the bounds. */
static void set_people(struct gmmrrt_world *w)
{
    const gmmrrt_obstacle_set_t *o = &w->obstacles;
    const gmmrrt_bounds_t *b = &o->bounds;
    const double reach = w->robot_radius_m + w->person_radius_m;
    w->person_reach2 = reach * reach;
    w->person_edge_reach = reach + GMMRRT_EDGE_MIN_CLEARANCE_M;
    w->person_edge_reach2 = w->person_edge_reach * w->person_edge_reach;
    w->num_near_people = 0;
    if (!(w->person_radius_m > 0.0))
        return; /* people of radius 0 are not obstacles (as exact_clearance) */
    const double m = w->person_edge_reach + GMMRRT_EDGE_MIN_CLEARANCE_M;
    for (int32_t k = 0; k < o->num_people; ++k) {
        const gmmrrt_pose_t *p = &o->people[k];
        if (p->x < b->xmin - m || p->x > b->xmax + m || p->y < b->ymin - m || p->y > b->ymax + m)
            continue;
        w->near_px[w->num_near_people] = p->x;
        w->near_py[w->num_near_people] = p->y;
        w->num_near_people++;
    }
}

gmmrrt_status_t gmmrrt_world_update(gmmrrt_world_t **world, void *mem, size_t size, int32_t grid_max_cells,
                                    double resolution_m, double robot_radius_m, double person_radius_m,
                                    const gmmrrt_obstacle_set_t *obstacles)
{
    if (!world)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    struct gmmrrt_world *prev = *world;
    *world = NULL;
    if (!mem || !obstacles || grid_max_cells < 1 || !isfinite(resolution_m) || resolution_m <= 0.0 ||
        !isfinite(robot_radius_m) || robot_radius_m < 0.0 || !isfinite(person_radius_m) ||
        person_radius_m < 0.0 || ((uintptr_t)mem & 7u) != 0 || (prev && (void *)prev != mem))
        return GMMRRT_ERR_INVALID_ARGUMENT;
    if (size < gmmrrt_world_mem_size(grid_max_cells))
        return GMMRRT_ERR_BUFFER_TOO_SMALL;
    gmmrrt_status_t st = validate_obstacles(obstacles);
    if (st != GMMRRT_OK)
        return st;
    const int32_t max_tiles = (int32_t)max_tiles_for(grid_max_cells);
    grid_layout_t nw;
    st = layout_for(&obstacles->bounds, resolution_m, grid_max_cells, max_tiles, &nw);
    if (st != GMMRRT_OK)
        return st;

    struct gmmrrt_world *w = mem;
    const int keep = prev && same_statics(w, grid_max_cells, resolution_m, robot_radius_m, obstacles);
    const grid_layout_t old = keep ? (grid_layout_t){w->gi0, w->gj0, w->tnx, w->tny} : (grid_layout_t){0};
    const gmmrrt_world_grid_stats_t counts = prev ? w->stats : (gmmrrt_world_grid_stats_t){0};

    w->obstacles.bounds = obstacles->bounds;
    w->obstacles.num_circles = obstacles->num_circles;
    memcpy(w->obstacles.circles, obstacles->circles, (size_t)obstacles->num_circles * sizeof obstacles->circles[0]);
    w->obstacles.num_boxes = obstacles->num_boxes;
    memcpy(w->obstacles.boxes, obstacles->boxes, (size_t)obstacles->num_boxes * sizeof obstacles->boxes[0]);
    w->obstacles.num_people = obstacles->num_people;
    memcpy(w->obstacles.people, obstacles->people, (size_t)obstacles->num_people * sizeof obstacles->people[0]);
    w->obstacles.raster = obstacles->raster;
    w->resolution_m = resolution_m;
    w->inv_resolution = 1.0 / resolution_m;
    w->robot_radius_m = robot_radius_m;
    w->person_radius_m = person_radius_m;
    w->edge_resolution_m = resolution_m;
    w->cap_m = GMMRRT_CLEARANCE_CAP_CELLS * resolution_m;
    w->gi0 = nw.gi0;
    w->gj0 = nw.gj0;
    w->gi0h = nw.gi0 + 0.5;
    w->gj0h = nw.gj0 + 0.5;
    w->tnx = nw.tnx;
    w->tny = nw.tny;
    w->nx = nw.tnx * TILE;
    w->ny = nw.tny * TILE;
    w->max_cells = grid_max_cells;
    w->max_tiles = max_tiles;
    w->ready = (uint8_t *)mem + gmmrrt_align8(sizeof(struct gmmrrt_world) + (size_t)max_tiles * TILE_CELLS * sizeof(float));
    w->stats = counts;
    w->exact_only = obstacles->num_circles + obstacles->num_boxes <= GMMRRT_EXACT_MAX_OBSTACLES;
    w->exact_queries_left = GMMRRT_EXACT_FIRST_QUERIES;
    w->raster = obstacles->raster;
    w->raster_generation = obstacles->raster ? obstacles->raster->generation : 0;
    w->raster_slack_m = obstacles->raster ? 1e-9 : 0.0;
    w->raster_union = 1; /* the tightest bound unless the planner's search says otherwise */
    set_people(w);
    for (int32_t k = 0; k < obstacles->num_boxes; ++k) {
        w->box_cos[k] = cos(obstacles->boxes[k].yaw);
        w->box_sin[k] = sin(obstacles->boxes[k].yaw);
    }

    /* Shared tiles as local indices of the new layout (exclusive ends); none when the
     * statics changed. Every other tile is marked not computed: the queries fill it. */
    int32_t ai = 0, bi = 0, aj = 0, bj = 0;
    if (keep) {
        const double ai_d = (fmax(old.gi0, nw.gi0) - nw.gi0) / TILE,
                     bi_d = (fmin(old.gi0 + old.tnx * TILE, nw.gi0 + nw.tnx * TILE) - nw.gi0) / TILE;
        const double aj_d = (fmax(old.gj0, nw.gj0) - nw.gj0) / TILE,
                     bj_d = (fmin(old.gj0 + old.tny * TILE, nw.gj0 + nw.tny * TILE) - nw.gj0) / TILE;
        if (ai_d < bi_d && aj_d < bj_d) {
            ai = (int32_t)ai_d;
            bi = (int32_t)bi_d;
            aj = (int32_t)aj_d;
            bj = (int32_t)bj_d;
        }
    }
    if (ai < bi) {
        const int same = old.gi0 == nw.gi0 && old.gj0 == nw.gj0 && old.tnx == nw.tnx && old.tny == nw.tny;
        if (!same) {
            move_shared_tiles(w, &old, &nw, ai, bi, aj, bj);
            for (int32_t tj = 0; tj < nw.tny; ++tj)
                for (int32_t ti = 0; ti < nw.tnx; ++ti)
                    if (tj < aj || tj >= bj || ti < ai || ti >= bi)
                        w->ready[tj * nw.tnx + ti] = 0;
        }
        w->stats.last = same ? GMMRRT_GRID_KEPT : GMMRRT_GRID_SHIFTED;
        if (same)
            w->stats.kept++;
        else
            w->stats.shifted++;
    } else {
        memset(w->ready, 0, (size_t)nw.tnx * (size_t)nw.tny);
        w->stats.last = GMMRRT_GRID_BUILT;
        w->stats.built++;
    }
    w->stats.last_cells = 0;
    w->lazy_cells = 0;
    *world = w;
    return GMMRRT_OK;
}

gmmrrt_status_t gmmrrt_world_build(gmmrrt_world_t **out, void *mem, size_t size, int32_t grid_max_cells,
                                   double resolution_m, double robot_radius_m, double person_radius_m,
                                   const gmmrrt_obstacle_set_t *obstacles)
{
    if (!out)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    *out = NULL;
    return gmmrrt_world_update(out, mem, size, grid_max_cells, resolution_m, robot_radius_m, person_radius_m,
                               obstacles);
}

gmmrrt_status_t gmmrrt_world_grid_stats(const gmmrrt_world_t *world, gmmrrt_world_grid_stats_t *out)
{
    if (!world || !out)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    *out = world->stats;
    return GMMRRT_OK;
}

/* Cell (i, j)'s stored value, its tile computed first when no query has read it yet. The
 * world is written (the tile and its flag) through a const pointer: the memory is the
 * caller's writable block, and a query's answer does not depend on which tiles were ready. */
static double cell_value(const struct gmmrrt_world *w, int32_t i, int32_t j)
{
    const int32_t t = (j >> TILE_SHIFT) * w->tnx + (i >> TILE_SHIFT);
    if (!w->ready[t])
        fill_tile((struct gmmrrt_world *)(uintptr_t)w, t);
    return (double)w->cells[(size_t)t * TILE_CELLS + (size_t)(((j & (TILE - 1)) << TILE_SHIFT) | (i & (TILE - 1)))];
}

/* Lower bound on the clearance from static obstacles at (x, y), from the four cell centres
 * around it (clamped to the grid: any cell's bound holds everywhere, only weaker). */
static double clearance_lower_bound(const struct gmmrrt_world *w, double x, double y)
{
    const double res = w->resolution_m;
    const double u = x * w->inv_resolution - w->gi0h, v = y * w->inv_resolution - w->gj0h;
    /* The point is inside the bounds, so u is within [-1, nx + 1] or so (the lattice cells
     * start at or before xmin) and the conversion is safe; the corners are clamped below. */
    const int32_t i0 = (int32_t)floor(u), j0 = (int32_t)floor(v);
    double best = -INFINITY;
    for (int32_t dj = 0; dj <= 1; ++dj) {
        int32_t j = j0 + dj;
        if (j < 0)
            j = 0;
        if (j >= w->ny)
            j = w->ny - 1;
        for (int32_t di = 0; di <= 1; ++di) {
            int32_t i = i0 + di;
            if (i < 0)
                i = 0;
            if (i >= w->nx)
                i = w->nx - 1;
            const double cx = (w->gi0h + (double)i) * res, cy = (w->gj0h + (double)j) * res;
            const double s = cell_value(w, i, j);
            const double dx = x - cx, dy = y - cy; /* plain sqrt: hypot is ~10x slower, no overflow here */
            const double lb = s - sqrt(dx * dx + dy * dy);
            if (lb > best)
                best = lb;
        }
    }
    return best;
}

/* The static obstacles that can come within reach of a region: those whose bounding circle
 * comes within robot radius + cap of the box [xlo, xhi] x [ylo, yhi]. Every other obstacle is
 * farther than that from each point of the box, so its clearance there exceeds the cap, and the
 * exact clearance needs only these (a long edge along a wall probes many times; with 64 + 64
 * obstacles each probe would otherwise test them all). Filled on first need (`ready`). */
typedef struct {
    int ready;
    double xlo, ylo, xhi, yhi;
    int32_t n_circles, n_boxes;
    int32_t circle[GMMRRT_MAX_CIRCLES], box[GMMRRT_MAX_BOXES];
} near_statics_t;

static void set_near_box(near_statics_t *n, double xlo, double ylo, double xhi, double yhi)
{
    n->ready = 0;
    n->xlo = xlo;
    n->ylo = ylo;
    n->xhi = xhi;
    n->yhi = yhi;
}

static void find_near_statics(const struct gmmrrt_world *w, near_statics_t *n)
{
    const gmmrrt_obstacle_set_t *o = &w->obstacles;
    const double reach = w->robot_radius_m + w->cap_m;
    n->n_circles = n->n_boxes = 0;
    for (int32_t k = 0; k < o->num_circles; ++k) {
        const gmmrrt_circle_t *c = &o->circles[k];
        const double r = c->radius_m + reach;
        if (!(c->x < n->xlo - r || c->x > n->xhi + r || c->y < n->ylo - r || c->y > n->yhi + r))
            n->circle[n->n_circles++] = k;
    }
    for (int32_t k = 0; k < o->num_boxes; ++k) {
        const gmmrrt_box_t *b = &o->boxes[k];
        const double r = 0.5 * sqrt(b->width_m * b->width_m + b->height_m * b->height_m) + reach;
        if (!(b->x < n->xlo - r || b->x > n->xhi + r || b->y < n->ylo - r || b->y > n->yhi + r))
            n->box[n->n_boxes++] = k;
    }
    n->ready = 1;
}

/* Exact clearance from the static obstacles at (x, y) inside n's box, at most the cap: closed
 * forms of what FCL computes for the grid (the robot disc against each circle and oriented
 * box: centre distance to the shape minus the robot's radius, negative inside). Only called
 * where the grid's bound cannot decide (at and within about a cell of an obstacle), where the
 * true clearance is below the cap, so the cap changes nothing there. */
static double exact_static_clearance(const struct gmmrrt_world *w, near_statics_t *n, double x, double y)
{
    if (!n->ready)
        find_near_statics(w, n);
    const gmmrrt_obstacle_set_t *o = &w->obstacles;
    double best = w->robot_radius_m + w->cap_m; /* obstacles not in n are farther */
    for (int32_t q = 0; q < n->n_circles; ++q) {
        const double d = circle_distance(&o->circles[n->circle[q]], x, y);
        best = d < best ? d : best;
    }
    for (int32_t q = 0; q < n->n_boxes; ++q) {
        const double d = box_distance(w, n->box[q], x, y);
        best = d < best ? d : best;
    }
    return best - w->robot_radius_m;
}

/* The grid's bound at (x, y), or the exact clearance where the bound is at most `need` (so it
 * cannot prove what the caller needs); both are lower bounds of the true clearance and
 * 1-Lipschitz in (x, y). EXACT_MARGIN_M absorbs the closed forms' rounding against FCL.
 * (x, y) must lie in n's box. */
#define EXACT_MARGIN_M 1e-9
static double static_clearance_obstacles(const struct gmmrrt_world *w, near_statics_t *n, double x, double y,
                                         double need)
{
    if (w->exact_only || w->exact_queries_left > 0) {
        /* Few obstacles: the closed forms over all of them, uncapped (long steps for the edges'
         * sphere tracing), cheaper than filling the tiles a search reaches. */
        const gmmrrt_obstacle_set_t *o = &w->obstacles;
        double best = INFINITY;
        for (int32_t k = 0; k < o->num_circles; ++k) {
            const double d = circle_distance(&o->circles[k], x, y);
            best = d < best ? d : best;
        }
        for (int32_t k = 0; k < o->num_boxes; ++k) {
            const double d = box_distance(w, k, x, y);
            best = d < best ? d : best;
        }
        (void)n;
        (void)need;
        if (!w->exact_only)
            ((struct gmmrrt_world *)(uintptr_t)w)->exact_queries_left--;
        return best - w->robot_radius_m - EXACT_MARGIN_M;
    }
    const double lb = clearance_lower_bound(w, x, y);
    if (lb > need)
        return lb;
    const double exact = exact_static_clearance(w, n, x, y) - EXACT_MARGIN_M;
    return exact > lb ? exact : lb;
}

/* The clearance from everything static (obstacles and the raster's blocked cells) as
 * static_clearance_obstacles: a lower bound of the true clearance, at most `need` when that
 * cannot be proved. The raster's part is its distance field's bound (raster.h: to the blocked
 * cells' squares, exact at the cells' corners; where the four-corner bound cannot decide, the
 * corners' discs together, except in the search's extensions before its first path) less the
 * robot's radius: never closer to a blocked cell than the robot's radius. That part may jump
 * across a cell's edge (raster.h); the sphere tracing needs only that it stays below the true
 * clearance, which is 1-Lipschitz. */
static double static_clearance(const struct gmmrrt_world *w, near_statics_t *n, double x, double y, double need)
{
    if (w->raster) {
        /* The raster's bound is the whole answer for the map: when it is at most `need`, so
         * is the minimum, and the caller refuses whatever the obstacles add. */
        double u, v, lb;
        gmmrrt_raster_to_cells(w->raster, x, y, &u, &v);
        if (!gmmrrt_raster_interior_bound(w->raster, u, v, &lb))
            lb = gmmrrt_raster_clearance_bound(w->raster, x, y);
        double lm = lb - w->raster_slack_m - w->robot_radius_m;
        if (!(lm > need) && w->raster_union) { /* near a wall: the corners' discs together prove more */
            const double lu = gmmrrt_raster_clearance_union(w->raster, x, y) - w->raster_slack_m - w->robot_radius_m;
            lm = lu > lm ? lu : lm;
        }
        /* Without circles and boxes the obstacles' clearance is infinite: the map alone. */
        if (!(lm > need) || w->obstacles.num_circles + w->obstacles.num_boxes == 0)
            return lm;
        const double ls = static_clearance_obstacles(w, n, x, y, need);
        return ls < lm ? ls : lm;
    }
    return static_clearance_obstacles(w, n, x, y, need);
}

static int inside_bounds(const struct gmmrrt_world *w, double x, double y)
{
    const gmmrrt_bounds_t *b = &w->obstacles.bounds;
    return x >= b->xmin && x <= b->xmax && y >= b->ymin && y <= b->ymax;
}

/* 1 when the robot at (x, y) touches no person: centre distance > robot + person radius. */
static int people_point_free(const struct gmmrrt_world *w, double x, double y)
{
    for (int32_t k = 0; k < w->num_near_people; ++k) {
        const double dx = x - w->near_px[k], dy = y - w->near_py[k];
        if (dx * dx + dy * dy <= w->person_reach2)
            return 0;
    }
    return 1;
}

/* 1 when every point of the segment (x0, y0) + t (dx, dy), t in [0, 1], len2 = dx^2 + dy^2 > 0,
 * keeps more than GMMRRT_EDGE_MIN_CLEARANCE_M from every person: exact point-segment distance
 * to each centre. */
static int people_segment_free(const struct gmmrrt_world *w, double x0, double y0, double dx, double dy,
                               double len2)
{
    const double e = w->person_edge_reach;
    const double x1 = x0 + dx, y1 = y0 + dy;
    const double xlo = (dx < 0.0 ? x1 : x0) - e, xhi = (dx < 0.0 ? x0 : x1) + e;
    const double ylo = (dy < 0.0 ? y1 : y0) - e, yhi = (dy < 0.0 ? y0 : y1) + e;
    for (int32_t k = 0; k < w->num_near_people; ++k) {
        const double px = w->near_px[k], py = w->near_py[k];
        if (px < xlo || px > xhi || py < ylo || py > yhi)
            continue;
        double t = ((px - x0) * dx + (py - y0) * dy) / len2;
        t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
        const double ex = x0 + t * dx - px, ey = y0 + t * dy - py;
        if (ex * ex + ey * ey <= w->person_edge_reach2)
            return 0;
    }
    return 1;
}

int gmmrrt_world_point_free(const gmmrrt_world_t *world, double x, double y)
{
    if (!world || !isfinite(x) || !isfinite(y) || !inside_bounds(world, x, y))
        return 0;
    if (!world->raster && (world->exact_only || world->exact_queries_left > 0)) {
        /* While the closed forms answer: the same test, squared distances (segment_exact.h). */
        if (!world->exact_only)
            ((struct gmmrrt_world *)(uintptr_t)world)->exact_queries_left--;
        return gmmrrt_point_clear_of_shapes(&world->obstacles, world->box_cos, world->box_sin,
                                            world->robot_radius_m + EXACT_MARGIN_M, x, y) &&
               people_point_free(world, x, y);
    }
    near_statics_t near; /* not zero-initialised: 0.5 KB per query; filled on first need */
    set_near_box(&near, x, y, x, y);
    return static_clearance(world, &near, x, y, 0.0) > 0.0 && people_point_free(world, x, y);
}

int gmmrrt_world_point_leavable(const gmmrrt_world_t *world, double x, double y)
{
    if (!gmmrrt_world_point_free(world, x, y))
        return 0;
    /* The start conditions of gmmrrt_world_segment_free for an edge from (x, y). */
    near_statics_t near;
    set_near_box(&near, x, y, x, y);
    if (!(static_clearance(world, &near, x, y, GMMRRT_EDGE_MIN_CLEARANCE_M) > GMMRRT_EDGE_MIN_CLEARANCE_M))
        return 0;
    for (int32_t k = 0; k < world->num_near_people; ++k) {
        const double dx = x - world->near_px[k], dy = y - world->near_py[k];
        if (dx * dx + dy * dy <= world->person_edge_reach2)
            return 0;
    }
    return 1;
}

int gmmrrt_world_segment_free(const gmmrrt_world_t *world, double x0, double y0, double x1, double y1)
{
    if (!world)
        return 0;
    /* Walk from the lexicographically smaller end so (a, b) and (b, a) get the same answer. */
    if (x1 < x0 || (x1 == x0 && y1 < y0)) {
        double t = x0;
        x0 = x1;
        x1 = t;
        t = y0;
        y0 = y1;
        y1 = t;
    }
    if (!isfinite(x0) || !isfinite(y0) || !isfinite(x1) || !isfinite(y1) || !inside_bounds(world, x0, y0) ||
        !inside_bounds(world, x1, y1))
        return 0;
    if (!world->raster && (world->exact_only || world->exact_queries_left > 0)) {
        /* While the closed forms answer: the exact segment test, one distance per shape
         * (segment_exact.h), refusing what comes within the edge margin as the walk below does. */
        if (!world->exact_only)
            ((struct gmmrrt_world *)(uintptr_t)world)->exact_queries_left--;
        const double ex = x1 - x0, ey = y1 - y0, el2 = ex * ex + ey * ey;
        if (!gmmrrt_segment_clear_of_shapes(&world->obstacles, world->box_cos, world->box_sin,
                                            world->robot_radius_m + GMMRRT_EDGE_MIN_CLEARANCE_M + EXACT_MARGIN_M,
                                            x0, y0, x1, y1))
            return 0;
        return el2 == 0.0 ? people_point_free(world, x0, y0) : people_segment_free(world, x0, y0, ex, ey, el2);
    }
    /* The end points' clearance bounds (as gmmrrt_world_point_free) are also the first probes. */
    const double m = GMMRRT_EDGE_MIN_CLEARANCE_M;
    near_statics_t near; /* not zero-initialised: 0.5 KB per query; filled on first need */
    set_near_box(&near, x0, y0 < y1 ? y0 : y1, x1, y0 < y1 ? y1 : y0);
    const double lb0 = static_clearance(world, &near, x0, y0, m), lb1 = static_clearance(world, &near, x1, y1, m);
    if (!(lb0 > 0.0) || !(lb1 > 0.0))
        return 0;
    const double dx = x1 - x0, dy = y1 - y0;
    const double len2 = dx * dx + dy * dy;
    if (len2 == 0.0)
        return people_point_free(world, x0, y0);
    if (!people_segment_free(world, x0, y0, dx, dy, len2))
        return 0;
    /* From here on only the static obstacles of the grid. */
    const double len = sqrt(len2); /* plain sqrt: map coordinates, no overflow */
    /* Free discs of radius lb0 and lb1 around the ends that overlap cover the whole edge
     * (same clearance floor as the walk below). */
    if (lb0 > GMMRRT_EDGE_MIN_CLEARANCE_M && lb1 > GMMRRT_EDGE_MIN_CLEARANCE_M && lb0 + lb1 > len)
        return 1;
    const double ux = dx / len, uy = dy / len;
    /* Bounds are convex and both ends are inside, so every point between is inside. */
    /* Sphere tracing: lb is a lower bound on the exact clearance and clearance is 1-Lipschitz, so
     * the robot is free everywhere within lb of the probe and a step of lb never skips an obstacle,
     * not even a corner cut between probes. Edges that pass closer than GMMRRT_EDGE_MIN_CLEARANCE_M
     * are refused instead of walked in ever smaller steps; that bounds the probes per edge by
     * len / GMMRRT_EDGE_MIN_CLEARANCE_M. */
    if (!(lb0 > GMMRRT_EDGE_MIN_CLEARANCE_M))
        return 0;
    double s = lb0;
    if (s >= len)
        return 1;
    for (;;) {
        const double lb = static_clearance(world, &near, x0 + s * ux, y0 + s * uy, m);
        if (!(lb > GMMRRT_EDGE_MIN_CLEARANCE_M))
            return 0;
        s += lb;
        if (s >= len)
            return 1; /* the end point was checked above */
    }
}

double gmmrrt_world_exact_clearance(const gmmrrt_world_t *world, double x, double y)
{
    if (!world || !isfinite(x) || !isfinite(y))
        return NAN;
    const gmmrrt_obstacle_set_t *o = &world->obstacles;
    const double r = world->robot_radius_m;
    double best = INFINITY;
    for (int32_t k = 0; k < o->num_circles; ++k) {
        const gmmrrt_circle_t *c = &o->circles[k];
        double d = gmmrrt_fcl_disc_distance(x, y, r, c->x, c->y, c->radius_m);
        if (d <= 0.0)
            d = -gmmrrt_fcl_disc_penetration(x, y, r, c->x, c->y, c->radius_m);
        if (d < best)
            best = d;
    }
    for (int32_t k = 0; k < o->num_people && world->person_radius_m > 0.0; ++k) {
        const gmmrrt_pose_t *p = &o->people[k];
        double d = gmmrrt_fcl_disc_distance(x, y, r, p->x, p->y, world->person_radius_m);
        if (d <= 0.0)
            d = -gmmrrt_fcl_disc_penetration(x, y, r, p->x, p->y, world->person_radius_m);
        if (d < best)
            best = d;
    }
    for (int32_t k = 0; k < o->num_boxes; ++k) {
        const gmmrrt_box_t *b = &o->boxes[k];
        double d = gmmrrt_fcl_box_distance(x, y, r, b->x, b->y, b->width_m, b->height_m, b->yaw);
        if (d <= 0.0)
            d = -gmmrrt_fcl_box_penetration(x, y, r, b->x, b->y, b->width_m, b->height_m, b->yaw);
        if (d < best)
            best = d;
    }
    if (world->raster) {
        /* Brute force over the blocked cells within reach: an oracle, not for the loop. */
        const double reach = isfinite(best) ? best + r : world->raster->resolution_m * 
            (double)(world->raster->width + world->raster->height) + fabs(x) + fabs(y);
        const double d = gmmrrt_world_map_clearance(world, x, y, reach);
        if (d < best)
            best = d;
    }
    return best;
}

double gmmrrt_world_map_clearance(const gmmrrt_world_t *world, double x, double y, double cap_m)
{
    if (!world || !isfinite(x) || !isfinite(y))
        return NAN;
    if (!world->raster)
        return INFINITY;
    return gmmrrt_raster_distance_to_blocked(world->raster, x, y, cap_m) - world->robot_radius_m;
}

/* Internal (declared in planner_internal.h): the planner sets the segment step. */
void gmmrrt_world_set_edge_resolution(gmmrrt_world_t *world, double edge_resolution_m);
void gmmrrt_world_set_edge_resolution(gmmrrt_world_t *world, double edge_resolution_m)
{
    if (world && isfinite(edge_resolution_m) && edge_resolution_m > 0.0)
        world->edge_resolution_m = edge_resolution_m;
}

/* Internal (declared in planner_internal.h): the planner turns the union bound on and off. */
void gmmrrt_world_set_raster_union(gmmrrt_world_t *world, int on);
void gmmrrt_world_set_raster_union(gmmrrt_world_t *world, int on)
{
    if (world)
        world->raster_union = on != 0;
}

int64_t gmmrrt_world_lazy_cells(const gmmrrt_world_t *world) { return world ? world->lazy_cells : -1; }

int gmmrrt_world_grid_layout(const gmmrrt_world_t *world, int32_t *nx, int32_t *ny, double *gi0, double *gj0)
{
    if (!world || !nx || !ny || !gi0 || !gj0)
        return 0;
    *nx = world->nx;
    *ny = world->ny;
    *gi0 = world->gi0;
    *gj0 = world->gj0;
    return 1;
}

float gmmrrt_world_grid_cell(const gmmrrt_world_t *world, int32_t i, int32_t j)
{
    if (!world || i < 0 || j < 0 || i >= world->nx || j >= world->ny)
        return NAN;
    return (float)cell_value(world, i, j);
}

int64_t gmmrrt_world_grid_tiles_ready(const gmmrrt_world_t *world)
{
    if (!world)
        return -1;
    int64_t n = 0;
    for (int32_t t = 0; t < world->tnx * world->tny; ++t)
        n += world->ready[t];
    return n;
}
