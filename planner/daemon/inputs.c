/*
 * inputs.c - gmmrrtd's inputs: every LCM message is decoded and validated through
 * lcmtypes/include/gmmrrt/msg_decode.h, checked against time (a channel's utime may not go
 * backwards, nor run more than max_future_ms ahead of the clock; a channel that keeps
 * disagreeing in one direction resynchronises the clock), counted by reason in planner_status_t.rejected when bad, and only then
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

/* The clock's idea of "now" when a message arrives: the live clock runs on the monotonic
 * clock since the newest accepted utime; the log clock stands at it. */
static int64_t expected_now_utime(const gmmrrtd_t *d)
{
    if (d->clock_mode == GMMRRTD_CLOCK_LIVE)
        return d->clock_utime + (gmmrrtd_mono_us() - d->clock_mono_us);
    return d->clock_utime;
}

/* Adopts utime as the clock (a stepped clock, docs/daemon.md "Clock steps"): the clock and
 * the log ticks restart there, and every channel's order restarts (their older utimes
 * belong to the old time line). The data already held is kept; a pose from the old time line
 * is judged by its age on the new clock like any other. */
static void resync_clock(gmmrrtd_t *d, int input, int64_t utime, int dir)
{
    const int64_t period_us = (int64_t)llround(1e6 / d->set.rate_hz);
    const int64_t step_us = utime - (dir > 0 ? expected_now_utime(d) : d->last_utime[input]);
    d->status.rejected[GMMRRT_PLANNER_STATUS_T_REJECT_CLOCK_RESYNC]++;
    gmmrrtd_log_limited(&d->rl[input][GMMRRT_PLANNER_STATUS_T_REJECT_CLOCK_RESYNC], gmmrrtd_mono_us() / 1000,
                        (int64_t)d->set.log_interval_ms, GMMRRTD_LOG_WARN,
                        "%s: %d consecutive messages %s the clock: adopting its time (step %+.3f s; resync %lld)",
                        k_input_names[input], (int)d->time_off_run[input], dir > 0 ? "ahead of" : "behind",
                        (double)step_us * 1e-6,
                        (long long)d->status.rejected[GMMRRT_PLANNER_STATUS_T_REJECT_CLOCK_RESYNC]);
    d->clock_utime = utime;
    d->clock_mono_us = gmmrrtd_mono_us();
    d->next_tick_utime = utime + period_us;
    for (int i = 0; i < GMMRRTD_NUM_INPUTS; ++i) {
        if (d->have[i] && d->last_utime[i] > utime)
            d->last_utime[i] = utime;
        d->time_off_dir[i] = 0;
        d->time_off_run[i] = 0;
    }
}

/* One more message of `input` off the clock in direction dir (+1 future, -1 backwards).
 * 1 when the run has reached time_resync_count (the clock was resynchronised to utime),
 * 0 when the message is to be rejected. */
static int off_clock(gmmrrtd_t *d, int input, int64_t utime, int dir)
{
    if (d->time_off_dir[input] != dir) {
        d->time_off_dir[input] = dir;
        d->time_off_run[input] = 0;
    }
    d->time_off_run[input]++;
    if (d->time_off_run[input] < d->set.time_resync_count)
        return 0;
    resync_clock(d, input, utime, dir);
    return 1;
}

/* Common checks after a successful decode. 1 to apply the message, 0 when rejected. */
static int accept_time(gmmrrtd_t *d, int input, int64_t utime)
{
    /* utime in 0..2^53 us (up to the year 2255): differences of accepted utimes and the clock
     * arithmetic below then cannot overflow int64 (found by tests/fuzz/fuzz_daemon_inputs). */
    if (utime < 0 || utime > GMMRRTD_MAX_UTIME) {
        gmmrrtd_reject(d, input, GMMRRT_PLANNER_STATUS_T_REJECT_BAD_VALUE, "utime %lld is outside 0..2^53 us",
                       (long long)utime);
        return 0;
    }
    int resynced = 0;
    if (d->have_clock) {
        /* Bounded future: one message stamped far ahead must not drag the clock (and with it
         * every later message of its channel into "backwards") along. */
        const double max_ms = d->clock_mode == GMMRRTD_CLOCK_LIVE ? d->set.max_future_ms : d->set.log_max_future_ms;
        const int64_t ahead_us = utime - expected_now_utime(d);
        if ((double)ahead_us > max_ms * 1e3) {
            resynced = off_clock(d, input, utime, +1);
            if (!resynced) {
                gmmrrtd_reject(d, input, GMMRRT_PLANNER_STATUS_T_REJECT_TIME_FUTURE,
                               "utime %lld is %.3f s ahead of the clock (limit %g ms)", (long long)utime,
                               (double)ahead_us * 1e-6, max_ms);
                return 0;
            }
        }
    }
    if (!resynced && d->have[input] && utime < d->last_utime[input]) {
        resynced = off_clock(d, input, utime, -1);
        if (!resynced) {
            gmmrrtd_reject(d, input, GMMRRT_PLANNER_STATUS_T_REJECT_TIME_BACKWARDS,
                           "utime %lld is %.3f s older than the last accepted one", (long long)utime,
                           (double)(d->last_utime[input] - utime) * 1e-6);
            return 0;
        }
    }
    if (!resynced) {
        d->time_off_dir[input] = 0;
        d->time_off_run[input] = 0;
        advance_clock(d, utime);
    }
    d->have[input] = 1;
    d->last_utime[input] = utime;
    return 1;
}

#define DECODE_INPUT(d, input, fn, buf, len, out)                                                   \
    do {                                                                                            \
        char err_[256];                                                                             \
        gmmrrt_msg_result_t r_ = fn((buf), (len), (out), err_, sizeof err_);                        \
        if (r_ != GMMRRT_MSG_OK) {                                                                  \
            gmmrrtd_reject((d), (input), reason_of(r_), "%s", err_);                                \
            return;                                                                                 \
        }                                                                                           \
    } while (0)

static void handle_pose(gmmrrtd_t *d, const void *buf, size_t len)
{
    static gmmrrt_pose2d_t m;
    DECODE_INPUT(d, GMMRRTD_IN_POSE, gmmrrt_msg_decode_pose2d, buf, len, &m);
    if (!accept_time(d, GMMRRTD_IN_POSE, m.utime))
        return;
    d->pose = m;
    d->pose_stale_counted = 0;
}

static void handle_people(gmmrrtd_t *d, const void *buf, size_t len)
{
    static gmmrrt_people_t m;
    DECODE_INPUT(d, GMMRRTD_IN_PEOPLE, gmmrrt_msg_decode_people, buf, len, &m);
    if (!accept_time(d, GMMRRTD_IN_PEOPLE, m.utime))
        return;
    d->people = m;
}

static int same_goal(const gmmrrt_nav_goal_t *a, const gmmrrt_nav_goal_t *b)
{
    return a->x == b->x && a->y == b->y && a->tolerance_m == b->tolerance_m && a->task == b->task &&
           a->target_person_id == b->target_person_id;
}

static void handle_goal(gmmrrtd_t *d, const void *buf, size_t len)
{
    static gmmrrt_nav_goal_t m;
    DECODE_INPUT(d, GMMRRTD_IN_GOAL, gmmrrt_msg_decode_nav_goal, buf, len, &m);
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

static void handle_obstacles(gmmrrtd_t *d, const void *buf, size_t len)
{
    static gmmrrt_obstacles_t m;
    DECODE_INPUT(d, GMMRRTD_IN_OBSTACLES, gmmrrt_msg_decode_obstacles, buf, len, &m);
    const int had = d->have[GMMRRTD_IN_OBSTACLES];
    if (!accept_time(d, GMMRRTD_IN_OBSTACLES, m.utime))
        return;
    if (!had || !same_obstacles(&m, &d->obstacles))
        d->obstacles_version++;
    d->obstacles = m;
}

void gmmrrtd_inputs_handle(gmmrrtd_t *d, int input, const void *buf, size_t len)
{
    switch (input) {
    case GMMRRTD_IN_POSE: handle_pose(d, buf, len); break;
    case GMMRRTD_IN_PEOPLE: handle_people(d, buf, len); break;
    case GMMRRTD_IN_GOAL: handle_goal(d, buf, len); break;
    case GMMRRTD_IN_OBSTACLES: handle_obstacles(d, buf, len); break;
    default: break;
    }
}

/* The LCM handlers: the message's bytes go to gmmrrtd_inputs_handle (the channel picks the input). */
#define ON_INPUT(name, input)                                                                       \
    static void on_##name(const lcm_recv_buf_t *rbuf, const char *channel, void *user)             \
    {                                                                                               \
        (void)channel;                                                                              \
        gmmrrtd_inputs_handle(user, (input), rbuf->data, (size_t)rbuf->data_size);                  \
    }
ON_INPUT(pose, GMMRRTD_IN_POSE)
ON_INPUT(people, GMMRRTD_IN_PEOPLE)
ON_INPUT(goal, GMMRRTD_IN_GOAL)
ON_INPUT(obstacles, GMMRRTD_IN_OBSTACLES)

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
