/*
 * msg_decode.c - decode-and-validate for the gmmrrt LCM messages (see msg_decode.h).
 * Validation rules per field are listed in docs/messages.md.
 */
#include "gmmrrt/msg_decode.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gmmrrt/detail/reason_text.h"
#include "gmmrrt/limits.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* One bound: the wire's capacity is the core's scan capacity (raster.h). */
_Static_assert(GMMRRT_PLANAR_SCAN_T_MAX_RANGES == GMMRRT_MAX_SCAN_RANGES,
               "planar_scan_t.MAX_RANGES must equal GMMRRT_MAX_SCAN_RANGES");
/* A grid must fit the raster's hard ceilings (limits.h). */
_Static_assert(GMMRRT_OCCUPANCY_GRID_T_MAX_CELLS <= GMMRRT_MAX_RASTER_CELLS,
               "occupancy_grid_t.MAX_CELLS above GMMRRT_MAX_RASTER_CELLS");

static gmmrrt_msg_result_t reject(gmmrrt_msg_result_t r, char *err, size_t errcap, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

static gmmrrt_msg_result_t reject(gmmrrt_msg_result_t r, char *err, size_t errcap, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    gmmrrt_vformat_reason(err, errcap, fmt, ap);
    va_end(ap);
    return r;
}

const char *gmmrrt_msg_result_str(gmmrrt_msg_result_t r)
{
    switch (r) {
    case GMMRRT_MSG_OK: return "ok";
    case GMMRRT_MSG_DECODE_FAILED: return "decode failed";
    case GMMRRT_MSG_COUNT_OVER_BOUND: return "count over bound";
    case GMMRRT_MSG_NOT_FINITE: return "not finite";
    case GMMRRT_MSG_BAD_VALUE: return "bad value";
    case GMMRRT_MSG_UNKNOWN_COMMAND: return "unknown command";
    case GMMRRT_MSG_WRONG_FRAME: return "wrong frame";
    }
    return "unknown";
}

gmmrrt_msg_result_t gmmrrt_msg_check_frame(const char *type, const char *frame, const char *expected, char *err,
                                           size_t errcap)
{
    if (frame == NULL || expected == NULL || strcmp(frame, expected) != 0)
        return reject(GMMRRT_MSG_WRONG_FRAME, err, errcap, "%s.frame \"%.64s\" is not the planning frame \"%.64s\"",
                      type != NULL ? type : "message", frame != NULL ? frame : "(none)",
                      expected != NULL ? expected : "(none)");
    return GMMRRT_MSG_OK;
}

/* The generated decoders take an int length; anything larger cannot be a gmmrrt message. */
static int decodable_len(size_t len) { return len <= (size_t)INT32_MAX; }

#define DECODE_OR_REJECT(type, buf, len, out, err, errcap)                                              \
    do {                                                                                                \
        if ((buf) == NULL || (out) == NULL || !decodable_len(len) ||                                    \
            gmmrrt_##type##_decode((buf), 0, (int)(len), (out)) < 0)                                    \
            return reject(GMMRRT_MSG_DECODE_FAILED, (err), (errcap),                                    \
                          #type ": cannot decode %zu bytes (wrong type or truncated)", (size_t)(len));  \
    } while (0)

/* The frame string of a type that has one sits right after the fingerprint and utime: an int32
 * big-endian length that counts the terminating NUL, then the bytes. LCM's generated decoder
 * allocates that length before it reads anything else, so it is read and judged here first:
 * nothing on the wire sizes an allocation beyond GMMRRT_MSG_FRAME_MAX + 1 bytes, and the string
 * the generated decoder makes is known to be terminated. */
enum { k_frame_offset = 16 };

/* The rule for a frame's name: 1..GMMRRT_MSG_FRAME_MAX bytes, each printable ASCII but the space. */
static gmmrrt_msg_result_t check_frame_name(const char *type, const uint8_t *name, size_t n, char *err,
                                            size_t errcap)
{
    if (n == 0 || n > GMMRRT_MSG_FRAME_MAX)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "%s is %zu bytes long: 1..%d bytes allowed", type, n,
                      GMMRRT_MSG_FRAME_MAX);
    for (size_t i = 0; i < n; ++i)
        if (name[i] < 0x21 || name[i] > 0x7e)
            return reject(GMMRRT_MSG_BAD_VALUE, err, errcap,
                          "%s has byte 0x%02x at %zu: printable ASCII without spaces only", type,
                          (unsigned)name[i], i);
    return GMMRRT_MSG_OK;
}

gmmrrt_msg_result_t gmmrrt_msg_check_frame_name(const char *name, char *err, size_t errcap)
{
    if (name == NULL)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "frame: no name");
    const char *end = memchr(name, '\0', GMMRRT_MSG_FRAME_MAX + 1);
    const size_t n = end != NULL ? (size_t)(end - name) : GMMRRT_MSG_FRAME_MAX + 1;
    return check_frame_name("the frame name", (const uint8_t *)name, n, err, errcap);
}

static gmmrrt_msg_result_t check_frame_on_wire(const char *type, int64_t fingerprint, const void *buf, size_t len,
                                               char *err, size_t errcap)
{
    const uint8_t *b = buf;
    if (b == NULL || !decodable_len(len) || len < k_frame_offset + 4)
        return reject(GMMRRT_MSG_DECODE_FAILED, err, errcap, "%s: cannot decode %zu bytes (wrong type or truncated)",
                      type, len);
    uint64_t fp = 0;
    for (int i = 0; i < 8; ++i)
        fp = fp << 8 | b[i];
    if ((int64_t)fp != fingerprint)
        return reject(GMMRRT_MSG_DECODE_FAILED, err, errcap, "%s: cannot decode %zu bytes (wrong type or truncated)",
                      type, len);
    const uint32_t n = (uint32_t)b[16] << 24 | (uint32_t)b[17] << 16 | (uint32_t)b[18] << 8 | (uint32_t)b[19];
    if (n == 0 || n > (uint32_t)len - (k_frame_offset + 4) || b[k_frame_offset + 4 + n - 1] != 0)
        return reject(GMMRRT_MSG_DECODE_FAILED, err, errcap,
                      "%s.frame: a string of %lu bytes does not fit the %zu-byte message or lacks its NUL", type,
                      (unsigned long)n, len);
    char what[48];
    snprintf(what, sizeof what, "%s.frame", type);
    return check_frame_name(what, b + k_frame_offset + 4, n - 1, err, errcap);
}

/* For a type with a frame: the frame judged on the wire, then the generated decoder into a
 * zeroed *out (so a failure after the frame was allocated frees exactly what was). From here on
 * every rejection goes through REJECT_HOLDING, which releases the frame. */
#define DECODE_WITH_FRAME_OR_REJECT(type, buf, len, out, err, errcap)                                    \
    do {                                                                                                \
        if ((out) == NULL)                                                                              \
            return reject(GMMRRT_MSG_DECODE_FAILED, (err), (errcap), #type ": no output");             \
        const gmmrrt_msg_result_t fr_ =                                                                 \
            check_frame_on_wire(#type, __gmmrrt_##type##_get_hash(), (buf), (len), (err), (errcap));     \
        if (fr_ != GMMRRT_MSG_OK)                                                                       \
            return fr_;                                                                                 \
        memset((out), 0, sizeof *(out));                                                                \
        if (gmmrrt_##type##_decode((buf), 0, (int)(len), (out)) < 0) {                                  \
            free((out)->frame);                                                                         \
            (out)->frame = NULL;                                                                        \
            return reject(GMMRRT_MSG_DECODE_FAILED, (err), (errcap),                                    \
                          #type ": cannot decode %zu bytes (wrong type or truncated)", (size_t)(len));  \
        }                                                                                               \
    } while (0)

#define REQUIRE_FINITE(type, field, value, err, errcap)                                                 \
    do {                                                                                                \
        if (!isfinite(value))                                                                           \
            return reject(GMMRRT_MSG_NOT_FINITE, (err), (errcap), #type ".%s is not finite", (field));   \
    } while (0)

static gmmrrt_msg_result_t check_count(const char *type, const char *field, int32_t n, int32_t max,
                                       char *err, size_t errcap)
{
    if (n < 0 || n > max)
        return reject(GMMRRT_MSG_COUNT_OVER_BOUND, err, errcap, "%s.%s = %d is outside 0..%d", type,
                      field, (int)n, (int)max);
    return GMMRRT_MSG_OK;
}

static gmmrrt_msg_result_t validate_pose2d(const gmmrrt_pose2d_t *out, char *err, size_t errcap)
{
    REQUIRE_FINITE(pose2d_t, "x", out->x, err, errcap);
    REQUIRE_FINITE(pose2d_t, "y", out->y, err, errcap);
    REQUIRE_FINITE(pose2d_t, "yaw", out->yaw, err, errcap);
    if (out->velocity_valid) {
        REQUIRE_FINITE(pose2d_t, "vx", out->vx, err, errcap);
        REQUIRE_FINITE(pose2d_t, "vy", out->vy, err, errcap);
        REQUIRE_FINITE(pose2d_t, "yaw_rate", out->yaw_rate, err, errcap);
    }
    return GMMRRT_MSG_OK;
}

static gmmrrt_msg_result_t validate_people(const gmmrrt_people_t *out, char *err, size_t errcap)
{
    gmmrrt_msg_result_t r =
        check_count("people_t", "num_people", out->num_people, GMMRRT_PEOPLE_T_MAX_PEOPLE, err, errcap);
    if (r != GMMRRT_MSG_OK)
        return r;
    for (int32_t i = 0; i < out->num_people; ++i) {
        const gmmrrt_person_t *p = &out->people[i];
        const char *bad = !isfinite(p->x)     ? "x"
                          : !isfinite(p->y)   ? "y"
                          : !isfinite(p->yaw) ? "yaw"
                          : !isfinite(p->vx)  ? "vx"
                          : !isfinite(p->vy)  ? "vy"
                                              : NULL;
        if (bad != NULL)
            return reject(GMMRRT_MSG_NOT_FINITE, err, errcap, "people_t.people[%d].%s is not finite", (int)i,
                          bad);
        if (p->id < 0)
            return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "people_t.people[%d].id = %d is negative", (int)i,
                          (int)p->id);
    }
    return GMMRRT_MSG_OK;
}

/* A CANCEL names its goal only; a NEW is a whole goal. The command is judged before anything
 * else, so that an unknown command is counted as that rather than by whatever its other fields
 * hold. */
static gmmrrt_msg_result_t validate_nav_goal(const gmmrrt_nav_goal_t *out, char *err, size_t errcap)
{
    if (out->command != GMMRRT_NAV_GOAL_T_COMMAND_NEW && out->command != GMMRRT_NAV_GOAL_T_COMMAND_CANCEL)
        return reject(GMMRRT_MSG_UNKNOWN_COMMAND, err, errcap,
                      "nav_goal_t.command = %d is not COMMAND_NEW (1) or COMMAND_CANCEL (2)", (int)out->command);
    if (out->goal_id <= 0)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "nav_goal_t.goal_id = %lld must be > 0",
                      (long long)out->goal_id);
    if (out->command == GMMRRT_NAV_GOAL_T_COMMAND_CANCEL)
        return GMMRRT_MSG_OK;
    REQUIRE_FINITE(nav_goal_t, "x", out->x, err, errcap);
    REQUIRE_FINITE(nav_goal_t, "y", out->y, err, errcap);
    REQUIRE_FINITE(nav_goal_t, "yaw", out->yaw, err, errcap);
    REQUIRE_FINITE(nav_goal_t, "tolerance_m", out->tolerance_m, err, errcap);
    REQUIRE_FINITE(nav_goal_t, "yaw_tolerance_rad", out->yaw_tolerance_rad, err, errcap);
    if (!(out->tolerance_m > 0.0))
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "nav_goal_t.tolerance_m = %g must be > 0",
                      out->tolerance_m);
    if (!(out->yaw_tolerance_rad >= 0.0 && out->yaw_tolerance_rad <= M_PI))
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap,
                      "nav_goal_t.yaw_tolerance_rad = %g must be within [0, pi] (0: heading not judged)",
                      out->yaw_tolerance_rad);
    if (out->task != GMMRRT_NAV_GOAL_T_TASK_NONE && out->task != GMMRRT_NAV_GOAL_T_TASK_AVOID &&
        out->task != GMMRRT_NAV_GOAL_T_TASK_APPROACH)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "nav_goal_t.task = %d is not a TASK_* value",
                      (int)out->task);
    if (out->task == GMMRRT_NAV_GOAL_T_TASK_APPROACH && out->target_person_id < 0)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap,
                      "nav_goal_t.target_person_id = %d: TASK_APPROACH needs a person id >= 0",
                      (int)out->target_person_id);
    if (out->preferred_side != GMMRRT_NAV_GOAL_T_SIDE_EITHER && out->preferred_side != GMMRRT_NAV_GOAL_T_SIDE_LEFT &&
        out->preferred_side != GMMRRT_NAV_GOAL_T_SIDE_RIGHT)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap,
                      "nav_goal_t.preferred_side = %d is not SIDE_EITHER (0), SIDE_LEFT (1) or SIDE_RIGHT (-1)",
                      (int)out->preferred_side);
    return GMMRRT_MSG_OK;
}

static gmmrrt_msg_result_t validate_obstacles(const gmmrrt_obstacles_t *out, char *err, size_t errcap)
{
    gmmrrt_msg_result_t r = check_count("obstacles_t", "num_circles", out->num_circles,
                                        GMMRRT_OBSTACLES_T_MAX_CIRCLES, err, errcap);
    if (r == GMMRRT_MSG_OK)
        r = check_count("obstacles_t", "num_boxes", out->num_boxes, GMMRRT_OBSTACLES_T_MAX_BOXES, err, errcap);
    if (r != GMMRRT_MSG_OK)
        return r;
    for (int32_t i = 0; i < out->num_circles; ++i) {
        const char *bad = !isfinite(out->circle_x[i])        ? "circle_x"
                          : !isfinite(out->circle_y[i])      ? "circle_y"
                          : !isfinite(out->circle_radius[i]) ? "circle_radius"
                                                             : NULL;
        if (bad != NULL)
            return reject(GMMRRT_MSG_NOT_FINITE, err, errcap, "obstacles_t.%s[%d] is not finite", bad, (int)i);
        if (!(out->circle_radius[i] > 0.0))
            return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "obstacles_t.circle_radius[%d] = %g must be > 0",
                          (int)i, out->circle_radius[i]);
    }
    for (int32_t i = 0; i < out->num_boxes; ++i) {
        const char *bad = !isfinite(out->box_x[i])        ? "box_x"
                          : !isfinite(out->box_y[i])      ? "box_y"
                          : !isfinite(out->box_width[i])  ? "box_width"
                          : !isfinite(out->box_height[i]) ? "box_height"
                          : !isfinite(out->box_yaw[i])    ? "box_yaw"
                                                          : NULL;
        if (bad != NULL)
            return reject(GMMRRT_MSG_NOT_FINITE, err, errcap, "obstacles_t.%s[%d] is not finite", bad, (int)i);
        if (!(out->box_width[i] > 0.0))
            return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "obstacles_t.box_width[%d] = %g must be > 0", (int)i,
                          out->box_width[i]);
        if (!(out->box_height[i] > 0.0))
            return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "obstacles_t.box_height[%d] = %g must be > 0",
                          (int)i, out->box_height[i]);
    }
    return GMMRRT_MSG_OK;
}

static gmmrrt_msg_result_t validate_waypoints(const gmmrrt_waypoints_t *out, char *err, size_t errcap)
{
    gmmrrt_msg_result_t r = check_count("waypoints_t", "num_waypoints", out->num_waypoints,
                                        GMMRRT_WAYPOINTS_T_MAX_WAYPOINTS, err, errcap);
    if (r != GMMRRT_MSG_OK)
        return r;
    for (int32_t i = 0; i < out->num_waypoints; ++i) {
        const char *bad = !isfinite(out->x[i])     ? "x"
                          : !isfinite(out->y[i])   ? "y"
                          : !isfinite(out->yaw[i]) ? "yaw"
                                                   : NULL;
        if (bad != NULL)
            return reject(GMMRRT_MSG_NOT_FINITE, err, errcap, "waypoints_t.%s[%d] is not finite", bad, (int)i);
    }
    if (out->planner < GMMRRT_WAYPOINTS_T_PLANNER_NONE || out->planner > GMMRRT_WAYPOINTS_T_PLANNER_GMM_RRT)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "waypoints_t.planner = %d is not a PLANNER_* value",
                      (int)out->planner);
    if (out->task < GMMRRT_NAV_GOAL_T_TASK_NONE || out->task > GMMRRT_NAV_GOAL_T_TASK_APPROACH)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "waypoints_t.task = %d is not a TASK_* value",
                      (int)out->task);
    return GMMRRT_MSG_OK;
}

gmmrrt_msg_result_t gmmrrt_msg_decode_planner_status(const void *buf, size_t len,
                                                     gmmrrt_planner_status_t *out, char *err, size_t errcap)
{
    DECODE_OR_REJECT(planner_status_t, buf, len, out, err, errcap);
    if (out->state < GMMRRT_PLANNER_STATUS_T_STATE_IDLE || out->state > GMMRRT_PLANNER_STATUS_T_STATE_ERROR)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "planner_status_t.state = %d is not a STATE_* value",
                      (int)out->state);
    if (out->approach_model < -1 || out->approach_model > 7)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap,
                      "planner_status_t.approach_model = %d is not -1 or a direction 0..7", (int)out->approach_model);
    if (out->goal_state < GMMRRT_PLANNER_STATUS_T_GOAL_NONE || out->goal_state > GMMRRT_PLANNER_STATUS_T_GOAL_FAILED)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "planner_status_t.goal_state = %d is not a GOAL_* value",
                      (int)out->goal_state);
    if (out->goal_failure < GMMRRT_PLANNER_STATUS_T_FAILURE_NONE ||
        out->goal_failure > GMMRRT_PLANNER_STATUS_T_FAILURE_SETUP)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "planner_status_t.goal_failure = %d is not a FAILURE_* value",
                      (int)out->goal_failure);
    if (out->side_result < GMMRRT_PLANNER_STATUS_T_SIDE_NOT_ASKED ||
        out->side_result > GMMRRT_PLANNER_STATUS_T_SIDE_NOT_FOUND)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "planner_status_t.side_result = %d is not a SIDE_* value",
                      (int)out->side_result);
    return GMMRRT_MSG_OK;
}

gmmrrt_msg_result_t gmmrrt_msg_decode_demo_info(const void *buf, size_t len, gmmrrt_demo_info_t *out,
                                                char *err, size_t errcap)
{
    DECODE_OR_REJECT(demo_info_t, buf, len, out, err, errcap);
    if (out->task < GMMRRT_NAV_GOAL_T_TASK_NONE || out->task > GMMRRT_NAV_GOAL_T_TASK_APPROACH)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "demo_info_t.task = %d is not a TASK_* value",
                      (int)out->task);
    if (out->homotopy < GMMRRT_DEMO_INFO_T_HOMOTOPY_UNKNOWN || out->homotopy > GMMRRT_DEMO_INFO_T_HOMOTOPY_FRONTAL)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "demo_info_t.homotopy = %d is not a HOMOTOPY_* value",
                      (int)out->homotopy);
    if (out->episode < 0)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "demo_info_t.episode = %d is negative",
                      (int)out->episode);
    return GMMRRT_MSG_OK;
}

gmmrrt_msg_result_t gmmrrt_msg_decode_planar_scan(const void *buf, size_t len, gmmrrt_planar_scan_t *out,
                                                  char *err, size_t errcap)
{
    DECODE_OR_REJECT(planar_scan_t, buf, len, out, err, errcap);
    const gmmrrt_msg_result_t r = check_count("planar_scan_t", "num_ranges", out->num_ranges,
                                              GMMRRT_PLANAR_SCAN_T_MAX_RANGES, err, errcap);
    if (r != GMMRRT_MSG_OK)
        return r;
    REQUIRE_FINITE(planar_scan_t, "rad0", out->rad0, err, errcap);
    REQUIRE_FINITE(planar_scan_t, "radstep", out->radstep, err, errcap);
    if (out->num_ranges > 0 && !isfinite(out->rad0 + (double)(out->num_ranges - 1) * out->radstep))
        return reject(GMMRRT_MSG_NOT_FINITE, err, errcap,
                      "planar_scan_t: the last beam's angle rad0 + %d radstep is not finite", (int)(out->num_ranges - 1));
    REQUIRE_FINITE(planar_scan_t, "range_min_m", out->range_min_m, err, errcap);
    REQUIRE_FINITE(planar_scan_t, "range_max_m", out->range_max_m, err, errcap);
    REQUIRE_FINITE(planar_scan_t, "sensor_x", out->sensor_x, err, errcap);
    REQUIRE_FINITE(planar_scan_t, "sensor_y", out->sensor_y, err, errcap);
    REQUIRE_FINITE(planar_scan_t, "sensor_yaw", out->sensor_yaw, err, errcap);
    if (out->range_min_m < 0.0)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "planar_scan_t.range_min_m = %g must be >= 0",
                      out->range_min_m);
    if (!(out->range_max_m > out->range_min_m))
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap,
                      "planar_scan_t.range_max_m = %g must be > range_min_m = %g", out->range_max_m,
                      out->range_min_m);
    return GMMRRT_MSG_OK;
}

/* A framed type's decoder and release (msg_decode.h): the frame judged on the wire, the type's
 * validate_<name>, and the frame string freed again when the message is refused or released. */
#define FRAMED_DECODER(name)                                                                            \
    gmmrrt_msg_result_t gmmrrt_msg_decode_##name(const void *buf, size_t len, gmmrrt_##name##_t *out, char *err, \
                                                 size_t errcap)                                         \
    {                                                                                                   \
        DECODE_WITH_FRAME_OR_REJECT(name##_t, buf, len, out, err, errcap);                              \
        const gmmrrt_msg_result_t r = validate_##name(out, err, errcap);                                \
        if (r != GMMRRT_MSG_OK)                                                                         \
            gmmrrt_msg_release_##name(out);                                                             \
        return r;                                                                                       \
    }                                                                                                   \
                                                                                                        \
    void gmmrrt_msg_release_##name(gmmrrt_##name##_t *m)                                                \
    {                                                                                                   \
        if (m == NULL)                                                                                  \
            return;                                                                                     \
        free(m->frame);                                                                                 \
        m->frame = NULL;                                                                                \
    }

FRAMED_DECODER(pose2d)
FRAMED_DECODER(people)
FRAMED_DECODER(nav_goal)
FRAMED_DECODER(obstacles)
FRAMED_DECODER(waypoints)

static gmmrrt_msg_result_t validate_occupancy_grid(const gmmrrt_occupancy_grid_t *out, char *err, size_t errcap)
{
    if (out->width < 1 || out->height < 1)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "occupancy_grid_t: width %d and height %d must be >= 1",
                      (int)out->width, (int)out->height);
    if ((int64_t)out->width * (int64_t)out->height > GMMRRT_OCCUPANCY_GRID_T_MAX_CELLS)
        return reject(GMMRRT_MSG_COUNT_OVER_BOUND, err, errcap,
                      "occupancy_grid_t: width %d x height %d is above MAX_CELLS = %d", (int)out->width,
                      (int)out->height, (int)GMMRRT_OCCUPANCY_GRID_T_MAX_CELLS);
    if ((int64_t)out->num_cells != (int64_t)out->width * (int64_t)out->height)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap,
                      "occupancy_grid_t.num_cells = %d, but width %d x height %d = %lld", (int)out->num_cells,
                      (int)out->width, (int)out->height, (long long)((int64_t)out->width * (int64_t)out->height));
    REQUIRE_FINITE(occupancy_grid_t, "resolution_m", out->resolution_m, err, errcap);
    REQUIRE_FINITE(occupancy_grid_t, "origin_x", out->origin_x, err, errcap);
    REQUIRE_FINITE(occupancy_grid_t, "origin_y", out->origin_y, err, errcap);
    REQUIRE_FINITE(occupancy_grid_t, "origin_yaw", out->origin_yaw, err, errcap);
    if (!(out->resolution_m > 0.0))
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "occupancy_grid_t.resolution_m = %g must be > 0",
                      out->resolution_m);
    for (int32_t k = 0; k < out->num_cells; ++k)
        if (out->data[k] < -1 || out->data[k] > 100)
            return reject(GMMRRT_MSG_BAD_VALUE, err, errcap,
                          "occupancy_grid_t.data[%d] = %d (cell %d, %d) is not -1 or 0..100", (int)k,
                          (int)out->data[k], (int)(k % out->width), (int)(k / out->width));
    return GMMRRT_MSG_OK;
}

FRAMED_DECODER(occupancy_grid)
