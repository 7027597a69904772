/*
 * limits.h - every capacity of the gmmrrt library in one place (like SQLite's sqliteLimit.h).
 *
 * Each limit has a default that can be overridden at compile time (-DGMMRRT_MAX_K=128)
 * and a hard ceiling checked here. Anything read from a file or the wire is checked
 * against these before it sizes or indexes anything.
 */
#ifndef GMMRRT_LIMITS_H
#define GMMRRT_LIMITS_H

/* Feature dimension of a mixture. The paper uses D = 2 (d, theta); the GMM-RRT
 * baseline's xy model uses D = 3 (progress, x, y); users may bring up to 8. */
#ifndef GMMRRT_MAX_DIM
#define GMMRRT_MAX_DIM 8
#endif

/* Mixture components. The paper uses k = 19; BIC sweeps go to 30. 64 leaves room. */
#ifndef GMMRRT_MAX_K
#define GMMRRT_MAX_K 64
#endif

/* Bytes of the provenance text a model file may carry after the model (model.h: the
 * learner's record of the data hash, command line, seed, K, BIC and log-likelihood). Bounds
 * what a loader reads; 4096 holds a command line of a few dozen input paths. */
#ifndef GMMRRT_MAX_PROVENANCE_BYTES
#define GMMRRT_MAX_PROVENANCE_BYTES 4096
#endif

/* People considered by the planner; equals people_t.MAX_PEOPLE on the wire. */
#ifndef GMMRRT_MAX_PEOPLE
#define GMMRRT_MAX_PEOPLE 32
#endif

/* Obstacles; equal obstacles_t.MAX_CIRCLES / MAX_BOXES on the wire. */
#ifndef GMMRRT_MAX_CIRCLES
#define GMMRRT_MAX_CIRCLES 64
#endif
#ifndef GMMRRT_MAX_BOXES
#define GMMRRT_MAX_BOXES 64
#endif

/* Waypoints of one published plan; equals waypoints_t.MAX_WAYPOINTS. */
#ifndef GMMRRT_MAX_WAYPOINTS
#define GMMRRT_MAX_WAYPOINTS 256
#endif

/* Largest weight of a cost term (w_length, w_task). An edge costs at most (w_length + w_task)
 * times its length (the task term's factor delta / max(p, delta) is <= 1), so with weights up
 * to 1e6 a path's cost stays far inside a double; 1e308 turned every cost into inf and every
 * plan into "no path yet". Not overridable: it guards arithmetic, not memory. */
#define GMMRRT_MAX_COST_WEIGHT 1e6

/* Occupancy rasters (raster.h): a side is indexed in int32_t and its squared length must stay
 * exact in a float (2^24 = 4096^2 is exact; 16384^2 cells of a side is the ceiling, whose
 * rounding the field absorbs, raster.c). The cells ceiling keeps byte offsets inside int32_t. */
#define GMMRRT_MAX_RASTER_SIDE 16384
#define GMMRRT_MAX_RASTER_CELLS (1 << 28)

/* Beams of one planar scan: a 1081-beam lidar (270 deg at 0.25 deg) with room. */
#ifndef GMMRRT_MAX_SCAN_RANGES
#define GMMRRT_MAX_SCAN_RANGES 4096
#endif

/* Tree nodes: nodes link by int32_t index, so the ceiling keeps every index and
 * every byte offset into the pool well inside int32_t. */
#define GMMRRT_MAX_NODES_CEILING (1 << 22)
#ifndef GMMRRT_DEFAULT_MAX_NODES
#define GMMRRT_DEFAULT_MAX_NODES 50000
#endif

/* Packed lower triangle of a D x D matrix. */
#define GMMRRT_TRI(d) ((d) * ((d) + 1) / 2)
#define GMMRRT_MAX_TRI GMMRRT_TRI(GMMRRT_MAX_DIM)

#if GMMRRT_MAX_DIM < 3 || GMMRRT_MAX_DIM > 16
#error "GMMRRT_MAX_DIM must be in 3..16 (the xy model needs 3; the angle mask is 32 bits)"
#endif
#if GMMRRT_MAX_K < 1 || GMMRRT_MAX_K > 1024
#error "GMMRRT_MAX_K must be in 1..1024"
#endif
#if GMMRRT_MAX_PROVENANCE_BYTES < 256 || GMMRRT_MAX_PROVENANCE_BYTES > 65536
#error "GMMRRT_MAX_PROVENANCE_BYTES must be in 256..65536"
#endif
#if GMMRRT_MAX_PEOPLE < 1 || GMMRRT_MAX_PEOPLE > 256
#error "GMMRRT_MAX_PEOPLE must be in 1..256"
#endif
#if GMMRRT_MAX_CIRCLES < 0 || GMMRRT_MAX_CIRCLES > 4096 || GMMRRT_MAX_BOXES < 0 || GMMRRT_MAX_BOXES > 4096
#error "GMMRRT_MAX_CIRCLES and GMMRRT_MAX_BOXES must be in 0..4096"
#endif
#if GMMRRT_MAX_WAYPOINTS < 2 || GMMRRT_MAX_WAYPOINTS > 65536
#error "GMMRRT_MAX_WAYPOINTS must be in 2..65536"
#endif
#if GMMRRT_DEFAULT_MAX_NODES < 2 || GMMRRT_DEFAULT_MAX_NODES > GMMRRT_MAX_NODES_CEILING
#error "GMMRRT_DEFAULT_MAX_NODES must be in 2..GMMRRT_MAX_NODES_CEILING"
#endif

#endif /* GMMRRT_LIMITS_H */
