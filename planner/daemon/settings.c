/*
 * settings.c - gmmrrtd's settings: defaults, INI file (inih) and getopt_long command line
 * from one key table (see settings.h; reference in docs/daemon.md). The [planner] section is
 * the core's settings table (gmmrrt/config_keys.h), the one gmmrrt-plan reads too.
 */
#include "settings.h"

#include <errno.h>
#include <fcntl.h>
#include <getopt.h>
#include <ini.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "gmmrrt/config_keys.h"
#include "gmmrrt/drivable.h"
#include "gmmrrt/problem_bounds.h"
#include "gmmrrt/planner.h"
#include "gmmrrt/msg_decode.h"
#include "log.h"

#ifndef GMMRRT_VERSION_STRING
#define GMMRRT_VERSION_STRING "unknown"
#endif

typedef enum { K_STR, K_F64, K_I32, K_I64, K_BOOL } key_type_t;

typedef struct {
    const char *section, *key; /* INI [section] key */
    const char *flag;          /* --flag (long option name) */
    key_type_t type;
    size_t offset, size;       /* into gmmrrtd_settings_t; size for K_STR */
    double min, max;           /* numeric range, inclusive */
    const char *help;
} key_t_;

#define OFF(f) offsetof(gmmrrtd_settings_t, f)
#define STR(sec, k, fl, f, h) {sec, k, fl, K_STR, OFF(f), sizeof(((gmmrrtd_settings_t *)0)->f), 0, 0, h}
#define NUM(sec, k, fl, ty, f, lo, hi, h) {sec, k, fl, ty, OFF(f), 0, lo, hi, h}

static const key_t_ k_keys[] = {
    STR("lcm", "url", "lcm-url", lcm_url, "LCM URL to subscribe (and publish) on"),
    STR("lcm", "out_url", "lcm-out-url", lcm_out_url, "separate LCM URL to publish on (e.g. file://out.lcmlog?mode=w)"),
    NUM("lcm", "exit_at_eof", "exit-at-eof", K_BOOL, exit_at_eof, 0, 1, "exit when a file:// input ends (flag: no value)"),
    STR("lcm", "clock", "clock", clock, "auto | live | log: planning clock (docs/daemon.md)"),
    STR("channels", "pose", "channel-pose", ch_pose, "robot pose channel (pose2d_t)"),
    STR("channels", "people", "channel-people", ch_people, "people channel (people_t)"),
    STR("channels", "goal", "channel-goal", ch_goal, "goal channel (nav_goal_t)"),
    STR("channels", "obstacles", "channel-obstacles", ch_obstacles, "obstacles channel (obstacles_t)"),
    STR("channels", "scan", "channel-scan", ch_scan, "laser scan channel (planar_scan_t; docs/world.md)"),
    STR("channels", "grid", "channel-grid", ch_grid, "local occupancy grid channel (occupancy_grid_t; replaces the map)"),
    STR("channels", "plan", "channel-plan", ch_plan, "plan output channel (waypoints_t)"),
    STR("channels", "status", "channel-status", ch_status, "status output channel (planner_status_t)"),
    STR("models", "avoid", "model-avoid", model_avoid, "model file for TASK_AVOID"),
    STR("models", "approach", "model-approach", model_approach, "model file for TASK_APPROACH"),
    STR("models", "approach_set", "approach-models", approach_set,
        "directory of the 8 approach direction models <dir>/1-front.gmm ... 8-45_left.gmm (excludes approach)"),
    NUM("timing", "rate_hz", "rate-hz", K_F64, rate_hz, 0.1, 1000, "planning cycles per second"),
    NUM("timing", "budget_ms", "budget-ms", K_F64, budget_ms, 0, 1e6, "planning time per cycle, ms (0: none)"),
    STR("timing", "trigger", "trigger", trigger, "tick | event: cycles at rate_hz only, or also on new input (live)"),
    NUM("timing", "min_period_ms", "min-period-ms", K_F64, min_period_ms, 0, 1e6,
        "event trigger: one cycle start per this long on average, ms"),
    NUM("timing", "event_burst", "event-burst", K_I32, event_burst, 1, 64,
        "event trigger: cycle starts allowed back to back (1: min_period_ms after every start)"),
    NUM("timing", "anytime_max_plans", "anytime-max-plans", K_I32, anytime_max_plans, 1, 64,
        "plans published per cycle at most (the first at once, then better ones)"),
    NUM("timing", "anytime_improvement", "anytime-improvement", K_F64, anytime_improvement, 0, 0.99,
        "a further plan of a cycle only when its cost fell by this fraction"),
    NUM("timing", "budget_iterations", "budget-iterations", K_I64, budget_iterations, 0, 1e12,
        "samples per cycle (0: none); deterministic replays"),
    NUM("timing", "pose_timeout_ms", "pose-timeout-ms", K_F64, pose_timeout_ms, 1, 1e7, "stop when the pose is older, ms"),
    NUM("timing", "unreachable_after_cycles", "unreachable-after", K_I32, unreachable_after_cycles, 1, 1e6,
        "cycles without a path before a goal counts as unreachable"),
    NUM("timing", "goal_fail_after_ms", "goal-fail-after-ms", K_F64, goal_fail_after_ms, 0, 1e9,
        "a goal that could not be planned for this long fails (no path, blocked, no model or target), ms"),
    NUM("timing", "people_timeout_ms", "people-timeout-ms", K_F64, people_timeout_ms, 0, 1e7,
        "drop the people list when older, ms (0: never)"),
    NUM("timing", "obstacles_timeout_ms", "obstacles-timeout-ms", K_F64, obstacles_timeout_ms, 0, 1e7,
        "stop when the obstacle list is older, ms (0: never; static obstacles)"),
    NUM("timing", "scan_timeout_ms", "scan-timeout-ms", K_F64, scan_timeout_ms, 0, 1e7,
        "scans seen and none newer, ms: STALE_SCAN (stop, or forget their marks: scan_stale_stop) (0: never)"),
    NUM("timing", "grid_timeout_ms", "grid-timeout-ms", K_F64, grid_timeout_ms, 0, 1e7,
        "a grid in use and none newer, ms: STALE_GRID, stop (0: never)"),
    NUM("timing", "max_future_ms", "max-future-ms", K_F64, max_future_ms, 1, 1e9,
        "reject a message stamped further than this from its own source's clock, ms"),
    NUM("timing", "time_resync_count", "time-resync-count", K_I32, time_resync_count, 1, 1e6,
        "consecutive consistent off-clock messages of a source before its clock offset steps"),
    NUM("timing", "time_resync_ms", "time-resync-ms", K_F64, time_resync_ms, 0, 1e7,
        "...and the local time such a run must span, ms"),
    NUM("timing", "clock_slew_ms_per_s", "clock-slew", K_F64, clock_slew_ms_per_s, 0, 500,
        "how fast a source's clock offset may follow its messages, ms per s"),
    NUM("timing", "long_step_ms", "long-step-ms", K_F64, long_step_ms, 100, 1e7,
        "watchdog interval granted around a step that may take long (world set-up, reload), ms"),
    STR("world", "frame", "frame", frame, "planning frame: inputs whose frame differs are refused"),
    NUM("world", "bounds_margin_m", "bounds-margin", K_F64, bounds_margin_m, GMMRRT_MIN_BOUNDS_MARGIN_M,
        GMMRRT_MAX_BOUNDS_MARGIN_M, "planning bounds margin, m (problem_bounds.h)"),
    STR("world", "map", "map", map, "static map, map_server YAML + PGM/PNG (docs/world.md); reloaded on SIGHUP"),
    NUM("world", "map_max_cells", "map-max-cells", K_I32, map_max_cells, 1, GMMRRT_MAX_RASTER_CELLS,
        "map raster capacity, cells (memory: 9 bytes a cell, allocated at start-up when a map is set)"),
    NUM("world", "map_max_side", "map-max-side", K_I32, map_max_side, 1, GMMRRT_MAX_RASTER_SIDE,
        "map raster capacity, cells a side"),
    NUM("world", "map_unknown_blocked", "map-unknown-blocked", K_I32, map_unknown_blocked, 0, 1,
        "1: unknown map (and grid) cells and everything outside block; 0: they are free"),
    NUM("world", "scan_decay_ms", "scan-decay-ms", K_F64, scan_decay_ms, 0, 1e7,
        "a scan's obstacle mark blocks this long unless a later beam clears it, ms"),
    NUM("world", "scan_pose_gap_ms", "scan-pose-gap-ms", K_F64, scan_pose_gap_ms, 0, 1e4,
        "a scan stamped after the newest pose by at most this is placed at it; later ones are refused, ms"),
    NUM("world", "scan_max_per_cycle", "scan-max-per-cycle", K_I32, scan_max_per_cycle, 1, 1000,
        "scans integrated between two cycles at most (a flood's rest is dropped and counted)"),
    NUM("world", "scan_stale_stop", "scan-stale-stop", K_I32, scan_stale_stop, 0, 1,
        "1: stale scans stop the robot; 0: plan without their marks (map only)"),
    NUM("world", "scan_reach_m", "scan-reach", K_F64, scan_reach_m, 0.05, 100,
        "with scan marks, the field is computed each cycle over the bounds from blocked cells this near, m"),
    NUM("world", "grid_occupied", "grid-occupied", K_I32, grid_occupied, 1, 100,
        "occupancy_grid_t cells at or above this value block (0..100)"),
    NUM("warm_start", "goal_shift_m", "warm-goal-shift", K_F64, warm_goal_shift_m, 0, 1e4, "warm start: goal moved less, m"),
    NUM("warm_start", "people_shift_m", "warm-people-shift", K_F64, warm_people_shift_m, 0, 1e4,
        "warm start: each person moved less, m"),
    NUM("warm_start", "robot_offset_m", "warm-robot-offset", K_F64, warm_robot_offset_m, 0, 1e4,
        "warm start: robot within this of the last path, m"),
    NUM("people", "nominal_speed_m_s", "nominal-speed", K_F64, nominal_speed_m_s, 0.01, 10,
        "robot speed that times the path against walking people, m/s"),
    NUM("people", "prediction_horizon_s", "prediction-horizon", K_F64, prediction_horizon_s, 0.01, 60,
        "how far walking people are predicted at constant velocity, s"),
    NUM("drive", "min_turn_radius_m", "min-turn-radius", K_F64, min_turn_radius_m, 0, 100,
        "smallest turning radius of the published path, m (0: turning in place)"),
    NUM("drive", "use_goal_yaw", "use-goal-yaw", K_BOOL, use_goal_yaw, 0, 1,
        "arrive on nav_goal_t.yaw (flag: no value)"),
    NUM("drive", "face_target", "face-target", K_BOOL, face_target, 0, 1,
        "approach arrives facing the target person"),
    NUM("drive", "yaw_tolerance_deg", "goal-yaw-tolerance", K_F64, yaw_tolerance_deg, 0.01, 180,
        "arrival heading tolerance, degrees"),
    NUM("drive", "arrival_leg_m", "arrival-leg", K_F64, arrival_leg_m, 0.001, 100,
        "shortest straight final leg on the arrival heading, m"),
    /* [planner]: every key of the core's settings table (gmmrrt/config_keys.h), not listed here. */
    STR("log", "level", "log-level", log_level, "error | warn | info | debug"),
    NUM("log", "interval_ms", "log-interval-ms", K_F64, log_interval_ms, 0, 1e9, "one line per reason per interval, ms"),
};
#define N_KEYS ((int)(sizeof k_keys / sizeof k_keys[0]))

/* The [planner] section, where the core's table has the keys. */
#define PLANNER_SECTION "planner"

const char *gmmrrtd_planner_name(int32_t planner)
{
    const gmmrrt_config_key_t *k = gmmrrt_config_key_find("planner");
    return planner >= 1 && planner <= GMMRRT_KEY_MAX_CHOICES && k->choices[planner - 1] ? k->choices[planner - 1]
                                                                                        : "?";
}

static int fail(char *err, size_t errcap, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int fail(char *err, size_t errcap, const char *fmt, ...)
{
    if (err != NULL && errcap > 0) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err, errcap, fmt, ap);
        va_end(ap);
    }
    return -1;
}

void gmmrrtd_settings_default(gmmrrtd_settings_t *s)
{
    memset(s, 0, sizeof *s);
    snprintf(s->lcm_url, sizeof s->lcm_url, "%s", GMMRRTD_DEFAULT_LCM_URL);
    snprintf(s->clock, sizeof s->clock, "auto");
    snprintf(s->ch_pose, sizeof s->ch_pose, "ROBOT_POSE");
    snprintf(s->ch_people, sizeof s->ch_people, "PEOPLE");
    snprintf(s->ch_goal, sizeof s->ch_goal, "NAV_GOAL");
    snprintf(s->ch_obstacles, sizeof s->ch_obstacles, "OBSTACLES");
    snprintf(s->ch_scan, sizeof s->ch_scan, "SCAN");
    snprintf(s->ch_grid, sizeof s->ch_grid, "GRID");
    snprintf(s->ch_plan, sizeof s->ch_plan, "PLAN");
    snprintf(s->ch_status, sizeof s->ch_status, "PLANNER_STATUS");
    s->rate_hz = 10.0;
    s->budget_ms = 60.0;
    s->budget_iterations = 0;
    snprintf(s->trigger, sizeof s->trigger, "tick");
    s->min_period_ms = 20.0;
    s->event_burst = 2;
    s->anytime_max_plans = 1;
    s->anytime_improvement = 0.05;
    s->pose_timeout_ms = 500.0;
    s->unreachable_after_cycles = 5;
    s->goal_fail_after_ms = 3000.0;
    s->people_timeout_ms = 1000.0;
    s->obstacles_timeout_ms = 0.0;
    s->scan_timeout_ms = 500.0;
    s->grid_timeout_ms = 1000.0;
    s->max_future_ms = 2000.0;
    s->time_resync_count = 5;
    s->time_resync_ms = 1000.0;
    s->clock_slew_ms_per_s = 10.0;
    s->long_step_ms = 30000.0;
    s->bounds_margin_m = GMMRRT_DEFAULT_BOUNDS_MARGIN_M;
    snprintf(s->frame, sizeof s->frame, "map");
    s->map[0] = '\0';
    s->map_max_cells = 2048 * 2048; /* 36 MiB of raster; 102 x 102 m at 5 cm */
    s->map_max_side = 4096;
    s->map_unknown_blocked = 1;
    s->scan_decay_ms = 2000.0;
    s->scan_pose_gap_ms = 100.0;
    s->scan_max_per_cycle = 4;
    s->scan_stale_stop = 1;
    s->scan_reach_m = 1.5;
    s->grid_occupied = 65;
    s->warm_goal_shift_m = 0.25;
    s->warm_people_shift_m = 0.3;
    s->warm_robot_offset_m = 0.5;
    s->nominal_speed_m_s = GMMRRT_DEFAULT_NOMINAL_SPEED_M_S;
    s->prediction_horizon_s = GMMRRT_DEFAULT_PREDICTION_HORIZON_S;
    gmmrrt_drive_options_t drive;
    gmmrrt_drive_options_default(&drive);
    s->min_turn_radius_m = drive.min_turn_radius_m;
    s->use_goal_yaw = 0;
    s->face_target = 1;
    s->yaw_tolerance_deg = drive.goal_yaw_tolerance_rad * 180.0 / M_PI;
    s->arrival_leg_m = drive.arrival_leg_m;
    gmmrrt_planner_config_default(&s->cfg);
    snprintf(s->log_level, sizeof s->log_level, "info");
    s->log_interval_ms = 5000.0;
}

/* Parses `value` into the field of key k. 0 or -1 with the reason (without location). */
static int set_key(gmmrrtd_settings_t *s, const key_t_ *k, const char *value, char *err, size_t errcap)
{
    char *field = (char *)s + k->offset;
    if (value == NULL)
        value = "";
    if (k->type == K_STR) {
        if (strlen(value) >= k->size)
            return fail(err, errcap, "%s: value longer than %zu characters", k->key, k->size - 1);
        memcpy(field, value, strlen(value) + 1);
        return 0;
    }
    if (k->type == K_BOOL) {
        int32_t b;
        if (!strcmp(value, "1") || !strcmp(value, "true") || !strcmp(value, "yes") || !strcmp(value, "on"))
            b = 1;
        else if (!strcmp(value, "0") || !strcmp(value, "false") || !strcmp(value, "no") || !strcmp(value, "off"))
            b = 0;
        else
            return fail(err, errcap, "%s = \"%s\": expected true or false", k->key, value);
        memcpy(field, &b, sizeof b);
        return 0;
    }
    /* Each number is parsed once, by the parser of the type it is stored in: a whole-number
     * key takes digits only ("1e3" or "2.5" are errors, never 1 or 2). */
    errno = 0;
    char *end = NULL;
    if (k->type == K_F64) {
        const double v = strtod(value, &end);
        if (end == value || *end != '\0' || errno == ERANGE || !isfinite(v))
            return fail(err, errcap, "%s = \"%s\": not a number", k->key, value);
        if (v < k->min || v > k->max)
            return fail(err, errcap, "%s = %s: outside %g..%g", k->key, value, k->min, k->max);
        memcpy(field, &v, sizeof v);
        return 0;
    }
    const long long x = strtoll(value, &end, 10);
    if (end == value || *end != '\0' || errno == ERANGE)
        return fail(err, errcap, "%s = \"%s\": expected a whole number of digits", k->key, value);
    if ((double)x < k->min || (double)x > k->max)
        return fail(err, errcap, "%s = %s: outside %g..%g", k->key, value, k->min, k->max);
    if (k->type == K_I32) {
        const int32_t v = (int32_t)x;
        memcpy(field, &v, sizeof v);
    } else {
        const int64_t v = (int64_t)x;
        memcpy(field, &v, sizeof v);
    }
    return 0;
}

typedef struct {
    gmmrrtd_settings_t *s;
    char first_err[512]; /* the handler's reason for the first bad line */
} ini_ctx_t;

static int on_ini_line(void *user, const char *section, const char *name, const char *value)
{
    ini_ctx_t *ctx = user;
    char why[256];
    if (strcmp(section, PLANNER_SECTION) == 0) {
        const gmmrrt_config_key_t *pk = gmmrrt_config_key_find(name);
        if (pk != NULL && strcmp(pk->name, name) == 0) {
            if (gmmrrt_config_key_set(&ctx->s->cfg, pk, value ? value : "", why, sizeof why) == GMMRRT_OK)
                return 1;
            if (ctx->first_err[0] == '\0')
                snprintf(ctx->first_err, sizeof ctx->first_err, "[%s] %s = %s: %s", section, name, value, why);
            return 0;
        }
    }
    for (int i = 0; i < N_KEYS; ++i) {
        if (strcmp(k_keys[i].section, section) != 0 || strcmp(k_keys[i].key, name) != 0)
            continue;
        if (set_key(ctx->s, &k_keys[i], value, why, sizeof why) == 0)
            return 1;
        if (ctx->first_err[0] == '\0')
            snprintf(ctx->first_err, sizeof ctx->first_err, "[%s] %s", section, why);
        return 0;
    }
    if (ctx->first_err[0] == '\0')
        snprintf(ctx->first_err, sizeof ctx->first_err, "unknown key \"%s\" in section [%s]", name, section);
    return 0;
}

int gmmrrtd_settings_load_ini(gmmrrtd_settings_t *s, const char *path, char *err, size_t errcap)
{
    /* Only a regular file of sane size: a directory would read as empty (defaults, no models),
     * /dev/zero would never end, a FIFO would block start-up or a reload. O_NONBLOCK so that
     * even the open() of a FIFO returns; fstat decides. */
    const int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0)
        return fail(err, errcap, "%s: cannot open: %s", path, strerror(errno));
    struct stat sb;
    const int stat_ok = fstat(fd, &sb) == 0;
    if (!stat_ok || !S_ISREG(sb.st_mode)) {
        const int is_dir = stat_ok && S_ISDIR(sb.st_mode);
        close(fd);
        return fail(err, errcap, "%s: %s, not a configuration file", path,
                    is_dir ? "is a directory" : "is not a regular file (a FIFO, device or socket)");
    }
    if (sb.st_size > GMMRRTD_CONFIG_MAX_BYTES) {
        close(fd);
        return fail(err, errcap, "%s: %lld bytes, more than any configuration (%d)", path, (long long)sb.st_size,
                    GMMRRTD_CONFIG_MAX_BYTES);
    }
    FILE *f = fdopen(fd, "r");
    if (f == NULL) {
        const int e = errno;
        close(fd);
        return fail(err, errcap, "%s: cannot read: %s", path, strerror(e));
    }
    ini_ctx_t ctx = {.s = s, .first_err = ""};
    const int rc = ini_parse_file(f, on_ini_line, &ctx);
    fclose(f);
    if (rc == -2)
        return fail(err, errcap, "%s: out of memory while parsing", path);
    if (rc != 0)
        return fail(err, errcap, "%s:%d: %s", path, rc, ctx.first_err[0] ? ctx.first_err : "syntax error");
    return 0;
}

void gmmrrtd_settings_print_help(const char *argv0)
{
    printf("Usage: %s [OPTION]...\n"
           "gmmrrtd: the gmmrrt social navigation planner daemon. Subscribes robot pose, people,\n"
           "goal and obstacles on LCM, publishes a plan and a status at a fixed rate.\n\n"
           "  -h, --help             this text\n"
           "  -V, --version          print the version\n"
           "  -c, --config FILE      INI file with the settings below ([section] key); flags override it\n",
           argv0);
    static gmmrrtd_settings_t defaults;
    gmmrrtd_settings_default(&defaults);
    for (int i = 0; i < N_KEYS; ++i) {
        const key_t_ *k = &k_keys[i];
        const char *field = (const char *)&defaults + k->offset;
        char left[64], def[80] = "";
        snprintf(left, sizeof left, "--%s%s", k->flag, k->type == K_BOOL ? "[=0|1]" : " V");
        if (k->type == K_STR && field[0] != '\0') {
            snprintf(def, sizeof def, "; default %.60s", field);
        } else if (k->type == K_F64) {
            double v;
            memcpy(&v, field, sizeof v);
            snprintf(def, sizeof def, "; default %g", v);
        } else if (k->type == K_I32 || k->type == K_BOOL) {
            int32_t v;
            memcpy(&v, field, sizeof v);
            snprintf(def, sizeof def, "; default %d", (int)v);
        } else if (k->type == K_I64) {
            int64_t v;
            memcpy(&v, field, sizeof v);
            snprintf(def, sizeof def, "; default %lld", (long long)v);
        }
        printf("      %-26s %s%s  [%s] %s\n", left, k->help, def, k->section, k->key);
    }
    for (int32_t i = 0; i < gmmrrt_config_key_count(); ++i) {
        const gmmrrt_config_key_t *k = gmmrrt_config_key_at(i);
        char left[64], def[64], range[128];
        snprintf(left, sizeof left, "--%s V", k->flag);
        printf("      %-26s %s; %s; default %s  [%s] %s\n", left, k->help,
               gmmrrt_config_key_range(k, range, sizeof range),
               gmmrrt_config_key_format(&defaults.cfg, k, def, sizeof def), PLANNER_SECTION, k->name);
    }
    printf("\nDefault LCM URL: %s (ttl=0: messages stay on this host).\n"
           "Signals: SIGINT/SIGTERM exit cleanly; SIGHUP reloads the config file and the models.\n"
           "Details: docs/daemon.md\n",
           GMMRRTD_DEFAULT_LCM_URL);
}

int gmmrrtd_settings_from_args(gmmrrtd_settings_t *s, int argc, char **argv, char *err, size_t errcap)
{
    enum { OPT_BASE = 1000, OPT_PLANNER_BASE = 2000 };
    struct option opts[N_KEYS + GMMRRT_CONFIG_MAX_KEYS + 4];
    int n = 0;
    opts[n++] = (struct option){"help", no_argument, NULL, 'h'};
    opts[n++] = (struct option){"version", no_argument, NULL, 'V'};
    opts[n++] = (struct option){"config", required_argument, NULL, 'c'};
    for (int i = 0; i < N_KEYS; ++i)
        opts[n++] = (struct option){k_keys[i].flag, k_keys[i].type == K_BOOL ? optional_argument : required_argument,
                                    NULL, OPT_BASE + i};
    for (int32_t i = 0; i < gmmrrt_config_key_count(); ++i)
        opts[n++] = (struct option){gmmrrt_config_key_at(i)->flag, required_argument, NULL, OPT_PLANNER_BASE + i};
    opts[n] = (struct option){NULL, 0, NULL, 0};

    /* Pass 1: --help, --version, --config, and any syntax error. */
    opterr = 0;
    optind = 0;
    int c;
    s->config_path[0] = '\0';
    while ((c = getopt_long(argc, argv, ":hVc:", opts, NULL)) != -1) {
        if (c == 'h') {
            gmmrrtd_settings_print_help(argv[0]);
            return 1;
        }
        if (c == 'V') {
            printf("gmmrrtd %s\n", GMMRRT_VERSION_STRING);
            return 1;
        }
        if (c == 'c') {
            if (strlen(optarg) >= sizeof s->config_path)
                return fail(err, errcap, "--config: path too long");
            snprintf(s->config_path, sizeof s->config_path, "%s", optarg);
        } else if (c == ':') {
            return fail(err, errcap, "%s: needs a value (see --help)", argv[optind - 1]);
        } else if (c == '?') {
            return fail(err, errcap, "%s: unknown option (see --help)", argv[optind - 1]);
        }
    }
    if (optind < argc)
        return fail(err, errcap, "unexpected argument \"%s\" (see --help)", argv[optind]);
    if (s->config_path[0] != '\0' && gmmrrtd_settings_load_ini(s, s->config_path, err, errcap) != 0)
        return -1;

    /* Pass 2: every other flag, over the file. */
    optind = 0;
    while ((c = getopt_long(argc, argv, ":hVc:", opts, NULL)) != -1) {
        if (c < OPT_BASE)
            continue;
        char why[256];
        if (c >= OPT_PLANNER_BASE) {
            const gmmrrt_config_key_t *pk = gmmrrt_config_key_at(c - OPT_PLANNER_BASE);
            if (gmmrrt_config_key_set(&s->cfg, pk, optarg, why, sizeof why) != GMMRRT_OK)
                return fail(err, errcap, "--%s: %s = %s: %s", pk->flag, pk->name, optarg, why);
            continue;
        }
        const key_t_ *k = &k_keys[c - OPT_BASE];
        /* A switch: --flag alone is 1, --flag=0 switches it off. */
        if (set_key(s, k, k->type == K_BOOL && optarg == NULL ? "1" : optarg, why, sizeof why) != 0)
            return fail(err, errcap, "--%s: %s", k->flag, why);
    }
    return 0;
}

gmmrrtd_clock_mode_t gmmrrtd_settings_clock(const gmmrrtd_settings_t *s)
{
    if (!strcmp(s->clock, "live"))
        return GMMRRTD_CLOCK_LIVE;
    if (!strcmp(s->clock, "log"))
        return GMMRRTD_CLOCK_LOG;
    return strncmp(s->lcm_url, "file://", 7) == 0 ? GMMRRTD_CLOCK_LOG : GMMRRTD_CLOCK_LIVE;
}

int gmmrrtd_settings_validate(const gmmrrtd_settings_t *s, char *err, size_t errcap)
{
    if (strcmp(s->clock, "auto") && strcmp(s->clock, "live") && strcmp(s->clock, "log"))
        return fail(err, errcap, "clock = \"%s\": expected auto, live or log", s->clock);
    gmmrrtd_log_level_t lvl;
    if (gmmrrtd_log_level_parse(s->log_level, &lvl) != 0)
        return fail(err, errcap, "log level \"%s\": expected error, warn, info or debug", s->log_level);
    if (s->lcm_url[0] == '\0')
        return fail(err, errcap, "lcm url is empty");
    if (strncmp(s->lcm_url, "file://", 7) == 0 && s->lcm_out_url[0] == '\0')
        return fail(err, errcap, "a file:// input (%s) cannot be published on: give --lcm-out-url", s->lcm_url);
    if (strncmp(s->lcm_url, "file://", 7) == 0 && !strcmp(s->clock, "live"))
        return fail(err, errcap, "clock = live with a file:// input (%s): a log is replayed on its own event times "
                                 "(clock = log or auto)", s->lcm_url);
    /* lcm_subscribe takes a channel as a POSIX regular expression: "ROBOT.POSE" would also take
     * "ROBOTXPOSE", and "PEOPLE|NAV_GOAL" two channels into one handler. A name is therefore a
     * literal, and the characters that would make it a pattern are refused. */
    const char *chans[] = {s->ch_pose, s->ch_people, s->ch_goal,   s->ch_obstacles,
                           s->ch_scan, s->ch_grid,   s->ch_plan, s->ch_status};
    const char *chan_keys[] = {"pose", "people", "goal", "obstacles", "scan", "grid", "plan", "status"};
    for (int i = 0; i < (int)(sizeof chans / sizeof chans[0]); ++i) {
        if (chans[i][0] == '\0')
            return fail(err, errcap, "[channels] %s: the channel name is empty", chan_keys[i]);
        const size_t bad = strcspn(chans[i], ".[]()*+?{}|^$\\ ");
        if (chans[i][bad] != '\0')
            return fail(err, errcap,
                        "[channels] %s = \"%s\": '%c' is not allowed in a channel name (LCM reads subscribed "
                        "names as regular expressions; use letters, digits, '_', '-', '/', ':')",
                        chan_keys[i], chans[i], chans[i][bad]);
    }
    char frame_why[160];
    if (gmmrrt_msg_check_frame_name(s->frame, frame_why, sizeof frame_why) != GMMRRT_MSG_OK)
        return fail(err, errcap, "[world] frame = \"%s\": %s", s->frame, frame_why);
    const double period_ms = 1000.0 / s->rate_hz;
    if (s->budget_ms >= period_ms)
        return fail(err, errcap, "budget_ms = %g must be below the period %g ms (rate_hz = %g)", s->budget_ms,
                    period_ms, s->rate_hz);
    if (s->budget_ms <= 0.0 && s->budget_iterations <= 0)
        return fail(err, errcap, "budget_ms and budget_iterations are both 0: a cycle would never end");
    if (strcmp(s->trigger, "tick") && strcmp(s->trigger, "event"))
        return fail(err, errcap, "trigger = \"%s\": expected tick or event", s->trigger);
    if (s->model_approach[0] != '\0' && s->approach_set[0] != '\0')
        return fail(err, errcap, "models: approach = %s and approach_set = %s exclude each other (one approach model "
                    "or a set of 8)", s->model_approach, s->approach_set);
    char why[200];
    if (gmmrrt_planner_config_validate(&s->cfg, why, sizeof why) != GMMRRT_OK)
        return fail(err, errcap, "planner settings: %s", why);
    /* The per-cycle field is capped at about scan_reach_m (raster.h): below the robot's radius
     * every point would be called blocked once scans arrive. */
    if (!(s->scan_reach_m > s->cfg.robot_radius_m))
        return fail(err, errcap, "[world] scan_reach_m = %g must exceed [planner] robot_radius_m = %g", s->scan_reach_m,
                    s->cfg.robot_radius_m);
    return 0;
}
