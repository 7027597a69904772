/*
 * raster.c - the occupancy raster of raster.h: cells, scan marks and their exact Euclidean
 * distance field (Felzenszwalb & Huttenlocher 2012: the lower envelope of parabolas, one 1-D
 * pass along the columns then one along the rows, O(cells)), the bound the collision world
 * reads, and scan integration by ray casting (Amanatides & Woo 1987 cell traversal).
 *
 * The field is sampled at the cells' corners, the (width + 1) x (height + 1) lattice points:
 * for a lattice point v and a blocked cell's closed square, each coordinate of the square's
 * nearest point to v is v's coordinate clamped to the cell's one-cell interval, which is a
 * lattice coordinate again, so the nearest point is one of the square's corners. The distance
 * from v to the union of blocked squares is therefore the distance to the nearest "blocked
 * corner" (a corner of a blocked cell), which the transform computes exactly. The bound a
 * point reads from its cell's four corners is then a lower bound of its distance to the
 * squares themselves, with nothing to subtract for the squares' extent.
 */
#include "gmmrrt/raster.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "block_layout.h"
#include "raster_bound.h"

/* "Nothing blocks" in squared cells: larger than any real squared distance (2 x 16385^2). */
#define FAR2 1e18
/* The field goes through floats (squared, then the distance): each rounding is relative
 * 2^-24; the stored distance is shrunk by this factor so it stays a lower bound. */
#define FIELD_SHRINK (1.0 - 1e-6)
/* The union's candidate points carry the rounding of a few products and square roots of
 * numbers of at most UNION_MAX_CELLS (the crossings' height in factored form, without
 * cancellation): a point counts as covered by a disc only when it is this far (relative) inside
 * it, and the result is lowered by as much. Behind it, the stored radii are shrunk by
 * FIELD_SHRINK, about a thousand times this margin, so rounding here cannot reach a wall. */
#define UNION_MARGIN 1e-9
#define UNION_MAX_CELLS 1e6


typedef struct {
    size_t cells, marks, dist, f, d, z, v, total;
} layout_t;

/* Corners of the largest raster the capacity admits: (w + 1)(h + 1) = wh + w + h + 1, where
 * wh <= max_cells, each side <= max_side, and w + h <= wh + 1 (both sides >= 1). */
static size_t max_corners(int32_t max_cells, int32_t max_side)
{
    const size_t n = (size_t)max_cells, two_sides = 2u * (size_t)max_side;
    return n + (two_sides < n + 1u ? two_sides : n + 1u) + 1u;
}

static layout_t layout_of(int32_t max_cells, int32_t max_side)
{
    layout_t l;
    /* A 1-D transform runs along at most max_side + 1 corners. */
    const size_t n = (size_t)max_cells, s = (size_t)max_side + 2;
    size_t off = 0;
    l.cells = gmmrrt_block_take(&off, n);
    l.marks = gmmrrt_block_take(&off, n * sizeof(uint32_t));
    l.dist = gmmrrt_block_take(&off, max_corners(max_cells, max_side) * sizeof(float));
    l.f = gmmrrt_block_take(&off, s * sizeof(double));
    l.d = gmmrrt_block_take(&off, s * sizeof(double));
    l.z = gmmrrt_block_take(&off, (s + 1) * sizeof(double));
    l.v = gmmrrt_block_take(&off, s * sizeof(int32_t));
    l.total = off;
    return l;
}

size_t gmmrrt_raster_mem_size(int32_t max_cells, int32_t max_side)
{
    if (max_cells < 1 || max_side < 1 || max_side > GMMRRT_MAX_RASTER_SIDE || max_cells > GMMRRT_MAX_RASTER_CELLS)
        return 0;
    return layout_of(max_cells, max_side).total;
}

double gmmrrt_raster_bytes(double width, double height)
{
    /* Per cell its value and a scan mark; per corner a float of the field. */
    return width * height * (double)(1 + sizeof(uint32_t)) + (width + 1.0) * (height + 1.0) * (double)sizeof(float);
}

gmmrrt_status_t gmmrrt_raster_init(gmmrrt_raster_t *r, void *mem, size_t size, int32_t max_cells, int32_t max_side)
{
    if (!r || !mem || ((uintptr_t)mem & 7u) != 0)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    const size_t need = gmmrrt_raster_mem_size(max_cells, max_side);
    if (need == 0)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    if (size < need)
        return GMMRRT_ERR_BUFFER_TOO_SMALL;
    const layout_t l = layout_of(max_cells, max_side);
    uint8_t *base = mem;
    memset(r, 0, sizeof *r);
    r->max_cells = max_cells;
    r->max_side = max_side;
    r->resolution_m = 1.0;
    r->inv_resolution_m = 1.0;
    r->cos_yaw = 1.0;
    r->unknown_blocked = 1;
    r->mark_epoch_utime = -1;
    r->cells = base + l.cells;
    r->marks = (uint32_t *)(void *)(base + l.marks);
    r->dist = (float *)(void *)(base + l.dist);
    r->scratch_f = (double *)(void *)(base + l.f);
    r->scratch_d = (double *)(void *)(base + l.d);
    r->scratch_z = (double *)(void *)(base + l.z);
    r->scratch_v = (int32_t *)(void *)(base + l.v);
    return GMMRRT_OK;
}

gmmrrt_status_t gmmrrt_raster_set_geometry(gmmrrt_raster_t *r, int32_t width, int32_t height, double resolution_m,
                                           double origin_x, double origin_y, double origin_yaw,
                                           int32_t unknown_blocked)
{
    if (!r || width < 1 || height < 1 || !isfinite(resolution_m) || resolution_m <= 0.0 || !isfinite(origin_x) ||
        !isfinite(origin_y) || !isfinite(origin_yaw) || (unknown_blocked != 0 && unknown_blocked != 1))
        return GMMRRT_ERR_INVALID_ARGUMENT;
    if (width > r->max_side || height > r->max_side || (int64_t)width * height > (int64_t)r->max_cells)
        return GMMRRT_ERR_BUFFER_TOO_SMALL;
    r->width = width;
    r->height = height;
    r->resolution_m = resolution_m;
    r->inv_resolution_m = 1.0 / resolution_m;
    r->origin_x = origin_x;
    r->origin_y = origin_y;
    r->origin_yaw = origin_yaw;
    r->cos_yaw = cos(origin_yaw);
    r->sin_yaw = sin(origin_yaw);
    r->unknown_blocked = unknown_blocked;
    const size_t n = (size_t)width * (size_t)height;
    memset(r->cells, GMMRRT_RASTER_UNKNOWN, n);
    memset(r->marks, 0, n * sizeof(uint32_t));
    r->mark_epoch_utime = -1;
    r->distance_ready = 0;
    r->generation++;
    return GMMRRT_OK;
}

int gmmrrt_raster_distance_ready(const gmmrrt_raster_t *r) { return r && r->width > 0 && r->distance_ready; }

/* 1-D squared distance transform of f[0..n) (FAR2: no site) into d[0..n): the lower envelope
 * of the parabolas (q - p)^2 + f(p) over the sites p. */
static void edt_1d(const double *f, double *d, int32_t *v, double *z, int32_t n)
{
    int32_t k = -1;
    for (int32_t q = 0; q < n; ++q) {
        if (!(f[q] < FAR2))
            continue;
        const double fq = f[q] + (double)q * (double)q;
        double s = -INFINITY;
        while (k >= 0) {
            const double p = (double)v[k];
            s = (fq - (f[v[k]] + p * p)) / (2.0 * ((double)q - p));
            if (s > z[k])
                break;
            --k;
        }
        ++k;
        v[k] = q;
        z[k] = k == 0 ? -INFINITY : s;
        z[k + 1] = INFINITY;
    }
    if (k < 0) {
        for (int32_t q = 0; q < n; ++q)
            d[q] = FAR2;
    } else {
        int32_t j = 0;
        for (int32_t q = 0; q < n; ++q) {
            while (z[j + 1] < (double)q)
                ++j;
            const double t = (double)(q - v[j]);
            d[q] = t * t + f[v[j]];
        }
    }
}

static int mark_active(const gmmrrt_raster_t *r, size_t c, double now_ms, double decay_ms)
{
    const uint32_t m = r->marks[c];
    return m != 0 && now_ms - (double)(m - 1u) <= decay_ms;
}

static int blocks(const gmmrrt_raster_t *r, size_t c, double now_ms, double decay_ms)
{
    const uint8_t v = r->cells[c];
    return v == GMMRRT_RASTER_OCCUPIED || (v == GMMRRT_RASTER_UNKNOWN && r->unknown_blocked) ||
           mark_active(r, c, now_ms, decay_ms);
}

/* The field over the corners [i0, i1) x [j0, j1) (write window), from the blocked corners of
 * [a0, a1) x [b0, b1) (a larger rectangle of corners around it, clipped to the lattice of
 * (width + 1) x (height + 1) corners), each value at most cap_m. A corner blocks when one of
 * the (up to four) cells around it blocks, or when it lies on the raster's border while the
 * outside (unknown) blocks. The corners of the larger rectangle outside the write window are
 * used as scratch. */
static void field_over(gmmrrt_raster_t *r, double now_ms, double decay_ms, int32_t a0, int32_t a1, int32_t b0,
                       int32_t b1, int32_t i0, int32_t i1, int32_t j0, int32_t j1, double cap_m)
{
    const int32_t w = r->width, h = r->height;
    const size_t cw = (size_t)w + 1u; /* corners per row */
    const int out = r->unknown_blocked; /* the outside is unknown */
    double *f = r->scratch_f, *d = r->scratch_d, *z = r->scratch_z;
    int32_t *v = r->scratch_v;
    /* Columns: squared distance along y to the nearest blocked corner of the same corner column. */
    for (int32_t i = a0; i < a1; ++i) {
        /* d[k] (k = j - b0 + 1): 1 when cell row j has a blocked cell left or right of corner
         * column i (cells i - 1 and i), for the cell rows b0 - 1 .. b1 - 1 the corners touch. */
        for (int32_t j = b0 - 1; j < b1; ++j) {
            int any = 0;
            if (j >= 0 && j < h) {
                const size_t row = (size_t)j * (size_t)w;
                any = (i > 0 && blocks(r, row + (size_t)i - 1u, now_ms, decay_ms)) ||
                      (i < w && blocks(r, row + (size_t)i, now_ms, decay_ms));
            }
            d[j - b0 + 1] = any ? 1.0 : 0.0;
        }
        const int border_column = out && (i == 0 || i == w);
        for (int32_t j = b0; j < b1; ++j) {
            const int blocked = border_column || (out && (j == 0 || j == h)) || d[j - b0] != 0.0 || d[j - b0 + 1] != 0.0;
            f[j - b0] = blocked ? 0.0 : FAR2;
        }
        edt_1d(f, d, v, z, b1 - b0);
        for (int32_t j = b0; j < b1; ++j)
            r->dist[(size_t)j * cw + (size_t)i] = (float)d[j - b0];
    }
    /* Rows: the 2-D squared distance, then the distance in metres, rounded down. */
    for (int32_t j = j0; j < j1; ++j) {
        float *row = r->dist + (size_t)j * cw;
        for (int32_t i = a0; i < a1; ++i)
            f[i - a0] = (double)row[i] >= FAR2 * 0.5 ? FAR2 : (double)row[i];
        edt_1d(f, d, v, z, a1 - a0);
        for (int32_t i = i0; i < i1; ++i) {
            const double di = d[i - a0];
            double m = di >= FAR2 * 0.5 ? (double)FLT_MAX : sqrt(di) * r->resolution_m * FIELD_SHRINK;
            m = m < cap_m ? m : cap_m;
            float x = (float)m;
            if ((double)x > m)
                x = nextafterf(x, 0.0f);
            row[i] = x;
        }
    }
    r->valid_i0 = i0;
    r->valid_i1 = i1;
    r->valid_j0 = j0;
    r->valid_j1 = j1;
    r->field_now_ms = now_ms;
    r->field_decay_ms = decay_ms;
    r->distance_ready = 1;
    r->generation++;
}

static double ms_since_epoch(const gmmrrt_raster_t *r, int64_t now_utime)
{
    return r->mark_epoch_utime < 0 ? 0.0 : (double)(now_utime - r->mark_epoch_utime) * 1e-3;
}

gmmrrt_status_t gmmrrt_raster_update_distance(gmmrrt_raster_t *r, int64_t now_utime, double mark_decay_ms)
{
    if (!r || r->width < 1 || !isfinite(mark_decay_ms) || mark_decay_ms < 0.0)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    const int32_t cw = r->width + 1, ch = r->height + 1; /* corners */
    field_over(r, ms_since_epoch(r, now_utime), mark_decay_ms, 0, cw, 0, ch, 0, cw, 0, ch, INFINITY);
    return GMMRRT_OK;
}

/* Index range [lo, hi) of the n corners along one raster axis that a point in [t0, t1] (cells)
 * reads (floor(t) and floor(t) + 1), and one more each side. */
static void corner_range(double t0, double t1, int32_t n, int32_t *lo, int32_t *hi)
{
    const double a = floor(t0) - 1.0, b = floor(t1) + 3.0;
    *lo = a < 0.0 ? 0 : (a > (double)n ? n : (int32_t)a);
    *hi = b < 0.0 ? 0 : (b > (double)n ? n : (int32_t)b);
}

gmmrrt_status_t gmmrrt_raster_update_distance_window(gmmrrt_raster_t *r, int64_t now_utime, double mark_decay_ms,
                                                     double xmin, double ymin, double xmax, double ymax,
                                                     double reach_m)
{
    if (!r || r->width < 1 || !isfinite(mark_decay_ms) || mark_decay_ms < 0.0 || !isfinite(xmin) ||
        !isfinite(ymin) || !isfinite(xmax) || !isfinite(ymax) || !(xmin <= xmax) || !(ymin <= ymax) ||
        !isfinite(reach_m) || !(reach_m > 0.0))
        return GMMRRT_ERR_INVALID_ARGUMENT;
    /* The box in raster cells: the range of its four corners. */
    double ulo = INFINITY, uhi = -INFINITY, vlo = INFINITY, vhi = -INFINITY;
    const double xs[2] = {xmin, xmax}, ys[2] = {ymin, ymax};
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
            double u, v;
            const double dx = xs[a] - r->origin_x, dy = ys[b] - r->origin_y;
            u = (dx * r->cos_yaw + dy * r->sin_yaw) / r->resolution_m;
            v = (-dx * r->sin_yaw + dy * r->cos_yaw) / r->resolution_m;
            ulo = fmin(ulo, u);
            uhi = fmax(uhi, u);
            vlo = fmin(vlo, v);
            vhi = fmax(vhi, v);
        }
    int32_t i0, i1, j0, j1;
    const int32_t cw = r->width + 1, ch = r->height + 1; /* corners */
    corner_range(ulo, uhi, cw, &i0, &i1);
    corner_range(vlo, vhi, ch, &j0, &j1);
    if (i0 >= i1 || j0 >= j1) {
        /* The box misses the raster: an empty valid window, every bound "blocked" inside it. */
        r->valid_i0 = r->valid_i1 = r->valid_j0 = r->valid_j1 = 0;
        r->distance_ready = 1;
        r->generation++;
        return GMMRRT_OK;
    }
    /* Margin m cells: a blocked corner beyond it is more than m cells from every window corner,
     * so capping the field at m cells keeps it a lower bound. */
    const double md = ceil(reach_m / r->resolution_m) + 1.0;
    const int32_t m = md > (double)(cw + ch) ? cw + ch : (int32_t)md;
    const int32_t a0 = i0 - m < 0 ? 0 : i0 - m, a1 = i1 + m > cw ? cw : i1 + m;
    const int32_t b0 = j0 - m < 0 ? 0 : j0 - m, b1 = j1 + m > ch ? ch : j1 + m;
    field_over(r, ms_since_epoch(r, now_utime), mark_decay_ms, a0, a1, b0, b1, i0, i1, j0, j1,
               (double)m * r->resolution_m);
    return GMMRRT_OK;
}

/* The two neighbour indices along one axis, floor(a) and floor(a) + 1, each clamped to
 * [0, n - 1] (a below -1 or NaN: both 0). */
static void neighbours(double a, int32_t n, int32_t *lo, int32_t *hi)
{
    if (!(a >= 0.0)) { /* floor(a) <= -1: the first clamps to 0, the second too */
        *lo = *hi = 0;
        return;
    }
    if (a >= (double)(n - 1)) {
        *lo = *hi = n - 1;
        return;
    }
    const int32_t f = (int32_t)a; /* a >= 0: truncation is floor */
    *lo = f;
    *hi = f + 1 < n ? f + 1 : n - 1;
}

/* The point (x, y) in cells (*u, *v) and the corners of its cell: floor and the next in each
 * direction, clamped to the lattice of (width + 1) x (height + 1) corners. */
static inline void cell_corners(const gmmrrt_raster_t *r, double x, double y, double *u, double *v, int32_t *ia,
                                int32_t *ib, int32_t *ja, int32_t *jb)
{
    gmmrrt_raster_to_cells(r, x, y, u, v);
    neighbours(*u, r->width + 1, ia, ib);
    neighbours(*v, r->height + 1, ja, jb);
}

double gmmrrt_raster_clearance_bound(const gmmrrt_raster_t *r, double x, double y)
{
    double u, v, inner;
    gmmrrt_raster_to_cells(r, x, y, &u, &v);
    if (gmmrrt_raster_interior_bound(r, u, v, &inner))
        return inner;
    int32_t ia, ib, ja, jb;
    neighbours(u, r->width + 1, &ia, &ib);
    neighbours(v, r->height + 1, &ja, &jb);
    /* Offsets from the point to each corner, in cells, squared. */
    const double cua = (double)ia - u, cub = (double)ib - u;
    const double cva = (double)ja - v, cvb = (double)jb - v;
    const double ua2 = cua * cua, ub2 = cub * cub, va2 = cva * cva, vb2 = cvb * cvb;
    const int ok_ia = ia >= r->valid_i0 && ia < r->valid_i1, ok_ib = ib >= r->valid_i0 && ib < r->valid_i1;
    const int ok_ja = ja >= r->valid_j0 && ja < r->valid_j1, ok_jb = jb >= r->valid_j0 && jb < r->valid_j1;
    const size_t w = (size_t)r->width + 1u;
    /* The four corners in the order (ia, ja), (ib, ja), (ia, jb), (ib, jb). Every index is
     * clamped to the lattice, so all four loads stay inside it; one outside the valid window is
     * loaded but left out. Loads and square roots first, then the maximum: four independent
     * chains instead of four branches (the same values as corner by corner). */
    const int ok[4] = {ok_ia && ok_ja, ok_ib && ok_ja, ok_ia && ok_jb, ok_ib && ok_jb};
    const float f[4] = {r->dist[(size_t)ja * w + (size_t)ia], r->dist[(size_t)ja * w + (size_t)ib],
                        r->dist[(size_t)jb * w + (size_t)ia], r->dist[(size_t)jb * w + (size_t)ib]};
    const double d2[4] = {ua2 + va2, ub2 + va2, ua2 + vb2, ub2 + vb2};
    double lb[4];
    for (int k = 0; k < 4; ++k)
        lb[k] = (double)f[k] - sqrt(d2[k]) * r->resolution_m;
    double best = -INFINITY; /* no valid neighbour: blocked */
    for (int k = 0; k < 4; ++k)
        if (ok[k] && lb[k] > best)
            best = lb[k];
    return best;
}

/* 1 when point (px, py) lies inside one of the n discs (cx, cy, rad_in) other than skip_a and
 * skip_b by more than the rounding margin (rad_in = the radius less the margin; a disc with
 * rad_in <= 0 covers nothing; compared squared). */
static int covered_by_another(double px, double py, int n, const double *cx, const double *cy, const double *rad_in,
                              int skip_a, int skip_b)
{
    for (int j = 0; j < n; ++j) {
        if (j == skip_a || j == skip_b || !(rad_in[j] > 0.0))
            continue;
        const double dx = px - cx[j], dy = py - cy[j];
        if (dx * dx + dy * dy < rad_in[j] * rad_in[j])
            return 1;
    }
    return 0;
}

double gmmrrt_raster_clearance_union(const gmmrrt_raster_t *r, double x, double y)
{
    double u, v;
    int32_t ia, ib, ja, jb;
    cell_corners(r, x, y, &u, &v, &ia, &ib, &ja, &jb);
    const size_t w = (size_t)r->width + 1u;
    const int32_t ci[4] = {ia, ib, ia, ib}, cj[4] = {ja, ja, jb, jb};
    /* The valid corners' circles, relative to the point, in cells. */
    double cx[4], cy[4], rad[4], rad_in[4], dist[4];
    int n = 0;
    double single = -INFINITY;
    for (int k = 0; k < 4; ++k) {
        if (!(ci[k] >= r->valid_i0 && ci[k] < r->valid_i1 && cj[k] >= r->valid_j0 && cj[k] < r->valid_j1))
            continue;
        if ((k == 1 && ib == ia) || (k == 2 && jb == ja) || (k == 3 && (ib == ia || jb == ja)))
            continue; /* a clamped corner counted already */
        cx[n] = (double)ci[k] - u;
        cy[n] = (double)cj[k] - v;
        rad[n] = (double)r->dist[(size_t)cj[k] * w + (size_t)ci[k]] * r->inv_resolution_m;
        rad_in[n] = rad[n] - UNION_MARGIN * (1.0 + rad[n]);
        dist[n] = sqrt(cx[n] * cx[n] + cy[n] * cy[n]);
        if (rad[n] - dist[n] > single)
            single = rad[n] - dist[n];
        ++n;
    }
    /* Not inside any disc, or inside one so large that the union is not needed (the field's
     * "nothing blocks"): the single discs' bound. */
    if (!(single > 0.0) || !(single < UNION_MAX_CELLS))
        return single * r->resolution_m;
    double best = INFINITY;
    /* The nearest point of each circle: along the ray from its centre through the point. */
    for (int k = 0; k < n; ++k) {
        double px, py;
        if (dist[k] > 0.0) {
            px = cx[k] - cx[k] / dist[k] * rad[k];
            py = cy[k] - cy[k] / dist[k] * rad[k];
        } else { /* the point is the centre: every point of the circle is as near; take any */
            px = cx[k] + rad[k];
            py = cy[k];
        }
        const double e = fabs(rad[k] - dist[k]);
        if (e < best && !covered_by_another(px, py, n, cx, cy, rad_in, k, k))
            best = e;
        if (dist[k] == 0.0 && rad[k] < best)
            best = rad[k]; /* any point of the circle is as near: the whole circle counts */
    }
    /* The circles' crossings (the ends of the union's boundary arcs). A crossing lies on both
     * circles, so it is at least each circle's nearest distance from the point: a pair whose
     * larger one is not below the best so far cannot lower it. */
    for (int a = 0; a < n; ++a)
        for (int b = a + 1; b < n; ++b) {
            const double ea = fabs(rad[a] - dist[a]), eb = fabs(rad[b] - dist[b]);
            if ((ea > eb ? ea : eb) >= best)
                continue;
            const double ex = cx[b] - cx[a], ey = cy[b] - cy[a];
            const double dd = sqrt(ex * ex + ey * ey);
            if (!(dd > 0.0) || !(dd < rad[a] + rad[b]) || !(dd > fabs(rad[a] - rad[b])))
                continue; /* apart, or one inside the other: no crossing */
            const double inv = 1.0 / dd, t = (rad[a] * rad[a] - rad[b] * rad[b] + dd * dd) * 0.5 * inv;
            /* h^2 = ra^2 - t^2 in factored form (each factor positive by the test above), so two
             * nearly tangent circles do not lose the crossing to cancellation. */
            const double h2 = (rad[a] + rad[b] - dd) * (rad[a] + rad[b] + dd) * (dd - rad[a] + rad[b]) *
                              (dd + rad[a] - rad[b]) * 0.25 * inv * inv;
            const double h = h2 > 0.0 ? sqrt(h2) : 0.0;
            const double ux = ex * inv, uy = ey * inv;
            const double mx = cx[a] + ux * t, my = cy[a] + uy * t;
            for (int sgn = -1; sgn <= 1; sgn += 2) {
                const double px = mx - (double)sgn * uy * h, py = my + (double)sgn * ux * h;
                const double e2 = px * px + py * py;
                if (e2 < best * best && !covered_by_another(px, py, n, cx, cy, rad_in, a, b))
                    best = sqrt(e2);
            }
        }
    if (!(best < INFINITY) || best < single)
        best = single; /* rounding: never below the single discs' bound, which holds anyway */
    return (best - UNION_MARGIN * (1.0 + best)) * r->resolution_m;
}

double gmmrrt_raster_distance_to_blocked(const gmmrrt_raster_t *r, double x, double y, double max_m)
{
    if (!r || r->width < 1 || !isfinite(x) || !isfinite(y) || !(max_m > 0.0))
        return NAN;
    double u, v;
    gmmrrt_raster_to_cells(r, x, y, &u, &v);
    if (r->unknown_blocked && !(u >= 0.0 && v >= 0.0 && u <= (double)r->width && v <= (double)r->height))
        return 0.0; /* in the outside, which blocks */
    const double reach = max_m / r->resolution_m + 1.0;
    double best = max_m / r->resolution_m;
    /* Raster cells and, when the outside blocks, the ring of cells just outside it (the
     * outside's nearest part is always on that ring). */
    const int out = r->unknown_blocked;
    const double lo_i = fmax(floor(u - reach), out ? -1.0 : 0.0), hi_i = fmin(ceil(u + reach), (double)(r->width - (out ? 0 : 1)));
    const double lo_j = fmax(floor(v - reach), out ? -1.0 : 0.0), hi_j = fmin(ceil(v + reach), (double)(r->height - (out ? 0 : 1)));
    const double now_ms = r->field_now_ms, decay_ms = r->field_decay_ms; /* the marks the field counted */
    for (double jj = lo_j; jj <= hi_j; jj += 1.0) {
        for (double ii = lo_i; ii <= hi_i; ii += 1.0) {
            const int32_t i = (int32_t)ii, j = (int32_t)jj;
            const int outside = i < 0 || j < 0 || i >= r->width || j >= r->height;
            if (!outside && !blocks(r, (size_t)j * (size_t)r->width + (size_t)i, now_ms, decay_ms))
                continue;
            const double ex = u < ii ? ii - u : (u > ii + 1.0 ? u - ii - 1.0 : 0.0);
            const double ey = v < jj ? jj - v : (v > jj + 1.0 ? v - jj - 1.0 : 0.0);
            const double e = sqrt(ex * ex + ey * ey);
            best = e < best ? e : best;
        }
    }
    return best * r->resolution_m;
}

gmmrrt_status_t gmmrrt_raster_apply_scan(gmmrrt_raster_t *r, const gmmrrt_scan_t *scan, double sensor_x,
                                         double sensor_y, double sensor_yaw, int64_t utime, int32_t *marked,
                                         int32_t *cleared)
{
    if (marked)
        *marked = 0;
    if (cleared)
        *cleared = 0;
    if (!r || !scan || r->width < 1 || scan->num_ranges < 0 || scan->num_ranges > GMMRRT_MAX_SCAN_RANGES ||
        (scan->num_ranges > 0 && !scan->ranges_m) || !isfinite(sensor_x) || !isfinite(sensor_y) ||
        !isfinite(sensor_yaw) || !isfinite(scan->rad0) || !isfinite(scan->radstep) ||
        !isfinite(scan->range_min_m) || !isfinite(scan->range_max_m) || scan->range_min_m < 0.0 ||
        !(scan->range_max_m > scan->range_min_m) || utime < 0)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    const int64_t epoch = r->mark_epoch_utime < 0 ? utime : r->mark_epoch_utime;
    if (utime < epoch || (utime - epoch) / 1000 >= (int64_t)UINT32_MAX - 1)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    r->mark_epoch_utime = epoch;
    const uint32_t stamp = (uint32_t)((utime - epoch) / 1000) + 1u;
    int32_t n_marked = 0, n_cleared = 0;
    double su, sv;
    gmmrrt_raster_to_cells(r, sensor_x, sensor_y, &su, &sv);
    for (int32_t k = 0; k < scan->num_ranges; ++k) {
        const double range = (double)scan->ranges_m[k];
        if (!(isfinite(range) && range >= scan->range_min_m && range < scan->range_max_m))
            continue; /* no return */
        const double a = sensor_yaw + scan->rad0 + (double)k * scan->radstep - r->origin_yaw;
        const double du = cos(a) * range / r->resolution_m, dv = sin(a) * range / r->resolution_m;
        const double eu = su + du, ev = sv + dv;
        /* Cell traversal from the sensor's cell to the end's (Amanatides & Woo). */
        double ci = floor(su), cj = floor(sv);
        const double ti = floor(eu), tj = floor(ev);
        const double step_i = du > 0.0 ? 1.0 : -1.0, step_j = dv > 0.0 ? 1.0 : -1.0;
        const double dtu = du != 0.0 ? fabs(1.0 / du) : INFINITY, dtv = dv != 0.0 ? fabs(1.0 / dv) : INFINITY;
        double tmu = du != 0.0 ? (du > 0.0 ? ci + 1.0 - su : su - ci) * dtu : INFINITY;
        double tmv = dv != 0.0 ? (dv > 0.0 ? cj + 1.0 - sv : sv - cj) * dtv : INFINITY;
        const double max_steps = fabs(ti - ci) + fabs(tj - cj);
        for (double s = 0.0; s < max_steps; s += 1.0) {
            if (ci >= 0.0 && cj >= 0.0 && ci < (double)r->width && cj < (double)r->height) {
                const size_t c = (size_t)cj * (size_t)r->width + (size_t)ci;
                if (r->marks[c] != 0) {
                    r->marks[c] = 0;
                    ++n_cleared;
                }
            }
            if (tmu < tmv) {
                ci += step_i;
                tmu += dtu;
            } else {
                cj += step_j;
                tmv += dtv;
            }
        }
        if (ti >= 0.0 && tj >= 0.0 && ti < (double)r->width && tj < (double)r->height) {
            r->marks[(size_t)tj * (size_t)r->width + (size_t)ti] = stamp;
            ++n_marked;
        }
    }
    r->distance_ready = 0;
    r->generation++;
    if (marked)
        *marked = n_marked;
    if (cleared)
        *cleared = n_cleared;
    return GMMRRT_OK;
}
