/*
 * block_layout.h - carving a caller-owned memory block into regions (STYLE: caller-owned memory,
 * like lcm-lite's lcmlite_init): every region starts on an 8-byte boundary, so doubles and
 * int64 fields are aligned wherever the block itself is. The one statement of that rule for the
 * planner, the collision world and the raster.
 */
#ifndef GMMRRT_BLOCK_LAYOUT_H
#define GMMRRT_BLOCK_LAYOUT_H

#include <stddef.h>

/* n rounded up to a multiple of 8. */
static inline size_t gmmrrt_align8(size_t n) { return (n + 7u) & ~(size_t)7u; }

/* Reserves `bytes` at *off: returns the region's offset and moves *off past it, to the next
 * 8-byte boundary. */
static inline size_t gmmrrt_block_take(size_t *off, size_t bytes)
{
    const size_t at = *off;
    *off += gmmrrt_align8(bytes);
    return at;
}

#endif /* GMMRRT_BLOCK_LAYOUT_H */
