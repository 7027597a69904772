/*
 * collision_internal.h - internal: a read-only view of the clearance grid of collision.c, so
 * tests can compare a kept or shifted grid with a fresh one cell for cell, and see which tiles
 * the queries computed (docs/planner.md,
 * "Collision checking"). Not a public header; the planner does not use it.
 */
#ifndef GMMRRT_COLLISION_INTERNAL_H
#define GMMRRT_COLLISION_INTERNAL_H

#include <stdint.h>

#include "gmmrrt/collision.h"

/* The grid's extent: nx x ny cells, cell (i, j) centred at ((gi0 + i + 0.5) res,
 * (gj0 + j + 0.5) res) (gi0, gj0: lattice index of cell (0, 0)). 0 when an argument is NULL. */
int gmmrrt_world_grid_layout(const gmmrrt_world_t *world, int32_t *nx, int32_t *ny, double *gi0, double *gj0);

/* Cell (i, j)'s stored value (its tile computed first if no query has read it); NAN outside
 * the grid or when world is NULL. */
float gmmrrt_world_grid_cell(const gmmrrt_world_t *world, int32_t i, int32_t j);

/* Tiles computed so far; -1 when world is NULL. */
int64_t gmmrrt_world_grid_tiles_ready(const gmmrrt_world_t *world);

#endif /* GMMRRT_COLLISION_INTERNAL_H */
