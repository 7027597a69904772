/*
 * collision_internal.h - internal: a read-only view of the clearance grid of collision.c, so
 * tests can compare a kept or shifted grid with a fresh one cell for cell (docs/planner.md,
 * "Collision checking"). Not a public header; the planner does not use it.
 */
#ifndef GMMRRT_COLLISION_INTERNAL_H
#define GMMRRT_COLLISION_INTERNAL_H

#include <stdint.h>

#include "gmmrrt/collision.h"

/* The grid's cells, row-major (j * nx + i); cell (i, j) is centred at ((gi0 + i + 0.5) res,
 * (gj0 + j + 0.5) res). Fills nx, ny, gi0, gj0 (lattice index of cell (0, 0)); NULL when
 * world is NULL. The pointer is into the world's memory, valid until its next update. */
const float *gmmrrt_world_grid_cells(const gmmrrt_world_t *world, int32_t *nx, int32_t *ny, double *gi0,
                                     double *gj0);

#endif /* GMMRRT_COLLISION_INTERNAL_H */
