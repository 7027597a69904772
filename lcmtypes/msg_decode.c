/*
 * msg_decode.c - decode-and-validate for the gmmrrt LCM messages (see msg_decode.h).
 * Validation rules per field are listed in docs/messages.md.
 */
#include "gmmrrt/msg_decode.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "gmmrrt/detail/reason_text.h"
#include "gmmrrt/limits.h"

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
    }
    return "unknown";
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

gmmrrt_msg_result_t gmmrrt_msg_decode_pose2d(const void *buf, size_t len, gmmrrt_pose2d_t *out,
                                             char *err, size_t errcap)
{
    DECODE_OR_REJECT(pose2d_t, buf, len, out, err, errcap);
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

gmmrrt_msg_result_t gmmrrt_msg_decode_people(const void *buf, size_t len, gmmrrt_people_t *out,
                                             char *err, size_t errcap)
{
    DECODE_OR_REJECT(people_t, buf, len, out, err, errcap);
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

gmmrrt_msg_result_t gmmrrt_msg_decode_nav_goal(const void *buf, size_t len, gmmrrt_nav_goal_t *out,
                                               char *err, size_t errcap)
{
    DECODE_OR_REJECT(nav_goal_t, buf, len, out, err, errcap);
    REQUIRE_FINITE(nav_goal_t, "x", out->x, err, errcap);
    REQUIRE_FINITE(nav_goal_t, "y", out->y, err, errcap);
    REQUIRE_FINITE(nav_goal_t, "yaw", out->yaw, err, errcap);
    REQUIRE_FINITE(nav_goal_t, "tolerance_m", out->tolerance_m, err, errcap);
    if (!(out->tolerance_m > 0.0))
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "nav_goal_t.tolerance_m = %g must be > 0",
                      out->tolerance_m);
    if (out->task != GMMRRT_NAV_GOAL_T_TASK_NONE && out->task != GMMRRT_NAV_GOAL_T_TASK_AVOID &&
        out->task != GMMRRT_NAV_GOAL_T_TASK_APPROACH)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "nav_goal_t.task = %d is not a TASK_* value",
                      (int)out->task);
    if (out->task == GMMRRT_NAV_GOAL_T_TASK_APPROACH && out->target_person_id < 0)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap,
                      "nav_goal_t.target_person_id = %d: TASK_APPROACH needs a person id >= 0",
                      (int)out->target_person_id);
    return GMMRRT_MSG_OK;
}

gmmrrt_msg_result_t gmmrrt_msg_decode_obstacles(const void *buf, size_t len, gmmrrt_obstacles_t *out,
                                                char *err, size_t errcap)
{
    DECODE_OR_REJECT(obstacles_t, buf, len, out, err, errcap);
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

gmmrrt_msg_result_t gmmrrt_msg_decode_waypoints(const void *buf, size_t len, gmmrrt_waypoints_t *out,
                                                char *err, size_t errcap)
{
    DECODE_OR_REJECT(waypoints_t, buf, len, out, err, errcap);
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

gmmrrt_msg_result_t gmmrrt_msg_decode_occupancy_grid(const void *buf, size_t len, gmmrrt_occupancy_grid_t *out,
                                                     char *err, size_t errcap)
{
    /* LCM's string decoder mallocs the length the wire claims before it checks that the bytes are
     * there (and leaks it when they are not): the frame's length is judged first. It sits after
     * the fixed part: fingerprint 8, utime 8, resolution and origin 4 x 8, three int32, the cells. */
    enum { k_frame_len_at = 8 + 8 + 4 * 8 + 3 * 4 + GMMRRT_OCCUPANCY_GRID_T_MAX_CELLS };
    if (buf != NULL && decodable_len(len) && len >= (size_t)k_frame_len_at + 4u) {
        const uint8_t *b = (const uint8_t *)buf + k_frame_len_at;
        const int64_t n = (int32_t)((uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3]);
        if (n < 1 || n > (int64_t)(len - (size_t)k_frame_len_at - 4u))
            return reject(GMMRRT_MSG_DECODE_FAILED, err, errcap,
                          "occupancy_grid_t: cannot decode %zu bytes (the frame's length %lld does not fit)", len,
                          (long long)n);
    }
    DECODE_OR_REJECT(occupancy_grid_t, buf, len, out, err, errcap);
    /* The generated decoder allocates the frame string. Only "map" and "" are accepted, so it is
     * freed here and out->frame points to a static copy of the same value: the caller's message
     * owns no memory (a rejected one leaves nothing behind either) and re-encodes to the same bytes. */
    static const char k_map[] = "map", k_none[] = "";
    const int is_map = out->frame != NULL && strcmp(out->frame, k_map) == 0;
    const int frame_ok = is_map || out->frame == NULL || out->frame[0] == '\0';
    char frame[40];
    snprintf(frame, sizeof frame, "%.32s%s", out->frame ? out->frame : "",
             out->frame && strlen(out->frame) > 32 ? "..." : "");
    gmmrrt_occupancy_grid_t_decode_cleanup(out);
    out->frame = (char *)(is_map ? k_map : k_none);
    if (!frame_ok)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap,
                      "occupancy_grid_t.frame = \"%s\": only \"map\" (or \"\", the same) is planned in", frame);
    if (out->width < 1 || out->height < 1)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "occupancy_grid_t: width %d and height %d must be >= 1",
                      (int)out->width, (int)out->height);
    if ((int64_t)out->width * (int64_t)out->height > GMMRRT_OCCUPANCY_GRID_T_MAX_CELLS)
        return reject(GMMRRT_MSG_COUNT_OVER_BOUND, err, errcap,
                      "occupancy_grid_t: width %d x height %d is above MAX_CELLS = %d", (int)out->width,
                      (int)out->height, (int)GMMRRT_OCCUPANCY_GRID_T_MAX_CELLS);
    if ((int64_t)out->num_cells != (int64_t)out->width * (int64_t)out->height)
        return reject(GMMRRT_MSG_BAD_VALUE, err, errcap, "occupancy_grid_t.num_cells = %d, but width %d x height %d = %lld",
                      (int)out->num_cells, (int)out->width, (int)out->height,
                      (long long)((int64_t)out->width * (int64_t)out->height));
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
