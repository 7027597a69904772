/*
 * daemon.h - gmmrrtd's state and the jobs of its shell (STYLE.md 10): dispatch.c takes each
 * LCM message through decode -> run the cycles due -> apply; inputs.c decodes, validates and
 * time-checks a message (clock.c, one clock model per source) and applies it; cycle.c makes
 * one planning cycle (problem from the latest inputs, library call, plan and status out);
 * counters.c counts and logs rejections and stops; main.c runs the loop (poll, ticks,
 * signals, reload, systemd). Calls go one way: dispatch -> inputs, dispatch -> cycle, and
 * everything -> counters.
 *
 * Everything lives in one gmmrrtd_t, allocated statically by main.c; the planner's block is
 * allocated once at start-up. Nothing here allocates after that.
 */
#ifndef GMMRRTD_DAEMON_H
#define GMMRRTD_DAEMON_H

#include <regex.h>
#include <stdint.h>

#include <lcm/lcm.h>

#include "gmmrrt/drivable.h"
#include "gmmrrt/model.h"
#include "gmmrrt/model_set.h"
#include "gmmrrt/msg_decode.h"
#include "gmmrrt/raster.h"
#include "gmmrrt/planner.h"
#include "log.h"
#include "pacing.h"
#include "settings.h"
#include "clock.h"
#include "stop.h"

enum {
    GMMRRTD_IN_POSE = 0,
    GMMRRTD_IN_PEOPLE = 1,
    GMMRRTD_IN_GOAL = 2,
    GMMRRTD_IN_OBSTACLES = 3,
    GMMRRTD_IN_SCAN = 4,
    GMMRRTD_IN_GRID = 5,
    GMMRRTD_NUM_INPUTS = 6
};
/* Robot poses kept to place scans (scan.c): at 100 Hz, 0.64 s of history. */
#define GMMRRTD_POSE_RING 64
/* Rate-limiter rows: one per input, then the daemon's own (planner, reload, stops). */
enum { GMMRRTD_RL_PLANNER = GMMRRTD_NUM_INPUTS, GMMRRTD_RL_STOP = GMMRRTD_NUM_INPUTS + 1, GMMRRTD_RL_ROWS = GMMRRTD_NUM_INPUTS + 2 };

/* One robot pose of the ring that places scans (scan.c), on the pose source's own stamps. */
typedef struct {
    int64_t utime;
    double x, y, yaw;
} gmmrrtd_pose_sample_t;

/* What the last published plan was made in: the warm start compares against it. */
typedef struct {
    int valid;
    double goal_x, goal_y;
    int32_t task, target_id, side;
    int32_t num_people;
    int32_t people_id[GMMRRT_MAX_PEOPLE];
    double people_x[GMMRRT_MAX_PEOPLE], people_y[GMMRRT_MAX_PEOPLE];
    int64_t obstacles_version;
    int64_t grid_version;
} gmmrrtd_snapshot_t;

/* Finished goals remembered, so that a late re-send of one is not taken as a new goal. */
#define GMMRRTD_FINISHED_GOALS 64

/* The current goal's life (goal.c; docs/daemon.md, "The goal's life"). */
typedef struct {
    int64_t id;                 /* the current (or last finished) goal's id; 0 = none yet */
    int8_t state;               /* planner_status_t.GOAL_* */
    int8_t failure;             /* planner_status_t.FAILURE_* when FAILED */
    int announce;               /* 1: the finished goal's empty plan is still to be published (once) */
    int64_t unusable_since_us;  /* local time since which no cycle could plan the goal; -1: it could */
    double remaining_m;         /* length of the last plan published for it; -1 none */
    int8_t side_result;         /* planner_status_t.SIDE_* of the last cycle */
    int64_t finished[GMMRRTD_FINISHED_GOALS]; /* ring of finished ids (0 = empty slot) */
    int32_t finished_next;
} gmmrrtd_goal_life_t;

/* One decoded message waiting to be applied (dispatch.c: decode -> cycles due -> apply). */
typedef struct {
    int input;                   /* GMMRRTD_IN_* or -1: nothing staged */
    gmmrrtd_source_clock_t clock;/* the source's clock model once the message is applied */
    union {
        gmmrrt_pose2d_t pose;
        gmmrrt_people_t people;
        gmmrrt_nav_goal_t goal;
        gmmrrt_obstacles_t obstacles;
        gmmrrt_planar_scan_t scan;
        gmmrrt_occupancy_grid_t grid;
    } m;
    double sensor_x, sensor_y, sensor_yaw; /* a scan: the sensor's world pose at its utime (scan.c) */
} gmmrrtd_staged_t;

typedef struct {
    gmmrrtd_settings_t set;
    gmmrrtd_clock_mode_t clock_mode;
    lcm_t *lcm_in;
    lcm_t *lcm_out;          /* == lcm_in unless --lcm-out-url */
    lcm_eventlog_t *replay;  /* a file:// input, read event by event (dispatch.c); NULL live */
    regex_t replay_re[GMMRRTD_NUM_INPUTS];

    /* Latest accepted inputs. */
    int have[GMMRRTD_NUM_INPUTS];
    gmmrrtd_source_clock_t src[GMMRRTD_NUM_INPUTS]; /* each source's clock model (clock.h) */
    gmmrrt_pose2d_t pose;
    gmmrrt_people_t people;
    gmmrrt_nav_goal_t goal;
    gmmrrt_obstacles_t obstacles;
    int64_t obstacles_version;   /* +1 whenever the obstacle content changes */
    int64_t goal_version;        /* +1 whenever the goal's content changes */
    gmmrrtd_goal_life_t life;    /* the goal's id and state (goal.c) */
    gmmrrtd_staged_t staged;

    /* Local time base (clock.h): live, CLOCK_MONOTONIC; log, the log's event times made
     * non-decreasing. In log mode cycles run at t0 + k / rate_hz as the log time passes them. */
    int have_time;
    int64_t log_now_us;
    int64_t next_tick_us;        /* log mode: the next cycle's local time */
    int32_t stale_mask;          /* STALE_* bits of the last cycle */
    int event_pending;           /* live, trigger = event: an input arrived that should start a cycle */
    gmmrrtd_pacing_t pacing;     /* live, trigger = event: how soon the next cycle may start */

    /* Models by task; loaded at start, replaced on SIGHUP only when the new file is good. */
    gmmrrt_model_t model_avoid, model_approach, model_scratch;
    int have_avoid, have_approach;
    /* The approach model set (model_set.h), used instead of model_approach when configured: all 8
     * directions or none (a reload loads into the scratch set and swaps only when all are good). */
    gmmrrt_model_t approach_set[GMMRRT_APPROACH_DIRECTIONS], approach_set_scratch[GMMRRT_APPROACH_DIRECTIONS];
    int have_approach_set;
    /* Each model file's background model (model.h, its background section; the density
     * [planner] task_cost = background divides by): loaded with its model into the scratch
     * slots and replaced together with it. has_bg_*: the model in use came with one (required
     * when task_cost = background, models.c). */
    gmmrrt_model_t bg_avoid, bg_approach, bg_scratch;
    int has_bg_avoid, has_bg_approach;
    gmmrrt_model_t approach_set_bg[GMMRRT_APPROACH_DIRECTIONS], approach_set_bg_scratch[GMMRRT_APPROACH_DIRECTIONS];
    int approach_set_has_bg[GMMRRT_APPROACH_DIRECTIONS], approach_set_has_bg_scratch[GMMRRT_APPROACH_DIRECTIONS];

    /* The static map (world.c): a raster allocated once at start-up when a map is configured,
     * sized by map_max_cells / map_max_side; replaced on SIGHUP only by a good file. */
    gmmrrt_raster_t map;
    void *map_mem;
    int32_t map_capacity_cells, map_capacity_side;
    int have_map;

    /* Scans (scan.c): the robot poses that place them, and what became of them. They mark the
     * raster planned in (gmmrrtd_world_raster): the grid's while one is in use, else the map's. */
    gmmrrtd_pose_sample_t pose_ring[GMMRRTD_POSE_RING];
    int32_t pose_ring_n, pose_ring_next;
    int64_t scan_last_utime;     /* the newest applied scan's stamp (the marks' clock) */
    int32_t scans_this_cycle;    /* applied since the last cycle (scan_max_per_cycle) */
    int64_t scans_applied, scans_dropped, scans_blind, scan_cells_marked, scan_cells_cleared;

    /* The local grid (grid.c): a raster of the wire's capacity, allocated at start-up, that
     * replaces the map while grids arrive; a malformed grid leaves the last good one. */
    gmmrrt_raster_t grid;
    void *grid_mem;
    int have_grid;
    int64_t grid_version;        /* +1 with every accepted grid */

    /* The planner: one block, allocated once. */
    void *mem;
    size_t mem_size;
    gmmrrt_planner_t *planner;
    gmmrrt_problem_t problem;
    gmmrrt_path_t path;
    gmmrrt_path_t last_path;     /* the last published path, for the warm start */
    gmmrrtd_snapshot_t last;     /* the situation it was made in */
    double seed_x[GMMRRT_MAX_WAYPOINTS + 1], seed_y[GMMRRT_MAX_WAYPOINTS + 1];

    /* Per-goal bookkeeping: planning faults are counted once per goal (docs/daemon.md). */
    int64_t counted_goal_version[GMMRRT_PLANNER_STATUS_T_NUM_REJECT_REASONS];
    int32_t no_path_cycles;
    int stale_counted[GMMRRTD_NUM_INPUTS]; /* the current gap of this input was counted */

    /* Outputs. */
    gmmrrt_planner_status_t status;
    gmmrrt_waypoints_t plan_msg;
    int64_t plan_seq;
    int64_t cycles;
    int64_t warm_starts;
    int64_t grid_updates[3]; /* set_problem's clearance grid: built, kept, shifted (gmmrrt_grid_update_t) */

    /* Watchdog (systemd): the normal interval, 0 when not supervised. main.c sets it. */
    int64_t watchdog_usec;

    gmmrrtd_ratelimit_t rl[GMMRRTD_RL_ROWS][GMMRRT_PLANNER_STATUS_T_NUM_REJECT_REASONS];
    gmmrrtd_ratelimit_t rl_stop[GMMRRT_PLANNER_STATUS_T_NUM_STOP_REASONS];
    gmmrrtd_ratelimit_t rl_goal;  /* the "new goal" line */
    gmmrrtd_ratelimit_t rl_escape; /* the "escaping" line */
    gmmrrtd_ratelimit_t rl_tight;  /* the "turns tighter than the bound" line */
    gmmrrt_drive_report_t drive_report; /* the last published path's (drivable.h) */
} gmmrrtd_t;

/* CLOCK_MONOTONIC in microseconds. */
int64_t gmmrrtd_mono_us(void);

/* The local time now: CLOCK_MONOTONIC live, the log time in log mode. */
int64_t gmmrrtd_now_us(const gmmrrtd_t *d);

/* min_period_ms in microseconds: the event trigger's refill period (pacing.h). */
int64_t gmmrrtd_min_period_us(const gmmrrtd_t *d);

/* dispatch.c: subscribes the six input channels. 0 or -1 (logged). */
int gmmrrtd_subscribe(gmmrrtd_t *d);

/* dispatch.c: one message of `input` (GMMRRTD_IN_*; other values are ignored), len raw bytes
 * at buf, received at recv_utime (the log's event time; only read in log mode): decode and
 * judge it (inputs.c), run the cycles due by its arrival (log mode), then apply it. The bytes
 * are only read, never kept. The entry point of the LCM handlers, the unit tests and
 * tests/fuzz/fuzz_daemon_inputs.c. */
void gmmrrtd_handle_message(gmmrrtd_t *d, int input, int64_t recv_utime, const void *buf, size_t len);

/* dispatch.c: a file:// input read with its event times. open: 0 or -1 (logged); step: 1
 * when an event was read (and handled when it is on an input channel), 0 at the end. */
int gmmrrtd_replay_open(gmmrrtd_t *d);
int gmmrrtd_replay_step(gmmrrtd_t *d);
void gmmrrtd_replay_close(gmmrrtd_t *d);

/* inputs.c: decodes, validates and time-checks one message arriving at local time local_us;
 * rejections are counted. 1 when it is staged in d->staged (apply with gmmrrtd_inputs_apply),
 * 0 when rejected. */
int gmmrrtd_inputs_decode(gmmrrtd_t *d, int input, int64_t local_us, const void *buf, size_t len);

/* inputs.c: makes the staged message the latest value of its channel. */
void gmmrrtd_inputs_apply(gmmrrtd_t *d);

/* goal.c: applies an accepted nav_goal_t (decoded, in the planning frame, on time): a NEW with
 * the current goal's id updates it, with a finished goal's id is refused (REJECT_GOAL_ID_REUSED),
 * with any other id replaces the current goal (which counts as finished); a CANCEL of the
 * current goal cancels it, of a finished goal is ignored (a re-send), of any other id is refused
 * (REJECT_BAD_VALUE). Returns 1 when the goal or its state changed (a cycle is due). */
int gmmrrtd_goal_apply(gmmrrtd_t *d, const gmmrrt_nav_goal_t *m);

/* goal.c: 1 while the current goal is to be planned (ACCEPTED or PLANNING). */
int gmmrrtd_goal_active(const gmmrrtd_t *d);

/* goal.c: the cycle's verdicts on the current goal. reached: within tolerance_m and, when
 * yaw_tolerance_rad > 0, the heading within it, judged on the pose (1 when it was). planned: a
 * plan was published (remaining_m its length). unusable: a goal-side stop (FAILURE_* of the
 * cause); after goal_fail_after_ms of those in a row the goal FAILS. finish: the goal ends in
 * `state` (REACHED, CANCELLED, FAILED), its id joins the finished ring. */
int gmmrrtd_goal_check_reached(gmmrrtd_t *d);
void gmmrrtd_goal_planned(gmmrrtd_t *d, double length_m);
void gmmrrtd_goal_unusable(gmmrrtd_t *d, int64_t now_us, int failure);
void gmmrrtd_goal_finish(gmmrrtd_t *d, int8_t state, int8_t failure);

/* counters.c: counts a rejection and logs it rate-limited. row = GMMRRTD_IN_* or
 * GMMRRTD_RL_PLANNER for the daemon's own reasons. */
void gmmrrtd_reject(gmmrrtd_t *d, int row, int reason, const char *fmt, ...) __attribute__((format(printf, 4, 5)));

/* counters.c: counts one stopped cycle under `stop` (STOP_* of planner_status_t) and logs
 * it rate-limited (one line per reason per log_interval_ms, with the count suppressed). */
void gmmrrtd_count_stop(gmmrrtd_t *d, int stop, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* cycle.c: one planning cycle at local time now_us; publishes PLAN (unless idle) and
 * PLANNER_STATUS. */
void gmmrrtd_cycle(gmmrrtd_t *d, int64_t now_us);

/* models.c: loads both model files (and the approach set) with their background models and
 * checks each against its use (task, the feature space the configured planner needs:
 * gmmrrt_planner_model_fits, and a background when [planner] task_cost = background). A model
 * and its background replace the ones in use together or not at all. At start-up (`reload` 0)
 * a failure is fatal (-1); on reload a failure keeps the old model, counts
 * REJECT_MODEL_RELOAD and logs every time. */
int gmmrrtd_models_load(gmmrrtd_t *d, int reload);

/* models.c: 1 when every model in use can drive a planner configured by cfg (its feature space,
 * gmmrrt_planner_model_fits, and a background of its own when cfg->task_cost = background);
 * else 0 with the first misfit in why[cap]. A reload whose new planner settings the models in
 * use do not fit (their new files were refused) keeps the old settings (main.c). */
int gmmrrtd_models_fit_config(const gmmrrtd_t *d, const gmmrrt_planner_config_t *cfg, char *why, size_t cap);

/* world.c: loads [world] map into the map raster (allocated at the first load, at start-up).
 * At start-up (`reload` 0) a failure is fatal (-1, logged); on reload a bad or missing file
 * keeps the old map, counts REJECT_MODEL_RELOAD and logs every time. An empty path removes
 * the map. */
int gmmrrtd_world_load(gmmrrtd_t *d, int reload);

/* scan.c: the pose ring (every accepted pose is added) and a scan's placement. place: 1 with
 * the sensor's world pose in d->staged when a pose brackets the scan's utime (interpolated) or
 * the newest pose is at most scan_pose_gap_ms older (held); 0 when refused (counted, logged).
 * apply: marks and clears the raster planned in, at most scan_max_per_cycle scans a cycle. */
void gmmrrtd_scan_add_pose(gmmrrtd_t *d, const gmmrrt_pose2d_t *pose);
int gmmrrtd_scan_place(gmmrrtd_t *d, const gmmrrt_planar_scan_t *scan);
void gmmrrtd_scan_apply(gmmrrtd_t *d);

/* scan.c: the raster a cycle plans in: the grid's while one is in use, else the map's, else NULL. */
gmmrrt_raster_t *gmmrrtd_world_raster(gmmrrtd_t *d);

/* scan.c: before a cycle's set_problem: the raster's field made ready over the problem's
 * bounds (the window only, when scan marks exist: bounded work per cycle; marks count while
 * younger than scan_decay_ms, and not at all while the scans are stale and scan_stale_stop
 * is 0). GMMRRT_OK or the raster's status. */
gmmrrt_status_t gmmrrtd_world_prepare(gmmrrtd_t *d, int64_t now_us);

/* grid.c: allocates the grid raster at start-up (0, or -1 logged); a decoded grid's check
 * against the raster (1 to stage, 0 refused and counted) and its application. */
int gmmrrtd_grid_setup(gmmrrtd_t *d);
int gmmrrtd_grid_check(gmmrrtd_t *d, const gmmrrt_occupancy_grid_t *grid);
void gmmrrtd_grid_apply(gmmrrtd_t *d);

/* main.c / watchdog.c: tells systemd's watchdog the daemon is alive; before a step that may
 * take long, gmmrrtd_watchdog_long_step(d, 1) stretches the interval to long_step_ms, and
 * (d, 0) restores it. No-ops without libsystemd or outside systemd. */
void gmmrrtd_watchdog_ping(const gmmrrtd_t *d);
void gmmrrtd_watchdog_long_step(const gmmrrtd_t *d, int begin);

#endif /* GMMRRTD_DAEMON_H */
