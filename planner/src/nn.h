/*
 * nn.h - internal: the nearest-neighbour index of the tree, a uniform grid of buckets over
 * the planning bounds whose lists run through the node pool (one int32_t per node, one
 * int32_t head per bucket). The RRT* needs the nearest node (extend) and the nodes within
 * a radius (choose-parent and rewire, Karaman & Frazzoli 2011, Alg. 6). Checked against a
 * linear scan in tests/unit/planner/test_nn.c.
 */
#ifndef GMMRRT_NN_H
#define GMMRRT_NN_H

#include <stdint.h>

#include "gmmrrt/collision.h"

/* One tree node: 40 bytes; with its bucket head 44 bytes per node of capacity. */
typedef struct {
    double x, y;           /* m, world */
    double cost;           /* cost-to-come from the root */
    int32_t parent;        /* -1 for the root */
    int32_t first_child;   /* -1 when a leaf */
    int32_t next_sibling;  /* next child of the same parent, -1 at the end */
    int32_t next_in_bucket;/* spatial index list, -1 at the end */
} gmmrrt_node_t;

typedef struct {
    int32_t *heads;        /* capacity buckets, owned by the planner block */
    int32_t capacity;
    int32_t nx, ny;
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

/* Adds node `idx` (its x, y set) to the index (adaptive: nodes 0..idx-1 already in). */
void gmmrrt_nn_insert(gmmrrt_nn_t *nn, gmmrrt_node_t *nodes, int32_t idx);

/* Index of the node nearest to (x, y) (ties: the one found first), -1 when empty. */
int32_t gmmrrt_nn_nearest(const gmmrrt_nn_t *nn, const gmmrrt_node_t *nodes, double x, double y);

/* Writes the indices of nodes within radius_m of (x, y) (distance <= radius_m) into
 * out[cap]; returns their number, or -1 when there are more than cap (out then holds
 * a partial list). */
int32_t gmmrrt_nn_near(const gmmrrt_nn_t *nn, const gmmrrt_node_t *nodes, double x, double y,
                       double radius_m, int32_t *out, int32_t cap);

#endif /* GMMRRT_NN_H */
