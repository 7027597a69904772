/*
 * msg_decode.h - decode-and-validate for every gmmrrt LCM message.
 *
 * LCM's generated decoders check only the wire format. These wrappers add what a
 * planner must not trust: counts within the declared capacity (MAX_* constants in
 * lcmtypes/), finite numbers in every meaningful field, positive sizes, known enum
 * values. All gmmrrt arrays have a fixed capacity, and the one string (the frame, below)
 * is bounded before it is allocated: nothing on the wire sizes an allocation.
 *
 * Every function: decodes `len` bytes at `buf` into `*out` (caller-owned), returns
 * GMMRRT_MSG_OK or the reason for rejection, and on rejection writes a one-line
 * message naming the type and field into err[errcap] (may be NULL).
 *
 * Frames: pose2d_t, people_t, nav_goal_t, obstacles_t, waypoints_t and occupancy_grid_t
 * carry a `frame` string (the frame of their coordinates), second on the wire after utime.
 * LCM's generated decoder allocates it; here its length is judged on the wire first
 * (1..GMMRRT_MSG_FRAME_MAX bytes of printable ASCII without spaces, NUL-terminated), so the
 * allocation is at most GMMRRT_MSG_FRAME_MAX + 1 bytes. On GMMRRT_MSG_OK out->frame is that
 * heap string, owned by the caller: release it with gmmrrt_msg_release_<type>(out). On
 * rejection nothing is held (out->frame is NULL). Which frame is right is the receiver's to
 * say: gmmrrt_msg_check_frame. planar_scan_t has no frame: its coordinates are the sensor's
 * and the robot's own, placed in a world frame only through the robot's pose at its stamp.
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
 * (decode, count over bound, not finite, bad value, unknown command, wrong frame) as the
 * daemon counts them. */
typedef enum {
    GMMRRT_MSG_OK = 0,
    GMMRRT_MSG_DECODE_FAILED = 1,    /* wrong fingerprint, truncated, malformed */
    GMMRRT_MSG_COUNT_OVER_BOUND = 2, /* a count is negative or above its MAX_* */
    GMMRRT_MSG_NOT_FINITE = 3,       /* NaN or Inf in a meaningful field */
    GMMRRT_MSG_BAD_VALUE = 4,        /* out of range: radius <= 0, unknown task, ... */
    GMMRRT_MSG_UNKNOWN_COMMAND = 5,  /* nav_goal_t.command is not COMMAND_NEW or COMMAND_CANCEL */
    GMMRRT_MSG_WRONG_FRAME = 6       /* gmmrrt_msg_check_frame: not the receiver's frame */
} gmmrrt_msg_result_t;

/* Longest frame name (bytes, without the NUL). */
#define GMMRRT_MSG_FRAME_MAX 64

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
/* occupancy_grid_t: frame judged as for every framed type (above); width and height >= 1
 * (BAD_VALUE) with width x height <= MAX_CELLS (COUNT_OVER_BOUND) and num_cells equal to it
 * (BAD_VALUE); resolution and origin finite (NOT_FINITE), resolution > 0 (BAD_VALUE); every used
 * cell -1 or 0..100 (BAD_VALUE, naming the first bad cell). */
gmmrrt_msg_result_t gmmrrt_msg_decode_occupancy_grid(const void *buf, size_t len, gmmrrt_occupancy_grid_t *out,
                                                     char *err, size_t errcap);
/* The receiver's rule for frames: GMMRRT_MSG_OK when `frame` is `expected` (byte for byte),
 * else GMMRRT_MSG_WRONG_FRAME with both named in err (type names the message, may be NULL). */
gmmrrt_msg_result_t gmmrrt_msg_check_frame(const char *type, const char *frame, const char *expected, char *err,
                                           size_t errcap);

/* The rule for a frame's name, for a receiver's own setting: GMMRRT_MSG_OK when `name` is
 * 1..GMMRRT_MSG_FRAME_MAX bytes of printable ASCII without spaces, else GMMRRT_MSG_BAD_VALUE. */
gmmrrt_msg_result_t gmmrrt_msg_check_frame_name(const char *name, char *err, size_t errcap);

/* Release the frame string of a message decoded with GMMRRT_MSG_OK (no-op on NULL, and on a
 * message already released). */
void gmmrrt_msg_release_pose2d(gmmrrt_pose2d_t *m);
void gmmrrt_msg_release_people(gmmrrt_people_t *m);
void gmmrrt_msg_release_nav_goal(gmmrrt_nav_goal_t *m);
void gmmrrt_msg_release_obstacles(gmmrrt_obstacles_t *m);
void gmmrrt_msg_release_waypoints(gmmrrt_waypoints_t *m);
void gmmrrt_msg_release_occupancy_grid(gmmrrt_occupancy_grid_t *m);

gmmrrt_msg_result_t gmmrrt_msg_decode_demo_info(const void *buf, size_t len, gmmrrt_demo_info_t *out,
                                                char *err, size_t errcap);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_MSG_DECODE_H */
