/*
 * dispatch.c - the path of one LCM message through gmmrrtd: decode and judge it (inputs.c),
 * run the planning cycles that fall due by its arrival (cycle.c; log mode only, the live loop
 * runs its own ticks in main.c), then apply it. A message thus never changes the inputs of a
 * cycle that was due before it arrived, which keeps replays deterministic (docs/daemon.md,
 * "Clock").
 *
 * Log mode's time base is the log's event time (the recorder's receive time, which no
 * sender sets; file:// logs are read below for it), made non-decreasing. Cycles run at t0 + k / rate_hz,
 * t0 = the first message's event time; a jump of more than k_max_catch_up cycles (a long
 * silence in a log) runs only the last of them.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "daemon.h"

enum { k_max_catch_up = 600 };

/* The log time base at a message received at recv_utime; runs the cycles due by then. */
static int64_t log_time_at(gmmrrtd_t *d, int64_t recv_utime)
{
    if (recv_utime < 0 || recv_utime > GMMRRTD_MAX_UTIME)
        recv_utime = d->have_time ? d->log_now_us : 0; /* a broken event time moves nothing */
    const int64_t period_us = (int64_t)llround(1e6 / d->set.rate_hz);
    if (!d->have_time) {
        d->have_time = 1;
        d->log_now_us = recv_utime;
        d->next_tick_us = recv_utime + period_us;
        return recv_utime;
    }
    if (recv_utime > d->log_now_us)
        d->log_now_us = recv_utime;
    return d->log_now_us;
}

static void run_due_cycles(gmmrrtd_t *d, int64_t local_us)
{
    const int64_t period_us = (int64_t)llround(1e6 / d->set.rate_hz);
    if (local_us - d->next_tick_us > (int64_t)k_max_catch_up * period_us) {
        const int64_t skip = (local_us - d->next_tick_us) / period_us - 1;
        LOG_WARN("log time jumps %.1f s ahead: skipping %lld cycles", (double)(local_us - d->next_tick_us) * 1e-6,
                 (long long)skip);
        d->next_tick_us += skip * period_us;
    }
    while (d->next_tick_us <= local_us) {
        gmmrrtd_cycle(d, d->next_tick_us);
        d->next_tick_us += period_us;
    }
}

void gmmrrtd_handle_message(gmmrrtd_t *d, int input, int64_t recv_utime, const void *buf, size_t len)
{
    if (input < 0 || input >= GMMRRTD_NUM_INPUTS)
        return;
    const int log = d->clock_mode == GMMRRTD_CLOCK_LOG;
    const int64_t local_us = log ? log_time_at(d, recv_utime) : gmmrrtd_mono_us();
    const int staged = gmmrrtd_inputs_decode(d, input, local_us, buf, len);
    if (log)
        run_due_cycles(d, local_us);
    if (staged)
        gmmrrtd_inputs_apply(d);
}

/* The LCM handlers: the message's bytes go to gmmrrtd_handle_message (the channel picks the input). */
#define ON_INPUT(name, input)                                                                       \
    static void on_##name(const lcm_recv_buf_t *rbuf, const char *channel, void *user)             \
    {                                                                                               \
        (void)channel;                                                                              \
        gmmrrtd_handle_message(user, (input), rbuf->recv_utime, rbuf->data, (size_t)rbuf->data_size); \
    }
ON_INPUT(pose, GMMRRTD_IN_POSE)
ON_INPUT(people, GMMRRTD_IN_PEOPLE)
ON_INPUT(goal, GMMRRTD_IN_GOAL)
ON_INPUT(obstacles, GMMRRTD_IN_OBSTACLES)
ON_INPUT(scan, GMMRRTD_IN_SCAN)
ON_INPUT(grid, GMMRRTD_IN_GRID)

int gmmrrtd_subscribe(gmmrrtd_t *d)
{
    const gmmrrtd_settings_t *s = &d->set;
    if (lcm_subscribe(d->lcm_in, s->ch_pose, on_pose, d) == NULL ||
        lcm_subscribe(d->lcm_in, s->ch_people, on_people, d) == NULL ||
        lcm_subscribe(d->lcm_in, s->ch_goal, on_goal, d) == NULL ||
        lcm_subscribe(d->lcm_in, s->ch_obstacles, on_obstacles, d) == NULL ||
        lcm_subscribe(d->lcm_in, s->ch_scan, on_scan, d) == NULL ||
        lcm_subscribe(d->lcm_in, s->ch_grid, on_grid, d) == NULL) {
        LOG_ERROR("cannot subscribe the input channels");
        return -1;
    }
    return 0;
}

/* --- file:// replays ---------------------------------------------------------------------
 * LCM's file provider hands a handler the wall-clock time of the call as recv_utime, not the
 * event's timestamp, so a replay reads the log itself with LCM's eventlog reader: each event's
 * timestamp (the recorder's receive time) is its arrival. Channels match as LCM's
 * subscriptions do: the name is a POSIX extended regular expression anchored at both ends. */

/* The path of a file:// URL, without its ?options. 0, or -1 when it is not one. */
static int url_path(const char *url, char *out, size_t cap)
{
    if (strncmp(url, "file://", 7) != 0)
        return -1;
    const char *p = url + 7, *q = strchr(p, '?');
    const size_t n = q ? (size_t)(q - p) : strlen(p);
    if (n == 0 || n >= cap)
        return -1;
    memcpy(out, p, n);
    out[n] = '\0';
    return 0;
}

int gmmrrtd_replay_open(gmmrrtd_t *d)
{
    char path[GMMRRTD_PATH_MAX];
    if (url_path(d->set.lcm_url, path, sizeof path) != 0) {
        LOG_ERROR("%s: not a file:// URL with a path", d->set.lcm_url);
        return -1;
    }
    const char *names[GMMRRTD_NUM_INPUTS] = {d->set.ch_pose,      d->set.ch_people, d->set.ch_goal,
                                             d->set.ch_obstacles, d->set.ch_scan,   d->set.ch_grid};
    for (int i = 0; i < GMMRRTD_NUM_INPUTS; ++i) {
        char re[128];
        snprintf(re, sizeof re, "^(%s)$", names[i]);
        if (regcomp(&d->replay_re[i], re, REG_EXTENDED | REG_NOSUB) != 0) {
            LOG_ERROR("channel \"%s\" is not a valid regular expression", names[i]);
            for (int j = 0; j < i; ++j)
                regfree(&d->replay_re[j]);
            return -1;
        }
    }
    d->replay = lcm_eventlog_create(path, "r");
    if (d->replay == NULL) {
        LOG_ERROR("cannot open LCM log %s: %s", path, strerror(errno));
        for (int i = 0; i < GMMRRTD_NUM_INPUTS; ++i)
            regfree(&d->replay_re[i]);
        return -1;
    }
    return 0;
}

int gmmrrtd_replay_step(gmmrrtd_t *d)
{
    lcm_eventlog_event_t *ev = lcm_eventlog_read_next_event(d->replay);
    if (ev == NULL)
        return 0;
    /* Every input whose channel pattern matches, as LCM calls every matching subscription. */
    for (int i = 0; i < GMMRRTD_NUM_INPUTS; ++i)
        if (ev->channel != NULL && regexec(&d->replay_re[i], ev->channel, 0, NULL, 0) == 0)
            gmmrrtd_handle_message(d, i, ev->timestamp, ev->data, ev->datalen > 0 ? (size_t)ev->datalen : 0);
    lcm_eventlog_free_event(ev);
    return 1;
}

void gmmrrtd_replay_close(gmmrrtd_t *d)
{
    if (d->replay == NULL)
        return;
    lcm_eventlog_destroy(d->replay);
    d->replay = NULL;
    for (int i = 0; i < GMMRRTD_NUM_INPUTS; ++i)
        regfree(&d->replay_re[i]);
}
