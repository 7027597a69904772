/*
 * status.h - the one status type of the gmmrrt C library.
 *
 * Like SQLite's result codes and OMPL's PlannerStatus: every public function that can
 * fail returns a gmmrrt_status_t naming the reason, never a bare -1. The numeric values
 * are stable: they travel in waypoints_t.status and planner_status_t.last_error.
 */
#ifndef GMMRRT_STATUS_H
#define GMMRRT_STATUS_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    GMMRRT_OK = 0,

    /* Arguments and memory */
    GMMRRT_ERR_INVALID_ARGUMENT = 1,   /* NULL, NaN/Inf, out-of-range parameter */
    GMMRRT_ERR_BUFFER_TOO_SMALL = 2,   /* caller-provided memory smaller than required */

    /* Model files (model.h); each names what the loader found wrong */
    GMMRRT_ERR_MODEL_TRUNCATED = 10,     /* shorter than its header says */
    GMMRRT_ERR_MODEL_BAD_MAGIC = 11,     /* not a gmmrrt model file */
    GMMRRT_ERR_MODEL_BAD_VERSION = 12,   /* format version this build cannot read */
    GMMRRT_ERR_MODEL_BAD_BYTE_ORDER = 13,/* byte-order mark is not little-endian */
    GMMRRT_ERR_MODEL_BAD_SIZE = 14,      /* D or K outside limits.h, or length mismatch */
    GMMRRT_ERR_MODEL_BAD_CHECKSUM = 15,  /* CRC-32 does not match */
    GMMRRT_ERR_MODEL_NOT_FINITE = 16,    /* NaN or Inf in a stored number */
    GMMRRT_ERR_MODEL_NOT_POSITIVE_DEFINITE = 17, /* a covariance factor has a diagonal <= 0 or is ill-conditioned */
    GMMRRT_ERR_MODEL_BAD_WEIGHTS = 18,   /* a weight outside (0, 1] or the sum is not 1 */
    GMMRRT_ERR_MODEL_BAD_FIELD = 19,     /* unknown kind, task, homotopy, angle flag or delta */
    GMMRRT_ERR_MODEL_TOO_LARGE = 20,     /* file larger than any valid model */
    GMMRRT_ERR_IO = 21,                  /* file could not be opened, read or written (io/ only) */

    /* Planning problems */
    GMMRRT_ERR_START_IN_COLLISION = 30,
    GMMRRT_ERR_GOAL_IN_COLLISION = 31,
    GMMRRT_ERR_START_OUT_OF_BOUNDS = 32,
    GMMRRT_ERR_GOAL_OUT_OF_BOUNDS = 33,
    GMMRRT_ERR_MODEL_MISMATCH = 34,      /* model kind or dimension does not fit the planner */
    GMMRRT_ERR_FROZEN = 35,              /* start in collision and no motion increases the clearance
                                            (gmmrrt_planner_escape_reason says why) */

    /* Planning outcomes that are not failures of the call */
    GMMRRT_NO_PATH_YET = 40,             /* budget spent, goal not reached (yet) */
    GMMRRT_POOL_FULL = 41,               /* node pool exhausted; best path so far kept */
    GMMRRT_TIMEOUT = 42,                 /* deadline reached before any work could be done */
    GMMRRT_ESCAPE = 43,                  /* start in collision: the plan first leaves along the shortest
                                            way out that increases clearance, then goes to the goal */
    GMMRRT_NO_PATH_ON_SIDE = 44,         /* budget spent, no path on the preferred side (yet); re-plan
                                            with GMMRRT_SIDE_EITHER to take the other side */
    GMMRRT_TIGHT_TURNS = 45,             /* a drivable path (drivable.h) that turns tighter than the minimum
                                            turning radius at some corner, or in place, where no free arc
                                            exists: a path all the same, flagged for the follower to slow
                                            down or turn on the spot there */

    /* 50 and above are not the library's: gmmrrtd's stop codes (planner/daemon/stop.h). */
} gmmrrt_status_t;

/* A short, static, human-readable description of `status` ("start in collision").
 * Unknown values give "unknown status". Never NULL. */
const char *gmmrrt_status_str(gmmrrt_status_t status);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_STATUS_H */
