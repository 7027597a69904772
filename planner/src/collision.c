/*
 * collision.c - the collision world of collision.h: a clearance grid built from FCL
 * distance queries when the world changes, and the conservative point and segment tests
 * the planning loop uses (docs/planner.md, "Collision checking").
 *
 * Grid: cell (i, j) stores min(C, clearance at its centre), C = 4 cells, where clearance
 * is the FCL distance from the robot disc centred there to the nearest circle, box or
 * person (0 when touching or overlapping). Clearance is 1-Lipschitz, so for any point q
 *     clearance(q) >= stored(c) - |q - c|
 * for every cell centre c; a point is declared free when that bound is positive for one
 * of the four centres around it. The test never calls a colliding point free; it may
 * call free points within about one cell of an obstacle blocked (the price of a query
 * that costs four loads). Segments are walked with steps of at least edge_resolution_m,
 * longer where the bound proves the gap free (sphere tracing).
 */
#include "gmmrrt/collision.h"

#include <math.h>
#include <string.h>

#include "fcl_adapter.h"

#define GMMRRT_CLEARANCE_CAP_CELLS 4.0

struct gmmrrt_world {
    gmmrrt_obstacle_set_t obstacles;
    double resolution_m;
    double robot_radius_m;
    double person_radius_m;
    double edge_resolution_m;
    double cap_m;
    int32_t nx, ny;
    int32_t max_cells;
    float clearance[]; /* nx * ny, row-major (j * nx + i) */
};

static size_t align8(size_t n) { return (n + 7u) & ~(size_t)7u; }

size_t gmmrrt_world_mem_size(int32_t grid_max_cells)
{
    if (grid_max_cells < 1)
        return 0;
    return align8(sizeof(struct gmmrrt_world) + (size_t)grid_max_cells * sizeof(float));
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
    return GMMRRT_OK;
}

/* Lowers the stored clearance of every cell whose centre lies in [x0, x1] x [y0, y1]
 * to the FCL distance of one obstacle (kind 0: disc, 1: box). */
static void splat(struct gmmrrt_world *w, int kind, double cx, double cy, double r_or_w, double h,
                  double yaw, double x0, double y0, double x1, double y1)
{
    const gmmrrt_bounds_t *b = &w->obstacles.bounds;
    const double res = w->resolution_m;
    /* Clip in double first: any finite position is valid on the wire, and one far outside the
     * bounds overflowed the int conversion below (UB; found by tests/fuzz/fuzz_daemon_inputs).
     * The margin of one cell keeps the cell range below exactly what it was for near obstacles. */
    if (!(x1 >= b->xmin - res && x0 <= b->xmax + res && y1 >= b->ymin - res && y0 <= b->ymax + res))
        return;
    x0 = fmax(x0, b->xmin - res);
    x1 = fmin(x1, b->xmax + res);
    y0 = fmax(y0, b->ymin - res);
    y1 = fmin(y1, b->ymax + res);
    int32_t i0 = (int32_t)floor((x0 - b->xmin) / res - 0.5), i1 = (int32_t)ceil((x1 - b->xmin) / res - 0.5);
    int32_t j0 = (int32_t)floor((y0 - b->ymin) / res - 0.5), j1 = (int32_t)ceil((y1 - b->ymin) / res - 0.5);
    if (i1 < 0 || j1 < 0 || i0 >= w->nx || j0 >= w->ny)
        return;
    if (i0 < 0)
        i0 = 0;
    if (j0 < 0)
        j0 = 0;
    if (i1 >= w->nx)
        i1 = w->nx - 1;
    if (j1 >= w->ny)
        j1 = w->ny - 1;
    for (int32_t j = j0; j <= j1; ++j) {
        const double y = b->ymin + (j + 0.5) * res;
        float *row = w->clearance + (size_t)j * (size_t)w->nx;
        for (int32_t i = i0; i <= i1; ++i) {
            const double x = b->xmin + (i + 0.5) * res;
            const double d = kind == 0 ? gmmrrt_fcl_disc_distance(x, y, w->robot_radius_m, cx, cy, r_or_w)
                                       : gmmrrt_fcl_box_distance(x, y, w->robot_radius_m, cx, cy, r_or_w, h, yaw);
            /* Round down to float so the stored value stays a lower bound. */
            float f = (float)d;
            if ((double)f > d)
                f = nextafterf(f, 0.0f);
            if (f < row[i])
                row[i] = f;
        }
    }
}

gmmrrt_status_t gmmrrt_world_build(gmmrrt_world_t **out, void *mem, size_t size, int32_t grid_max_cells,
                                   double resolution_m, double robot_radius_m, double person_radius_m,
                                   const gmmrrt_obstacle_set_t *obstacles)
{
    if (!out || !mem || !obstacles || grid_max_cells < 1 || !isfinite(resolution_m) || resolution_m <= 0.0 ||
        !isfinite(robot_radius_m) || robot_radius_m < 0.0 || !isfinite(person_radius_m) ||
        person_radius_m < 0.0 || ((uintptr_t)mem & 7u) != 0)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    if (size < gmmrrt_world_mem_size(grid_max_cells))
        return GMMRRT_ERR_BUFFER_TOO_SMALL;
    gmmrrt_status_t st = validate_obstacles(obstacles);
    if (st != GMMRRT_OK)
        return st;
    const gmmrrt_bounds_t *b = &obstacles->bounds;
    const double nxd = ceil((b->xmax - b->xmin) / resolution_m), nyd = ceil((b->ymax - b->ymin) / resolution_m);
    if (!(nxd * nyd <= (double)grid_max_cells))
        return GMMRRT_ERR_BUFFER_TOO_SMALL;

    struct gmmrrt_world *w = mem;
    memcpy(&w->obstacles, obstacles, sizeof *obstacles);
    w->resolution_m = resolution_m;
    w->robot_radius_m = robot_radius_m;
    w->person_radius_m = person_radius_m;
    w->edge_resolution_m = resolution_m;
    w->cap_m = GMMRRT_CLEARANCE_CAP_CELLS * resolution_m;
    w->nx = nxd < 1.0 ? 1 : (int32_t)nxd;
    w->ny = nyd < 1.0 ? 1 : (int32_t)nyd;
    w->max_cells = grid_max_cells;
    const size_t n = (size_t)w->nx * (size_t)w->ny;
    for (size_t c = 0; c < n; ++c)
        w->clearance[c] = (float)w->cap_m;

    /* Only cells within reach (robot radius + cap) of an obstacle can hold less than the cap. */
    const double reach = robot_radius_m + w->cap_m;
    for (int32_t k = 0; k < obstacles->num_circles; ++k) {
        const gmmrrt_circle_t *c = &obstacles->circles[k];
        const double e = c->radius_m + reach;
        splat(w, 0, c->x, c->y, c->radius_m, 0.0, 0.0, c->x - e, c->y - e, c->x + e, c->y + e);
    }
    for (int32_t k = 0; k < obstacles->num_people; ++k) {
        const gmmrrt_pose_t *p = &obstacles->people[k];
        const double e = person_radius_m + reach;
        if (person_radius_m > 0.0)
            splat(w, 0, p->x, p->y, person_radius_m, 0.0, 0.0, p->x - e, p->y - e, p->x + e, p->y + e);
    }
    for (int32_t k = 0; k < obstacles->num_boxes; ++k) {
        const gmmrrt_box_t *bx = &obstacles->boxes[k];
        const double hx = 0.5 * (fabs(cos(bx->yaw)) * bx->width_m + fabs(sin(bx->yaw)) * bx->height_m);
        const double hy = 0.5 * (fabs(sin(bx->yaw)) * bx->width_m + fabs(cos(bx->yaw)) * bx->height_m);
        splat(w, 1, bx->x, bx->y, bx->width_m, bx->height_m, bx->yaw, bx->x - hx - reach, bx->y - hy - reach,
              bx->x + hx + reach, bx->y + hy + reach);
    }
    *out = w;
    return GMMRRT_OK;
}

/* Lower bound on the clearance at (x, y) from the four cell centres around it; the point
 * must lie inside the bounds. */
/* Margin an edge must keep from every obstacle (m): edges closer than this are refused, which is
 * what keeps sphere tracing exact and finite (see gmmrrt_world_segment_free). */
#define GMMRRT_EDGE_MIN_CLEARANCE_M 1e-3

static double clearance_lower_bound(const struct gmmrrt_world *w, double x, double y)
{
    const gmmrrt_bounds_t *b = &w->obstacles.bounds;
    const double res = w->resolution_m;
    const double u = (x - b->xmin) / res - 0.5, v = (y - b->ymin) / res - 0.5;
    int32_t i0 = (int32_t)floor(u), j0 = (int32_t)floor(v);
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
            const double cx = b->xmin + (i + 0.5) * res, cy = b->ymin + (j + 0.5) * res;
            const double s = (double)w->clearance[(size_t)j * (size_t)w->nx + (size_t)i];
            const double dx = x - cx, dy = y - cy; /* plain sqrt: hypot is ~10x slower, no overflow here */
            const double lb = s - sqrt(dx * dx + dy * dy);
            if (lb > best)
                best = lb;
        }
    }
    return best;
}

static int inside_bounds(const struct gmmrrt_world *w, double x, double y)
{
    const gmmrrt_bounds_t *b = &w->obstacles.bounds;
    return x >= b->xmin && x <= b->xmax && y >= b->ymin && y <= b->ymax;
}

int gmmrrt_world_point_free(const gmmrrt_world_t *world, double x, double y)
{
    if (!world || !isfinite(x) || !isfinite(y) || !inside_bounds(world, x, y))
        return 0;
    return clearance_lower_bound(world, x, y) > 0.0;
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
    /* The end points' clearance bounds (as gmmrrt_world_point_free) are also the first probes. */
    const double lb0 = clearance_lower_bound(world, x0, y0), lb1 = clearance_lower_bound(world, x1, y1);
    if (!(lb0 > 0.0) || !(lb1 > 0.0))
        return 0;
    const double dx = x1 - x0, dy = y1 - y0;
    const double len = sqrt(dx * dx + dy * dy); /* plain sqrt: map coordinates, no overflow */
    if (len == 0.0)
        return 1;
    /* Free discs of radius lb0 and lb1 around the ends that overlap cover the whole edge
     * (same clearance floor as the walk below). */
    if (lb0 > GMMRRT_EDGE_MIN_CLEARANCE_M && lb1 > GMMRRT_EDGE_MIN_CLEARANCE_M && lb0 + lb1 > len)
        return 1;
    const double ux = (x1 - x0) / len, uy = (y1 - y0) / len;
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
        const double lb = clearance_lower_bound(world, x0 + s * ux, y0 + s * uy);
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
    return best;
}

/* Internal (declared in planner_internal.h): the planner sets the segment step. */
void gmmrrt_world_set_edge_resolution(gmmrrt_world_t *world, double edge_resolution_m);
void gmmrrt_world_set_edge_resolution(gmmrrt_world_t *world, double edge_resolution_m)
{
    if (world && isfinite(edge_resolution_m) && edge_resolution_m > 0.0)
        world->edge_resolution_m = edge_resolution_m;
}
