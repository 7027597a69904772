/*
 * msg_decode.h - decode-and-validate for every gmmrrt LCM message.
 *
 * LCM's generated decoders check only the wire format. These wrappers add what a
 * planner must not trust: counts within the declared capacity (MAX_* constants in
 * lcmtypes/), finite numbers in every meaningful field, positive sizes, known enum
 * values. All gmmrrt messages use fixed-capacity arrays, so nothing on the wire
 * sizes an allocation (occupancy_grid_t's frame string is the one allocation of a
 * generated decoder, freed before its wrapper returns).
 *
 * Every function: decodes `len` bytes at `buf` into `*out` (caller-owned), returns
 * GMMRRT_MSG_OK or the reason for rejection, and on rejection writes a one-line
 * message naming the type and field into err[errcap] (may be NULL).
 */
#ifndef GMMRRT_MSG_DECODE_H
#define GMMRRT_MSG_DECODE_H

#include <stddef.h>

#include "gmmrrt/gmmrrt_demo_info_t.h"
#include "gmmrrt/gmmrrt_nav_goal_t.h"
#include "gmmrrt/gmmrrt_obstacles_t.h"
#include "gmmrrt/gmmrrt_occupancy_grid_t.h"
#include "gmmrrt/gmmrrt_people_t.h"
#include "gmmrrt/gmmrrt_planar_scan_t.h"
#include "gmmrrt/gmmrrt_planner_status_t.h"
#include "gmmrrt/gmmrrt_pose2d_t.h"
#include "gmmrrt/gmmrrt_waypoints_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Why a message was rejected. Maps one-to-one onto planner_status_t.REJECT_*
 * (decode, count over bound, not finite, bad value) as the daemon counts them. */
typedef enum {
    GMMRRT_MSG_OK = 0,
    GMMRRT_MSG_DECODE_FAILED = 1,    /* wrong fingerprint, truncated, malformed */
    GMMRRT_MSG_COUNT_OVER_BOUND = 2, /* a count is negative or above its MAX_* */
    GMMRRT_MSG_NOT_FINITE = 3,       /* NaN or Inf in a meaningful field */
    GMMRRT_MSG_BAD_VALUE = 4         /* out of range: radius <= 0, unknown task, ... */
} gmmrrt_msg_result_t;

const char *gmmrrt_msg_result_str(gmmrrt_msg_result_t r);

gmmrrt_msg_result_t gmmrrt_msg_decode_pose2d(const void *buf, size_t len, gmmrrt_pose2d_t *out,
                                             char *err, size_t errcap);
gmmrrt_msg_result_t gmmrrt_msg_decode_people(const void *buf, size_t len, gmmrrt_people_t *out,
                                             char *err, size_t errcap);
gmmrrt_msg_result_t gmmrrt_msg_decode_nav_goal(const void *buf, size_t len, gmmrrt_nav_goal_t *out,
                                               char *err, size_t errcap);
gmmrrt_msg_result_t gmmrrt_msg_decode_obstacles(const void *buf, size_t len, gmmrrt_obstacles_t *out,
                                                char *err, size_t errcap);
gmmrrt_msg_result_t gmmrrt_msg_decode_waypoints(const void *buf, size_t len, gmmrrt_waypoints_t *out,
                                                char *err, size_t errcap);
gmmrrt_msg_result_t gmmrrt_msg_decode_planner_status(const void *buf, size_t len,
                                                     gmmrrt_planner_status_t *out, char *err,
                                                     size_t errcap);
/* planar_scan_t: num_ranges within 0..MAX_RANGES (COUNT_OVER_BOUND); rad0, radstep, the last
 * beam's angle rad0 + (num_ranges - 1) radstep, the limits and the sensor's pose finite
 * (NOT_FINITE); range_min_m >= 0 and range_max_m > range_min_m (BAD_VALUE). Ranges are not
 * judged: NaN, +-inf and out-of-range values are "no return" and kept as they are. */
gmmrrt_msg_result_t gmmrrt_msg_decode_planar_scan(const void *buf, size_t len, gmmrrt_planar_scan_t *out,
                                                  char *err, size_t errcap);
/* occupancy_grid_t: frame "map" or "" (BAD_VALUE: the daemon has no transforms); width and
 * height >= 1 (BAD_VALUE) with width x height <= MAX_CELLS (COUNT_OVER_BOUND) and num_cells equal
 * to it (BAD_VALUE); resolution and origin finite (NOT_FINITE), resolution > 0 (BAD_VALUE); every
 * used cell -1 or 0..100 (BAD_VALUE, naming the first bad cell). The frame string the generated
 * decoder allocates is freed before returning: out->frame then points to a static "map" or "" (the
 * value received when accepted), so the caller's copy owns no memory. */
gmmrrt_msg_result_t gmmrrt_msg_decode_occupancy_grid(const void *buf, size_t len, gmmrrt_occupancy_grid_t *out,
                                                     char *err, size_t errcap);
gmmrrt_msg_result_t gmmrrt_msg_decode_demo_info(const void *buf, size_t len, gmmrrt_demo_info_t *out,
                                                char *err, size_t errcap);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_MSG_DECODE_H */
