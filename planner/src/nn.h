/*
 * nn.h - internal: the nearest-neighbour index of the tree, a uniform grid of buckets over
 * the planning bounds, each bucket a list through the node pool then a run of consecutive
 * pool entries (one int32_t per node, one int32_t head per bucket; see gmmrrt_nn_t and
 * docs/planner.md). The RRT* needs the nearest node (extend) and the nodes within
 * a radius (choose-parent and rewire, Karaman & Frazzoli 2011, Alg. 6). Checked against a
 * linear scan in tests/unit/planner/test_nn.c.
 */
#ifndef GMMRRT_NN_H
#define GMMRRT_NN_H

#include <stdint.h>

#include "gmmrrt/collision.h"

/* The tree's nodes as a structure of arrays, entry i of each array for node i: 40 bytes a
 * node, 44 with its bucket head. Positions are apart from the rest because every spatial
 * query scans them (16 bytes a node read, not the whole record); costs are apart because
 * choose-parent and rewire read them only for the near set. */
typedef struct {
    double x, y;           /* m, world */
} gmmrrt_xy_t;

typedef struct {
    int32_t parent;        /* -1 for the root */
    int32_t first_child;   /* -1 when a leaf */
    int32_t next_sibling;  /* next child of the same parent, -1 at the end */
} gmmrrt_links_t;

typedef struct {
    gmmrrt_xy_t *xy;
    double *cost;          /* cost-to-come from the root */
    gmmrrt_links_t *link;
    int32_t *next_in_bucket; /* spatial index: see gmmrrt_nn_t */
} gmmrrt_pool_t;

/* A bucket's nodes are a list then a run. The list holds the nodes added since the last
 * sorted re-layout (newest first) and the root; it starts at heads[bucket] and goes on
 * through next_in_bucket until -1 or a run start. The run is the bucket's nodes of the last
 * sorted re-layout: pool indices [s, next_in_bucket[s]) for its first node s, every node of
 * the run holding the run's end (exclusive) in next_in_bucket. Runs are the nodes
 * 1..sorted_end-1, so a node n > 0 reached through the list starts a run iff n < sorted_end
 * (the root, node 0, is always a list node). Without a sorted re-layout sorted_end = 1:
 * every bucket is a plain list. The scan order (list, then run) is the order queries report
 * nodes in, and the planner's trees depend on it. */

typedef struct {
    int32_t *heads;        /* capacity buckets, owned by the planner block */
    int32_t capacity;
    int32_t nx, ny;
    int32_t sorted_end;    /* nodes 1..sorted_end-1 lie in bucket runs (1: none) */
    double x0, y0;         /* m, lower corner of the grid */
    double cell_m;         /* bucket edge */
    /* Adaptive layout (gmmrrt_nn_reset_adaptive; all zero = fixed layout): the grid is laid
     * again for the current node count each time it doubles, so buckets hold ~1-2 nodes at
     * any tree size. */
    int32_t adaptive;
    int32_t relayout_at;   /* node count that triggers the next layout */
    gmmrrt_bounds_t bounds;
} gmmrrt_nn_t;

/* Bytes of bucket heads for a pool of max_nodes. */
int32_t gmmrrt_nn_capacity(int32_t max_nodes);

/* Empties the index and lays the grid over `bounds` with buckets of at least min_cell_m,
 * using at most nn->capacity buckets. */
void gmmrrt_nn_reset(gmmrrt_nn_t *nn, const gmmrrt_bounds_t *bounds, double min_cell_m);

/* Empties the index for a tree that grows by gmmrrt_nn_insert of nodes 0, 1, 2, ... in
 * order: the bucket edge follows the node count (about GMMRRT_NN_NODES_PER_CELL nodes per
 * bucket right after each re-layout, which happens when the count doubles and re-buckets
 * nodes 0..idx: amortised O(1) per insert, no memory beyond the heads). */
void gmmrrt_nn_reset_adaptive(gmmrrt_nn_t *nn, const gmmrrt_bounds_t *bounds);

/* 1 when the adaptive grid wants laying again before a tree of n_next nodes is indexed. */
int gmmrrt_nn_relayout_due(const gmmrrt_nn_t *nn, int32_t n_next);

/* Lays the adaptive grid again for nodes 0..n-1 and renumbers nodes 1..n-1 in bucket order
 * (row-major buckets, each bucket's nodes one run of the pool; node 0, the root, keeps
 * its index and is its bucket's list), so that a query's buckets are a few contiguous runs
 * of memory, scanned without following links, instead of scattered pool entries: the pool
 * outgrows the CPU caches long before planning ends, and the near-set scan is memory bound. Rewrites
 * every tree link (parent, first_child, next_sibling) and the n_refs node indices in refs[]
 * (the caller's other references into the pool, -1 entries left alone). Uses no memory but
 * the pool and the bucket heads (next_in_bucket is the scratch). O(n). Any node index the
 * caller keeps elsewhere is stale afterwards. */
void gmmrrt_nn_relayout_sorted(gmmrrt_nn_t *nn, gmmrrt_pool_t *pool, int32_t n, int32_t *refs, int32_t n_refs);

/* Adds node `idx` (its x, y set) to the index (adaptive: nodes 0..idx-1 already in). */
void gmmrrt_nn_insert(gmmrrt_nn_t *nn, gmmrrt_pool_t *pool, int32_t idx);

/* Index of the node nearest to (x, y) (ties: the one found first), -1 when empty. */
int32_t gmmrrt_nn_nearest(const gmmrrt_nn_t *nn, const gmmrrt_pool_t *pool, double x, double y);

/* A near set of at least the k nearest nodes to (x, y) within max_d (m): every node within
 * the largest disc around (x, y) that the scanned buckets cover, which holds at least k
 * nodes (all of them when the tree has fewer), cut to radius max_d; when that is more than
 * kmax, exactly the k nearest (cut to max_d). The nearest node is always in it, however far.
 * Uses buf[cap] and buf_d2[cap] (cap >= 2 kmax) as scratch and returns the number of nodes,
 * their indices in buf[0..) and squared distances (m^2) in buf_d2[0..). buf[0] is the
 * nearest (of equally near nodes the first found); the others are in scan order. Grows
 * square rings of buckets around (x, y) (OMPL's nearestK, here on the bucket grid; the
 * disc usually holds a ring's worth more than k, which k-nearest RRT* allows: its bound is
 * a lower one, Karaman & Frazzoli 2011) and stops early once max_d is covered. Returns 0
 * when k <= 0, kmax < k, cap < 2 kmax or max_d <= 0. */
int32_t gmmrrt_nn_nearest_k(const gmmrrt_nn_t *nn, const gmmrrt_pool_t *pool, double x, double y, int32_t k,
                            int32_t kmax, double max_d, int32_t *buf, double *buf_d2, int32_t cap);

/* Writes the indices of nodes within radius_m of (x, y) (distance <= radius_m) into
 * out[cap]; returns their number, or -1 when there are more than cap (out then holds
 * a partial list). */
int32_t gmmrrt_nn_near(const gmmrrt_nn_t *nn, const gmmrrt_pool_t *pool, double x, double y,
                       double radius_m, int32_t *out, int32_t cap);

#endif /* GMMRRT_NN_H */
