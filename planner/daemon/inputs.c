/*
 * inputs.c - gmmrrtd's inputs: every LCM message is decoded and validated through
 * lcmtypes/include/gmmrrt/msg_decode.h, checked against time (a channel's utime may not go
 * backwards), counted by reason in planner_status_t.rejected when bad, and only then
 * becomes the latest value of its channel. In log-clock mode the cycles due before a
 * message's utime run before it is applied, so a replay is the same every time
 * (docs/daemon.md, "Clock").
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "daemon.h"

int64_t gmmrrtd_mono_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

static const char *const k_input_names[] = {"pose", "people", "goal", "obstacles", "planner"};

void gmmrrtd_reject(gmmrrtd_t *d, int input, int reason, const char *fmt, ...)
{
    d->status.rejected[reason]++;
    char line[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    gmmrrtd_log_limited(&d->rl[input][reason], gmmrrtd_mono_us() / 1000, (int64_t)d->set.log_interval_ms,
                        GMMRRTD_LOG_WARN, "%s rejected (total %lld): %s", k_input_names[input],
                        (long long)d->status.rejected[reason], line);
}

static int reason_of(gmmrrt_msg_result_t r)
{
    switch (r) {
    case GMMRRT_MSG_COUNT_OVER_BOUND: return GMMRRT_PLANNER_STATUS_T_REJECT_COUNT_OVER_BOUND;
    case GMMRRT_MSG_NOT_FINITE: return GMMRRT_PLANNER_STATUS_T_REJECT_NOT_FINITE;
    case GMMRRT_MSG_BAD_VALUE: return GMMRRT_PLANNER_STATUS_T_REJECT_BAD_VALUE;
    default: return GMMRRT_PLANNER_STATUS_T_REJECT_DECODE;
    }
}

/* Advances the planning clock to utime; in log mode first runs every cycle due by then.
 * A jump of more than k_max_catch_up cycles (a long silence in a log) runs only the last. */
static void advance_clock(gmmrrtd_t *d, int64_t utime)
{
    const int64_t period_us = (int64_t)llround(1e6 / d->set.rate_hz);
    if (!d->have_clock) {
        d->have_clock = 1;
        d->clock_utime = utime;
        d->clock_mono_us = gmmrrtd_mono_us();
        d->next_tick_utime = utime + period_us;
        return;
    }
    if (d->clock_mode == GMMRRTD_CLOCK_LOG) {
        enum { k_max_catch_up = 600 };
        if (utime - d->next_tick_utime > (int64_t)k_max_catch_up * period_us) {
            const int64_t skip = (utime - d->next_tick_utime) / period_us - 1;
            LOG_WARN("log clock jumps %.1f s ahead: skipping %lld cycles", (double)(utime - d->clock_utime) * 1e-6,
                     (long long)skip);
            d->next_tick_utime += skip * period_us;
        }
        while (d->next_tick_utime <= utime) {
            gmmrrtd_cycle(d, d->next_tick_utime);
            d->next_tick_utime += period_us;
        }
    }
    if (utime > d->clock_utime) {
        d->clock_utime = utime;
        d->clock_mono_us = gmmrrtd_mono_us();
    }
}

/* Common checks after a successful decode. 1 to apply the message, 0 when rejected. */
static int accept_time(gmmrrtd_t *d, int input, int64_t utime)
{
    if (d->have[input] && utime < d->last_utime[input]) {
        gmmrrtd_reject(d, input, GMMRRT_PLANNER_STATUS_T_REJECT_TIME_BACKWARDS,
                       "utime %lld is %.3f s older than the last accepted one", (long long)utime,
                       (double)(d->last_utime[input] - utime) * 1e-6);
        return 0;
    }
    advance_clock(d, utime);
    d->have[input] = 1;
    d->last_utime[input] = utime;
    return 1;
}

#define DECODE_INPUT(d, input, fn, rbuf, out)                                                       \
    do {                                                                                            \
        char err_[256];                                                                             \
        gmmrrt_msg_result_t r_ = fn((rbuf)->data, (size_t)(rbuf)->data_size, (out), err_, sizeof err_); \
        if (r_ != GMMRRT_MSG_OK) {                                                                  \
            gmmrrtd_reject((d), (input), reason_of(r_), "%s", err_);                                \
            return;                                                                                 \
        }                                                                                           \
    } while (0)

static void on_pose(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    gmmrrtd_t *d = user;
    static gmmrrt_pose2d_t m;
    DECODE_INPUT(d, GMMRRTD_IN_POSE, gmmrrt_msg_decode_pose2d, rbuf, &m);
    if (!accept_time(d, GMMRRTD_IN_POSE, m.utime))
        return;
    d->pose = m;
    d->pose_stale_counted = 0;
}

static void on_people(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    gmmrrtd_t *d = user;
    static gmmrrt_people_t m;
    DECODE_INPUT(d, GMMRRTD_IN_PEOPLE, gmmrrt_msg_decode_people, rbuf, &m);
    if (!accept_time(d, GMMRRTD_IN_PEOPLE, m.utime))
        return;
    d->people = m;
}

static int same_goal(const gmmrrt_nav_goal_t *a, const gmmrrt_nav_goal_t *b)
{
    return a->x == b->x && a->y == b->y && a->tolerance_m == b->tolerance_m && a->task == b->task &&
           a->target_person_id == b->target_person_id;
}

static void on_goal(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    gmmrrtd_t *d = user;
    static gmmrrt_nav_goal_t m;
    DECODE_INPUT(d, GMMRRTD_IN_GOAL, gmmrrt_msg_decode_nav_goal, rbuf, &m);
    const int had_goal = d->have[GMMRRTD_IN_GOAL];
    if (!accept_time(d, GMMRRTD_IN_GOAL, m.utime))
        return;
    if (!had_goal || !same_goal(&m, &d->goal)) {
        d->goal_version++;
        d->no_path_cycles = 0;
        LOG_INFO("new goal (%.2f, %.2f) task %d target %d", m.x, m.y, (int)m.task, (int)m.target_person_id);
    }
    d->goal = m;
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

static void on_obstacles(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    gmmrrtd_t *d = user;
    static gmmrrt_obstacles_t m;
    DECODE_INPUT(d, GMMRRTD_IN_OBSTACLES, gmmrrt_msg_decode_obstacles, rbuf, &m);
    const int had = d->have[GMMRRTD_IN_OBSTACLES];
    if (!accept_time(d, GMMRRTD_IN_OBSTACLES, m.utime))
        return;
    if (!had || !same_obstacles(&m, &d->obstacles))
        d->obstacles_version++;
    d->obstacles = m;
}

int gmmrrtd_inputs_subscribe(gmmrrtd_t *d)
{
    const gmmrrtd_settings_t *s = &d->set;
    if (lcm_subscribe(d->lcm_in, s->ch_pose, on_pose, d) == NULL ||
        lcm_subscribe(d->lcm_in, s->ch_people, on_people, d) == NULL ||
        lcm_subscribe(d->lcm_in, s->ch_goal, on_goal, d) == NULL ||
        lcm_subscribe(d->lcm_in, s->ch_obstacles, on_obstacles, d) == NULL) {
        LOG_ERROR("cannot subscribe the input channels");
        return -1;
    }
    return 0;
}
