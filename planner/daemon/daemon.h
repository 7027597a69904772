/*
 * daemon.h - gmmrrtd's state and the three jobs of its shell (STYLE.md 10):
 * inputs.c takes LCM messages in (decode, validate, time checks, counters), cycle.c makes
 * one planning cycle (problem from the latest inputs, library call, plan and status out),
 * main.c runs the loop (poll, ticks, signals, reload, systemd).
 *
 * Everything lives in one gmmrrtd_t, allocated statically by main.c; the planner's block is
 * allocated once at start-up. Nothing here allocates after that.
 */
#ifndef GMMRRTD_DAEMON_H
#define GMMRRTD_DAEMON_H

#include <stdint.h>

#include <lcm/lcm.h>

#include "gmmrrt/model.h"
#include "gmmrrt/msg_decode.h"
#include "gmmrrt/rrtstar.h"
#include "log.h"
#include "settings.h"

/* Largest input utime accepted (us); larger or negative ones count as REJECT_BAD_VALUE. */
#define GMMRRTD_MAX_UTIME ((int64_t)1 << 53)

enum { GMMRRTD_IN_POSE = 0, GMMRRTD_IN_PEOPLE = 1, GMMRRTD_IN_GOAL = 2, GMMRRTD_IN_OBSTACLES = 3, GMMRRTD_NUM_INPUTS = 4 };

/* What the last published plan was made in: the warm start compares against it. */
typedef struct {
    int valid;
    double goal_x, goal_y;
    int32_t task, target_id;
    int32_t num_people;
    int32_t people_id[GMMRRT_MAX_PEOPLE];
    double people_x[GMMRRT_MAX_PEOPLE], people_y[GMMRRT_MAX_PEOPLE];
    int64_t obstacles_version;
} gmmrrtd_snapshot_t;

typedef struct {
    gmmrrtd_settings_t set;
    gmmrrtd_clock_mode_t clock_mode;
    lcm_t *lcm_in;
    lcm_t *lcm_out;          /* == lcm_in unless --lcm-out-url */

    /* Latest accepted inputs. */
    int have[GMMRRTD_NUM_INPUTS];
    int64_t last_utime[GMMRRTD_NUM_INPUTS]; /* per channel: older messages are rejected */
    gmmrrt_pose2d_t pose;
    gmmrrt_people_t people;
    gmmrrt_nav_goal_t goal;
    gmmrrt_obstacles_t obstacles;
    int64_t obstacles_version;   /* +1 whenever the obstacle content changes */
    int64_t goal_version;        /* +1 whenever the goal's content changes */

    /* Planning clock (docs/daemon.md): the newest accepted input utime, plus in live mode
     * the monotonic time since it arrived. */
    int have_clock;
    int64_t clock_utime;
    int64_t clock_mono_us;
    int64_t next_tick_utime;     /* log mode: the next cycle's time */
    /* Time guard (docs/daemon.md, "Clock steps"): per channel, the direction (+1 future,
     * -1 backwards, 0 none) and length of the current run of messages off the clock. */
    int time_off_dir[GMMRRTD_NUM_INPUTS];
    int32_t time_off_run[GMMRRTD_NUM_INPUTS];

    /* Models by task; loaded at start, replaced on SIGHUP only when the new file is good. */
    gmmrrt_model_t model_avoid, model_approach, model_scratch;
    int have_avoid, have_approach;

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
    int pose_stale_counted;      /* the current pose gap was counted */

    /* Outputs. */
    gmmrrt_planner_status_t status;
    gmmrrt_waypoints_t plan_msg;
    int64_t plan_seq;
    int64_t cycles;
    int64_t warm_starts;
    int64_t grid_updates[3]; /* set_problem's clearance grid: built, kept, shifted (gmmrrt_grid_update_t) */

    gmmrrtd_ratelimit_t rl[GMMRRTD_NUM_INPUTS + 1][GMMRRT_PLANNER_STATUS_T_NUM_REJECT_REASONS];
} gmmrrtd_t;

/* CLOCK_MONOTONIC in microseconds. */
int64_t gmmrrtd_mono_us(void);

/* inputs.c: subscribes the four input channels. 0 or -1 (logged). */
int gmmrrtd_inputs_subscribe(gmmrrtd_t *d);

/* inputs.c: decodes, validates and applies one message of `input` (GMMRRTD_IN_*; other values
 * are ignored) from len raw bytes at buf, exactly as the LCM handler of its channel does:
 * rejections are counted, in log-clock mode due cycles run first. The bytes are only read,
 * never kept. The entry point of the handlers and of tests/fuzz/fuzz_daemon_inputs.c. */
void gmmrrtd_inputs_handle(gmmrrtd_t *d, int input, const void *buf, size_t len);

/* inputs.c: counts a rejection and logs it rate-limited. input = GMMRRTD_IN_* or
 * GMMRRTD_NUM_INPUTS for the planner's own reasons. */
void gmmrrtd_reject(gmmrrtd_t *d, int input, int reason, const char *fmt, ...) __attribute__((format(printf, 4, 5)));

/* cycle.c: one planning cycle at planner time now_utime; publishes PLAN (unless idle) and
 * PLANNER_STATUS. */
void gmmrrtd_cycle(gmmrrtd_t *d, int64_t now_utime);

/* models.c: loads both model files. At start-up (`reload` 0) a failure is fatal (-1);
 * on reload a failure keeps the old model and counts REJECT_MODEL_RELOAD. */
int gmmrrtd_models_load(gmmrrtd_t *d, int reload);

#endif /* GMMRRTD_DAEMON_H */
