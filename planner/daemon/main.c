/*
 * main.c - gmmrrtd's main loop, like Redis's (STYLE.md 10): poll() on the LCM file
 * descriptor with a timeout to the next tick, a fixed cycle rate with a planning budget
 * inside each period, signal handlers that only set flags (SIGINT/SIGTERM: exit cleanly;
 * SIGHUP: reload config and models), systemd readiness and watchdog via sd_notify when
 * built with libsystemd. Two time bases (docs/daemon.md, clock.h): live (ticks on
 * CLOCK_MONOTONIC) and log (ticks on the log's event times, for deterministic file:// replays).
 */
#include <errno.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef GMMRRT_HAVE_SYSTEMD
#include <systemd/sd-daemon.h>
#define NOTIFY(...) sd_notifyf(0, __VA_ARGS__)
#else
#define NOTIFY(...) ((void)0)
#endif

#include "daemon.h"

static volatile sig_atomic_t g_stop;
static volatile sig_atomic_t g_reload;
static gmmrrtd_t g_d; /* the whole daemon; static, allocated once */

static void on_signal(int sig)
{
    if (sig == SIGHUP)
        g_reload = 1;
    else
        g_stop = 1;
}

static int install_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0; /* no SA_RESTART: poll() returns EINTR and the loop sees the flag */
    if (sigaction(SIGINT, &sa, NULL) != 0 || sigaction(SIGTERM, &sa, NULL) != 0 || sigaction(SIGHUP, &sa, NULL) != 0)
        return -1;
    signal(SIGPIPE, SIG_IGN);
    return 0;
}

/* The planner block: sized by the config, allocated once, 64-byte aligned. */
static int planner_setup(gmmrrtd_t *d)
{
    d->mem_size = gmmrrt_planner_mem_size(&d->set.cfg);
    if (d->mem_size == 0) {
        LOG_ERROR("planner configuration gives a zero-sized block");
        return -1;
    }
    const size_t rounded = (d->mem_size + 63u) / 64u * 64u;
    d->mem = aligned_alloc(64, rounded);
    if (d->mem == NULL) {
        LOG_ERROR("cannot allocate the planner block (%zu bytes)", rounded);
        return -1;
    }
    const gmmrrt_status_t st = gmmrrt_planner_init(&d->planner, d->mem, d->mem_size, &d->set.cfg);
    if (st != GMMRRT_OK) {
        LOG_ERROR("planner init: %s", gmmrrt_status_str(st));
        return -1;
    }
    LOG_INFO("planner block %.1f MiB, %d nodes", (double)d->mem_size / (1024.0 * 1024.0), (int)d->set.cfg.max_nodes);
    return 0;
}

static int settings_differ_str(const char *a, const char *b) { return strcmp(a, b) != 0; }

/* SIGHUP: re-read the config file and the command line, then the models. What needs a new
 * memory block or new LCM instances (URLs, channels) waits for a restart; a planner config
 * that fits the block is applied by re-initialising the planner in place. */
static void reload(gmmrrtd_t *d, int argc, char **argv)
{
    NOTIFY("RELOADING=1");
    gmmrrtd_watchdog_long_step(d, 1); /* files are read: bounded by long_step_ms, not by WatchdogSec */
    static gmmrrtd_settings_t s;
    char err[512];
    gmmrrtd_settings_default(&s);
    if (gmmrrtd_settings_from_args(&s, argc, argv, err, sizeof err) != 0 ||
        gmmrrtd_settings_validate(&s, err, sizeof err) != 0) {
        d->status.rejected[GMMRRT_PLANNER_STATUS_T_REJECT_MODEL_RELOAD]++;
        LOG_ERROR("reload rejected (total %lld): %s; keeping the running configuration",
                  (long long)d->status.rejected[GMMRRT_PLANNER_STATUS_T_REJECT_MODEL_RELOAD], err);
        gmmrrtd_watchdog_long_step(d, 0);
        NOTIFY("READY=1");
        return;
    }
    if (settings_differ_str(s.lcm_url, d->set.lcm_url) || settings_differ_str(s.lcm_out_url, d->set.lcm_out_url) ||
        settings_differ_str(s.ch_pose, d->set.ch_pose) || settings_differ_str(s.ch_people, d->set.ch_people) ||
        settings_differ_str(s.ch_goal, d->set.ch_goal) || settings_differ_str(s.ch_obstacles, d->set.ch_obstacles) ||
        settings_differ_str(s.ch_plan, d->set.ch_plan) || settings_differ_str(s.ch_status, d->set.ch_status) ||
        settings_differ_str(s.ch_scan, d->set.ch_scan) || settings_differ_str(s.ch_grid, d->set.ch_grid) ||
        settings_differ_str(s.clock, d->set.clock)) {
        LOG_WARN("reload: LCM URLs, channels and clock apply at the next restart");
        memcpy(s.lcm_url, d->set.lcm_url, sizeof s.lcm_url);
        memcpy(s.lcm_out_url, d->set.lcm_out_url, sizeof s.lcm_out_url);
        memcpy(s.ch_pose, d->set.ch_pose, sizeof s.ch_pose);
        memcpy(s.ch_people, d->set.ch_people, sizeof s.ch_people);
        memcpy(s.ch_goal, d->set.ch_goal, sizeof s.ch_goal);
        memcpy(s.ch_obstacles, d->set.ch_obstacles, sizeof s.ch_obstacles);
        memcpy(s.ch_plan, d->set.ch_plan, sizeof s.ch_plan);
        memcpy(s.ch_status, d->set.ch_status, sizeof s.ch_status);
        memcpy(s.ch_scan, d->set.ch_scan, sizeof s.ch_scan);
        memcpy(s.ch_grid, d->set.ch_grid, sizeof s.ch_grid);
        memcpy(s.clock, d->set.clock, sizeof s.clock);
    }
    const gmmrrt_planner_config_t old_cfg = d->set.cfg;
    if (memcmp(&s.cfg, &d->set.cfg, sizeof s.cfg) != 0) {
        if (gmmrrt_planner_mem_size(&s.cfg) > d->mem_size) {
            LOG_ERROR("reload: the new planner settings need %zu bytes, the block has %zu; keeping the old ones "
                      "(restart to grow it)",
                      gmmrrt_planner_mem_size(&s.cfg), d->mem_size);
            s.cfg = d->set.cfg;
        } else if (gmmrrt_planner_init(&d->planner, d->mem, d->mem_size, &s.cfg) != GMMRRT_OK) {
            LOG_ERROR("reload: planner init refused the new settings; keeping the old ones");
            s.cfg = d->set.cfg;
            (void)gmmrrt_planner_init(&d->planner, d->mem, d->mem_size, &d->set.cfg);
        }
        d->last.valid = 0;
    }
    /* Models: each replaced only when its new file is good and fits the (new) planner. */
    d->set.cfg = s.cfg;
    memcpy(d->set.model_avoid, s.model_avoid, sizeof s.model_avoid);
    memcpy(d->set.model_approach, s.model_approach, sizeof s.model_approach);
    memcpy(d->set.approach_set, s.approach_set, sizeof s.approach_set);
    (void)gmmrrtd_models_load(d, 1);
    /* New planner settings that the models in use do not fit (a new file was refused, so an old
     * model stays: e.g. task_cost = background with files that have no background) would stop
     * every goal of that task; the old settings stay instead, when the models fit them. */
    char why[256], why_old[256];
    if (memcmp(&d->set.cfg, &old_cfg, sizeof old_cfg) != 0 &&
        !gmmrrtd_models_fit_config(d, &d->set.cfg, why, sizeof why) &&
        gmmrrtd_models_fit_config(d, &old_cfg, why_old, sizeof why_old)) {
        d->status.rejected[GMMRRT_PLANNER_STATUS_T_REJECT_MODEL_RELOAD]++;
        LOG_ERROR("reload rejected (total %lld): the new planner settings do not fit the models in use: %s; keeping "
                  "the old planner settings",
                  (long long)d->status.rejected[GMMRRT_PLANNER_STATUS_T_REJECT_MODEL_RELOAD], why);
        s.cfg = old_cfg;
        d->set.cfg = old_cfg;
        (void)gmmrrt_planner_init(&d->planner, d->mem, d->mem_size, &d->set.cfg);
    }
    memcpy(s.model_avoid, d->set.model_avoid, sizeof s.model_avoid);
    memcpy(s.model_approach, d->set.model_approach, sizeof s.model_approach);
    memcpy(s.approach_set, d->set.approach_set, sizeof s.approach_set);
    /* The map: its raster's capacity is fixed at start-up; a new file replaces it only when good. */
    if (s.map_max_cells != d->set.map_max_cells || s.map_max_side != d->set.map_max_side) {
        LOG_WARN("reload: map_max_cells and map_max_side apply at the next restart");
        s.map_max_cells = d->set.map_max_cells;
        s.map_max_side = d->set.map_max_side;
    }
    memcpy(d->set.map, s.map, sizeof s.map);
    d->set.map_unknown_blocked = s.map_unknown_blocked;
    (void)gmmrrtd_world_load(d, 1);
    d->set = s;
    gmmrrtd_log_level_t lvl;
    if (gmmrrtd_log_level_parse(d->set.log_level, &lvl) == 0)
        gmmrrtd_log_set_level(lvl);
    d->last.valid = 0;
    LOG_INFO("reloaded");
    gmmrrtd_watchdog_long_step(d, 0);
    NOTIFY("READY=1");
}

/* A file:// input: events in order, each at its recorded time; cycles run from dispatch.c. */
static int run_replay(gmmrrtd_t *d, int argc, char **argv)
{
    int eof = 0;
    int64_t events = 0;
    while (!g_stop) {
        if (g_reload) {
            g_reload = 0;
            reload(d, argc, argv);
        }
        if (eof) {
            if (d->set.exit_at_eof)
                break;
            (void)poll(NULL, 0, 500);
            gmmrrtd_watchdog_ping(d);
            continue;
        }
        if (!gmmrrtd_replay_step(d)) {
            LOG_INFO("end of input log after %lld cycles, %lld plans", (long long)d->cycles,
                     (long long)d->status.plans_published);
            eof = 1;
        }
        if ((++events & 255) == 0)
            gmmrrtd_watchdog_ping(d);
    }
    return 0;
}

static int run(gmmrrtd_t *d, int argc, char **argv)
{
    if (d->replay != NULL)
        return run_replay(d, argc, argv);
    const int fd = lcm_get_fileno(d->lcm_in);
    int64_t period_us = (int64_t)llround(1e6 / d->set.rate_hz);
    int64_t next_tick = gmmrrtd_mono_us() + period_us;
    int eof = 0;
    while (!g_stop) {
        if (g_reload) {
            g_reload = 0;
            reload(d, argc, argv);
            period_us = (int64_t)llround(1e6 / d->set.rate_hz);
        }
        int timeout_ms;
        int64_t now = gmmrrtd_mono_us();
        if (d->clock_mode == GMMRRTD_CLOCK_LIVE) {
            /* trigger = event: new input starts a cycle at once, at most event_burst back to back and
             * one per min_period_ms on average (pacing.h); the ticks stay as the fallback
             * (staleness, status) and restart a period after it. */
            const int event = d->event_pending && !strcmp(d->set.trigger, "event");
            const int64_t earliest =
                gmmrrtd_pacing_earliest_us(&d->pacing, gmmrrtd_min_period_us(d), d->set.event_burst);
            if (event && now >= earliest && now < next_tick) {
                gmmrrtd_cycle(d, now);
                gmmrrtd_watchdog_ping(d);
                const int64_t done = gmmrrtd_mono_us();
                if (done > now + period_us)
                    d->status.missed_deadlines++;
                next_tick = done + period_us;
                now = done;
            } else if (now >= next_tick) {
                const int64_t tick = next_tick;
                gmmrrtd_cycle(d, now);
                gmmrrtd_watchdog_ping(d);
                const int64_t done = gmmrrtd_mono_us();
                if (done > tick + period_us) {
                    d->status.missed_deadlines++;
                    LOG_DEBUG("cycle overran its period by %.1f ms", (double)(done - tick - period_us) * 1e-3);
                }
                next_tick = tick + period_us;
                if (next_tick <= done) /* skip the ticks we can no longer make */
                    next_tick = done + period_us - (done - next_tick) % period_us;
                now = done;
            }
            int64_t wake = next_tick;
            if (d->event_pending && !strcmp(d->set.trigger, "event")) {
                const int64_t earliest_next =
                    gmmrrtd_pacing_earliest_us(&d->pacing, gmmrrtd_min_period_us(d), d->set.event_burst);
                if (earliest_next < wake)
                    wake = earliest_next > now ? earliest_next : now;
            }
            timeout_ms = (int)((wake - now + 999) / 1000);
        } else {
            timeout_ms = 500; /* log clock: cycles run from the input handlers */
            gmmrrtd_watchdog_ping(d);
        }
        if (eof) {
            if (d->set.exit_at_eof)
                break;
            (void)poll(NULL, 0, timeout_ms);
            continue;
        }
        struct pollfd pfd = {.fd = fd, .events = POLLIN};
        const int n = poll(&pfd, 1, timeout_ms);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            LOG_ERROR("poll: %s", strerror(errno));
            return -1;
        }
        if (n > 0 && (pfd.revents & POLLIN)) {
            if (lcm_handle(d->lcm_in) != 0) {
                if (strncmp(d->set.lcm_url, "file://", 7) == 0) {
                    LOG_INFO("end of input log after %lld cycles, %lld plans", (long long)d->cycles,
                             (long long)d->status.plans_published);
                    eof = 1;
                } else {
                    gmmrrtd_log_limited(&d->rl[GMMRRTD_RL_PLANNER][0], gmmrrtd_mono_us() / 1000,
                                        (int64_t)d->set.log_interval_ms, GMMRRTD_LOG_ERROR, "lcm_handle failed");
                }
            }
        }
    }
    return 0;
}

/* The exit line's counters, by name (every non-zero one). */
static void summarize(const gmmrrtd_t *d, char *rej, size_t rcap, char *stp, size_t scap)
{
    static const char *const k_rej[GMMRRT_PLANNER_STATUS_T_NUM_REJECT_REASONS] = {
        "decode", "count", "not_finite", "backwards", "goal_coll", "unreachable", "pose_stale", "bad_value",
        "unknown_target", "start_coll", "model_reload", "time_future", "clock_resync", "people_stale",
        "obstacles_stale", "planning_box", "scan_stale", "grid_stale", "setup", "no_model", "person_speed"};
    static const char *const k_stop[GMMRRT_PLANNER_STATUS_T_NUM_STOP_REASONS] = {
        "pose_stale", "no_model", "unknown_target", "obstacles_stale", "start_blocked", "goal_blocked", "no_path",
        "planning_box", "setup", "scan_stale", "grid_stale", "frozen"};
    size_t off = 0;
    rej[0] = stp[0] = '\0';
    for (int i = 0; i < GMMRRT_PLANNER_STATUS_T_NUM_REJECT_REASONS && off < rcap; ++i)
        if (k_rej[i] != NULL)
            off += (size_t)snprintf(rej + off, rcap - off, " %s=%lld", k_rej[i], (long long)d->status.rejected[i]);
    off = 0;
    for (int i = 0; i < GMMRRT_PLANNER_STATUS_T_NUM_STOP_REASONS && off < scap; ++i)
        if (k_stop[i] != NULL)
            off += (size_t)snprintf(stp + off, scap - off, " %s=%lld", k_stop[i], (long long)d->status.stops[i]);
}

int main(int argc, char **argv)
{
    gmmrrtd_t *d = &g_d;
    char err[512];
    gmmrrtd_settings_default(&d->set);
    const int rc = gmmrrtd_settings_from_args(&d->set, argc, argv, err, sizeof err);
    if (rc > 0)
        return 0;
    if (rc < 0 || gmmrrtd_settings_validate(&d->set, err, sizeof err) != 0) {
        fprintf(stderr, "gmmrrtd: error: %s\n", err);
        return 2;
    }
    gmmrrtd_log_level_t lvl = GMMRRTD_LOG_INFO;
    (void)gmmrrtd_log_level_parse(d->set.log_level, &lvl);
    gmmrrtd_log_set_level(lvl);
    d->clock_mode = gmmrrtd_settings_clock(&d->set);
    d->status.first_solution_ms = -1.0;
    d->status.best_cost = -1.0;

    if (install_signals() != 0) {
        LOG_ERROR("cannot install signal handlers: %s", strerror(errno));
        return 1;
    }
    if (gmmrrtd_models_load(d, 0) != 0)
        return 1;
    if (gmmrrtd_world_load(d, 0) != 0)
        return 1;
    if (gmmrrtd_grid_setup(d) != 0)
        return 1;
    if (planner_setup(d) != 0)
        return 1;
#ifdef GMMRRT_HAVE_SYSTEMD
    uint64_t wd_usec = 0;
    if (sd_watchdog_enabled(0, &wd_usec) > 0)
        d->watchdog_usec = (int64_t)wd_usec;
#endif
    d->staged.input = -1;
    const int file_input = strncmp(d->set.lcm_url, "file://", 7) == 0;
    if (file_input) {
        if (gmmrrtd_replay_open(d) != 0)
            return 1;
    } else {
        d->lcm_in = lcm_create(d->set.lcm_url);
        if (d->lcm_in == NULL) {
            LOG_ERROR("cannot open LCM input %s", d->set.lcm_url);
            return 1;
        }
    }
    d->lcm_out = d->lcm_in;
    if (d->set.lcm_out_url[0] != '\0') {
        d->lcm_out = lcm_create(d->set.lcm_out_url);
        if (d->lcm_out == NULL) {
            LOG_ERROR("cannot open LCM output %s", d->set.lcm_out_url);
            if (d->lcm_in != NULL)
                lcm_destroy(d->lcm_in);
            gmmrrtd_replay_close(d);
            return 1;
        }
    }
    if (!file_input && gmmrrtd_subscribe(d) != 0)
        return 1;
    LOG_INFO("running: %s clock, %.1f Hz, budget %g ms / %lld iterations, in %s%s%s",
             d->clock_mode == GMMRRTD_CLOCK_LOG ? "log" : "live", d->set.rate_hz, d->set.budget_ms,
             (long long)d->set.budget_iterations, d->set.lcm_url, d->set.lcm_out_url[0] ? ", out " : "",
             d->set.lcm_out_url);
    NOTIFY("READY=1\nSTATUS=planning at %.1f Hz", d->set.rate_hz);

    const int result = run(d, argc, argv);

    NOTIFY("STOPPING=1");
    char summary[1024], stops[512];
    summarize(d, summary, sizeof summary, stops, sizeof stops);
    LOG_INFO("exiting: %lld cycles, %lld plans, %lld warm starts, %lld missed deadlines, %lld escapes; rejected:%s; "
             "stops:%s",
             (long long)d->cycles, (long long)d->status.plans_published, (long long)d->warm_starts,
             (long long)d->status.missed_deadlines, (long long)d->status.escapes, summary, stops);
    LOG_INFO("clearance grid: %lld built, %lld shifted, %lld kept", (long long)d->grid_updates[GMMRRT_GRID_BUILT],
             (long long)d->grid_updates[GMMRRT_GRID_SHIFTED], (long long)d->grid_updates[GMMRRT_GRID_KEPT]);
    LOG_INFO("scans: %lld integrated (%lld cells marked, %lld cleared; %lld without a return), %lld dropped in "
             "floods; grids: %lld accepted",
             (long long)d->scans_applied, (long long)d->scan_cells_marked, (long long)d->scan_cells_cleared,
             (long long)d->scans_blind, (long long)d->scans_dropped, (long long)d->grid_version);
    if (d->lcm_out != d->lcm_in)
        lcm_destroy(d->lcm_out);
    if (d->lcm_in != NULL)
        lcm_destroy(d->lcm_in);
    gmmrrtd_replay_close(d);
    free(d->mem);
    free(d->map_mem);
    free(d->grid_mem);
    return result == 0 ? 0 : 1;
}
