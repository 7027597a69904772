/*
 * inputs.c - gmmrrtd's inputs: every LCM message is decoded and validated through
 * lcmtypes/include/gmmrrt/msg_decode.h, then its utime is judged against its own source's
 * clock model (clock.h: bounded offset per source, so no sender can move another source's
 * time or the daemon's), counted by reason in planner_status_t.rejected when bad, and only
 * then staged; gmmrrtd_inputs_apply makes it the latest value of its channel. dispatch.c
 * runs the cycles due in between (docs/daemon.md, "Clock").
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "daemon.h"

static const char *const k_input_names[] = {"pose", "people", "goal", "obstacles", "scan", "grid"};
_Static_assert(sizeof k_input_names / sizeof k_input_names[0] == GMMRRTD_NUM_INPUTS, "a name per input");

static int reason_of(gmmrrt_msg_result_t r)
{
    switch (r) {
    case GMMRRT_MSG_COUNT_OVER_BOUND: return GMMRRT_PLANNER_STATUS_T_REJECT_COUNT_OVER_BOUND;
    case GMMRRT_MSG_NOT_FINITE: return GMMRRT_PLANNER_STATUS_T_REJECT_NOT_FINITE;
    case GMMRRT_MSG_BAD_VALUE: return GMMRRT_PLANNER_STATUS_T_REJECT_BAD_VALUE;
    case GMMRRT_MSG_UNKNOWN_COMMAND: return GMMRRT_PLANNER_STATUS_T_REJECT_UNKNOWN_COMMAND;
    case GMMRRT_MSG_WRONG_FRAME: return GMMRRT_PLANNER_STATUS_T_REJECT_WRONG_FRAME;
    default: return GMMRRT_PLANNER_STATUS_T_REJECT_DECODE;
    }
}

static gmmrrtd_clock_params_t clock_params(const gmmrrtd_settings_t *s)
{
    return (gmmrrtd_clock_params_t){
        .max_off_us = (int64_t)llround(s->max_future_ms * 1e3),
        .resync_count = s->time_resync_count,
        .resync_us = (int64_t)llround(s->time_resync_ms * 1e3),
        .slew_us_per_s = (int64_t)llround(s->clock_slew_ms_per_s * 1e3),
    };
}

/* The time check of a decoded message. 1 to stage it, 0 when rejected (counted). The
 * source's clock model after an accepted message waits in d->staged.clock until it is
 * applied (a cycle due before the message must see the old data time with the old data);
 * a rejection only moves the run counters, which take effect at once. */
static int accept_time(gmmrrtd_t *d, int input, int64_t utime, int64_t local_us)
{
    const gmmrrtd_clock_params_t p = clock_params(&d->set);
    int64_t resid = 0, step = 0;
    gmmrrtd_source_clock_t *c = &d->staged.clock;
    *c = d->src[input];
    const gmmrrtd_stamp_t v = gmmrrtd_clock_judge(c, &p, utime, local_us, &resid, &step);
    if (v == GMMRRTD_STAMP_RANGE || v == GMMRRTD_STAMP_AHEAD || v == GMMRRTD_STAMP_BACKWARDS)
        d->src[input] = *c;
    switch (v) {
    case GMMRRTD_STAMP_OK: return 1;
    case GMMRRTD_STAMP_FIRST:
        if (step != 0)
            gmmrrtd_log_limited(&d->rl[input][GMMRRT_PLANNER_STATUS_T_REJECT_CLOCK_RESYNC], gmmrrtd_mono_us() / 1000,
                                (int64_t)d->set.log_interval_ms, GMMRRTD_LOG_WARN,
                                "%s: its first clock offset was not confirmed; restarted %+.3f s away",
                                k_input_names[input], (double)step * 1e-6);
        return 1;
    case GMMRRTD_STAMP_RESYNC:
        d->status.rejected[GMMRRT_PLANNER_STATUS_T_REJECT_CLOCK_RESYNC]++;
        gmmrrtd_log_limited(&d->rl[input][GMMRRT_PLANNER_STATUS_T_REJECT_CLOCK_RESYNC], gmmrrtd_mono_us() / 1000,
                            (int64_t)d->set.log_interval_ms, GMMRRTD_LOG_WARN,
                            "%s: its clock stepped %+.3f s (%d consecutive messages agree): following it "
                            "(resync %lld; other channels unaffected)",
                            k_input_names[input], (double)step * 1e-6, (int)d->set.time_resync_count,
                            (long long)d->status.rejected[GMMRRT_PLANNER_STATUS_T_REJECT_CLOCK_RESYNC]);
        return 1;
    case GMMRRTD_STAMP_RANGE:
        gmmrrtd_reject(d, input, GMMRRT_PLANNER_STATUS_T_REJECT_BAD_VALUE, "utime %lld is outside 0..2^53 us",
                       (long long)utime);
        return 0;
    case GMMRRTD_STAMP_AHEAD:
        gmmrrtd_reject(d, input, GMMRRT_PLANNER_STATUS_T_REJECT_TIME_FUTURE,
                       "utime %lld is %.3f s ahead of its source's clock (limit %g ms)", (long long)utime,
                       (double)resid * 1e-6, d->set.max_future_ms);
        return 0;
    case GMMRRTD_STAMP_BACKWARDS:
    default:
        gmmrrtd_reject(d, input, GMMRRT_PLANNER_STATUS_T_REJECT_TIME_BACKWARDS,
                       "utime %lld is older than the channel's last (%lld) or %.3f s behind its source's clock "
                       "(limit %g ms)",
                       (long long)utime, (long long)d->src[input].last_utime, (double)-resid * 1e-6,
                       d->set.max_future_ms);
        return 0;
    }
}

/* Decodes through msg_decode.h, then refuses a frame other than [world] frame (msg_decode.h's
 * rule). The frame string is released at once: every kept message is in the planning frame. */
#define DECODE_INPUT(d, input, type, short_name, buf, len, out)                                     \
    do {                                                                                            \
        char err_[256];                                                                             \
        gmmrrt_msg_result_t r_ = gmmrrt_msg_decode_##short_name((buf), (len), (out), err_, sizeof err_); \
        if (r_ == GMMRRT_MSG_OK) {                                                                  \
            r_ = gmmrrt_msg_check_frame(#type, (out)->frame, (d)->set.frame, err_, sizeof err_);     \
            gmmrrt_msg_release_##short_name(out);                                                   \
        }                                                                                           \
        if (r_ != GMMRRT_MSG_OK) {                                                                  \
            gmmrrtd_reject((d), (input), reason_of(r_), "%s", err_);                                \
            return 0;                                                                               \
        }                                                                                           \
    } while (0)

/* A planar_scan_t has no frame of its own: its beams are in the sensor's frame, the sensor is
 * placed on the robot, and the scan in the planning frame through the robot's pose at its stamp
 * (scan.c), a pose already held to [world] frame. */
#define DECODE_UNFRAMED_INPUT(d, input, short_name, buf, len, out)                                  \
    do {                                                                                            \
        char err_[256];                                                                             \
        const gmmrrt_msg_result_t r_ = gmmrrt_msg_decode_##short_name((buf), (len), (out), err_, sizeof err_); \
        if (r_ != GMMRRT_MSG_OK) {                                                                  \
            gmmrrtd_reject((d), (input), reason_of(r_), "%s", err_);                                \
            return 0;                                                                               \
        }                                                                                           \
    } while (0)

/* Walking people are predicted from their velocity (planner.h): a speed above
 * GMMRRT_MAX_PERSON_SPEED_M_S (the core's bound; faster than a running person is a tracking
 * error) refuses the whole list, counted as REJECT_PERSON_SPEED, and the last good list stays.
 * A velocity that is not finite was already refused by the decoder (REJECT_NOT_FINITE). */
static int people_speeds_ok(gmmrrtd_t *d, const gmmrrt_people_t *m)
{
    for (int32_t i = 0; i < m->num_people; ++i) {
        const gmmrrt_person_t *q = &m->people[i];
        const double speed = hypot(q->vx, q->vy);
        if (!(speed <= GMMRRT_MAX_PERSON_SPEED_M_S)) {
            gmmrrtd_reject(d, GMMRRTD_IN_PEOPLE, GMMRRT_PLANNER_STATUS_T_REJECT_PERSON_SPEED,
                           "person id %d moves at %.2f m/s (vx %.2f, vy %.2f), above the %.1f m/s bound",
                           (int)q->id, speed, q->vx, q->vy, GMMRRT_MAX_PERSON_SPEED_M_S);
            return 0;
        }
    }
    return 1;
}

int gmmrrtd_inputs_decode(gmmrrtd_t *d, int input, int64_t local_us, const void *buf, size_t len)
{
    gmmrrtd_staged_t *st = &d->staged;
    st->input = -1;
    int64_t utime;
    switch (input) {
    case GMMRRTD_IN_POSE:
        DECODE_INPUT(d, input, pose2d_t, pose2d, buf, len, &st->m.pose);
        utime = st->m.pose.utime;
        break;
    case GMMRRTD_IN_PEOPLE:
        DECODE_INPUT(d, input, people_t, people, buf, len, &st->m.people);
        if (!people_speeds_ok(d, &st->m.people))
            return 0;
        utime = st->m.people.utime;
        break;
    case GMMRRTD_IN_GOAL:
        DECODE_INPUT(d, input, nav_goal_t, nav_goal, buf, len, &st->m.goal);
        utime = st->m.goal.utime;
        break;
    case GMMRRTD_IN_OBSTACLES:
        DECODE_INPUT(d, input, obstacles_t, obstacles, buf, len, &st->m.obstacles);
        utime = st->m.obstacles.utime;
        break;
    case GMMRRTD_IN_SCAN:
        DECODE_UNFRAMED_INPUT(d, input, planar_scan, buf, len, &st->m.scan);
        utime = st->m.scan.utime;
        break;
    case GMMRRTD_IN_GRID:
        DECODE_INPUT(d, input, occupancy_grid_t, occupancy_grid, buf, len, &st->m.grid);
        if (!gmmrrtd_grid_check(d, &st->m.grid))
            return 0;
        utime = st->m.grid.utime;
        break;
    default: return 0;
    }
    if (!accept_time(d, input, utime, local_us))
        return 0;
    /* A scan is placed with the robot's pose at its stamp (pose ring, scan.c) now, while the
     * poses it needs are known; a scan no pose places is refused. */
    if (input == GMMRRTD_IN_SCAN && !gmmrrtd_scan_place(d, &st->m.scan))
        return 0;
    st->input = input;
    return 1;
}

/* The obstacle content that matters (used entries only), compared to bump the version. */
static int same_obstacles(const gmmrrt_obstacles_t *a, const gmmrrt_obstacles_t *b)
{
    if (a->num_circles != b->num_circles || a->num_boxes != b->num_boxes)
        return 0;
    const size_t nc = (size_t)a->num_circles * sizeof(double), nb = (size_t)a->num_boxes * sizeof(double);
    return !memcmp(a->circle_x, b->circle_x, nc) && !memcmp(a->circle_y, b->circle_y, nc) &&
           !memcmp(a->circle_radius, b->circle_radius, nc) && !memcmp(a->box_x, b->box_x, nb) &&
           !memcmp(a->box_y, b->box_y, nb) && !memcmp(a->box_width, b->box_width, nb) &&
           !memcmp(a->box_height, b->box_height, nb) && !memcmp(a->box_yaw, b->box_yaw, nb);
}

void gmmrrtd_inputs_apply(gmmrrtd_t *d)
{
    gmmrrtd_staged_t *st = &d->staged;
    const int input = st->input;
    if (input < 0 || input >= GMMRRTD_NUM_INPUTS)
        return;
    const int had = d->have[input];
    d->have[input] = 1;
    d->src[input] = st->clock;
    d->stale_counted[input] = 0; /* a new message ends the gap */
    /* What starts an event-triggered cycle (main.c): a new pose or people list, a changed goal or
     * world. A re-sent goal or obstacle list with the same content does not. */
    const int64_t obstacles_version = d->obstacles_version;
    int goal_changed = 0;
    switch (input) {
    case GMMRRTD_IN_POSE:
        d->pose = st->m.pose;
        gmmrrtd_scan_add_pose(d, &st->m.pose);
        break;
    case GMMRRTD_IN_SCAN: gmmrrtd_scan_apply(d); break;
    case GMMRRTD_IN_GRID: gmmrrtd_grid_apply(d); break;
    case GMMRRTD_IN_PEOPLE: d->people = st->m.people; break;
    case GMMRRTD_IN_GOAL:
        /* The goal's life (goal.c): a new id, an update, a cancel; a reused id is refused there. */
        d->have[input] = had;
        goal_changed = gmmrrtd_goal_apply(d, &st->m.goal);
        break;
    case GMMRRTD_IN_OBSTACLES:
        if (!had || !same_obstacles(&st->m.obstacles, &d->obstacles))
            d->obstacles_version++;
        d->obstacles = st->m.obstacles;
        break;
    default: break;
    }
    /* Scans do not start a cycle (they come at the lidar's rate; the next pose does). */
    if (input == GMMRRTD_IN_POSE || input == GMMRRTD_IN_PEOPLE || input == GMMRRTD_IN_GRID || goal_changed ||
        obstacles_version != d->obstacles_version)
        d->event_pending = 1;
    st->input = -1;
}
