/*
 * settings.h - everything gmmrrtd can be told: defaults, the INI file (read with inih) and
 * the command line (getopt_long), one table of keys shared by both so that a flag and its
 * INI key can never drift apart. Flags override the file. Every bad value is an error that
 * names file:line or the flag. The reference is docs/daemon.md.
 */
#ifndef GMMRRTD_SETTINGS_H
#define GMMRRTD_SETTINGS_H

#include <stddef.h>
#include <stdint.h>

#include "gmmrrt/config.h"

#define GMMRRTD_PATH_MAX 512
/* Largest configuration file read (bytes): anything longer is not one. */
#define GMMRRTD_CONFIG_MAX_BYTES (1 << 20)
#define GMMRRTD_DEFAULT_LCM_URL "udpm://239.255.76.67:7667?ttl=0"

typedef enum { GMMRRTD_CLOCK_AUTO = 0, GMMRRTD_CLOCK_LIVE = 1, GMMRRTD_CLOCK_LOG = 2 } gmmrrtd_clock_mode_t;

typedef struct {
    /* [lcm] */
    char lcm_url[GMMRRTD_PATH_MAX];      /* input (and output unless lcm_out_url is set) */
    char lcm_out_url[GMMRRTD_PATH_MAX];  /* "" = publish on lcm_url */
    int32_t exit_at_eof;                 /* 1: exit 0 when a file:// input ends */
    char clock[16];                      /* "auto" (log for file://, else live), "live", "log" */
    /* [channels] */
    char ch_pose[64], ch_people[64], ch_goal[64], ch_obstacles[64], ch_plan[64], ch_status[64];
    char ch_scan[64], ch_grid[64]; /* planar_scan_t, occupancy_grid_t inputs (docs/world.md) */
    /* [models] paths; "" = none (tasks that need it publish a stop) */
    char model_avoid[GMMRRTD_PATH_MAX];
    char model_approach[GMMRRTD_PATH_MAX];
    char approach_set[GMMRRTD_PATH_MAX]; /* directory of 8 direction models (model_set.h); excludes model_approach */
    /* [timing] */
    double rate_hz;              /* cycles per second, (0, 1000] */
    double budget_ms;            /* planning time per cycle, >= 0, < period; 0 = no time limit */
    char trigger[16];            /* "tick": cycles at rate_hz only; "event": also on new input (live clock) */
    double min_period_ms;        /* event trigger: one cycle start per this long on average */
    int32_t event_burst;         /* event trigger: cycle starts allowed back to back (pacing.h) */
    int32_t anytime_max_plans;   /* plans published per cycle at most, >= 1 (1: one at the end) */
    double anytime_improvement;  /* a further plan of the cycle only when its cost fell by this fraction */
    int64_t budget_iterations;   /* samples per cycle, >= 0; 0 = no cap. Deterministic replays use this */
    double pose_timeout_ms;      /* > 0: no pose newer than this -> stop */
    int32_t unreachable_after_cycles; /* consecutive cycles without a path before the goal counts unreachable */
    double goal_fail_after_ms;   /* a goal that could not be planned for this long fails (docs/daemon.md) */
    double people_timeout_ms;    /* >= 0: a people list older than this is dropped (0: never) */
    double obstacles_timeout_ms; /* >= 0: an obstacle list older than this stops the robot (0: never) */
    double scan_timeout_ms;      /* >= 0: scans seen, none newer: STALE_SCAN (stop, or forget the marks) (0: never) */
    double grid_timeout_ms;      /* >= 0: a grid in use, none newer: STALE_GRID, stop (0: never) */
    double max_future_ms;        /* a message stamped further than this from its own source's clock (ahead:
                                    REJECT_TIME_FUTURE, behind: REJECT_TIME_BACKWARDS) is refused (clock.h) */
    int32_t time_resync_count;   /* a consistent off-clock run of one source this long ...            */
    double time_resync_ms;       /* ... and spanning this much local time steps that source's offset */
    double clock_slew_ms_per_s;  /* how fast an accepted message may move its source's offset */
    double long_step_ms;         /* watchdog interval granted around a step that may take long */
    /* [world] */
    double bounds_margin_m;      /* planning bounds: box around robot, goal, people, obstacles + this */
    char frame[65];              /* the planning frame: inputs in any other are refused (msg_decode.h) */
    char map[GMMRRTD_PATH_MAX];  /* map_server YAML (docs/world.md); "" = no map */
    int32_t map_max_cells;       /* raster capacity, fixed at start-up: cells ... */
    int32_t map_max_side;        /* ... and cells a side; a larger map is refused */
    int32_t map_unknown_blocked; /* 1: unknown cells and the outside of the map (or grid) block */
    double scan_decay_ms;        /* a scan's mark blocks this long after the scan that made it */
    double scan_pose_gap_ms;     /* a scan newer than the newest pose by at most this is placed at it */
    int32_t scan_max_per_cycle;  /* scans integrated between two cycles at most; the rest dropped */
    int32_t scan_stale_stop;     /* 1: stale scans stop the robot; 0: their marks stop counting */
    double scan_reach_m;         /* per-cycle field around the bounds: how far blocked cells are looked for */
    int32_t grid_occupied;       /* grid cells >= this (0..100) block, as map_server's occupied_thresh */
    /* [warm_start]: the situation "has not changed much" when all hold */
    double warm_goal_shift_m;    /* goal moved less than this, same task and target */
    double warm_people_shift_m;  /* same tracked ids, each moved less than this */
    double warm_robot_offset_m;  /* robot within this of the last path */
    /* [people]: walking people (planner.h, "Walking people") */
    double nominal_speed_m_s;    /* robot speed that times the path against walkers, (0, 10] */
    double prediction_horizon_s; /* constant-velocity prediction horizon, (0, 60] */
    /* [drive]: the published path (drivable.h) */
    double min_turn_radius_m;    /* >= 0: smallest turning radius; 0 allows turning in place */
    int32_t use_goal_yaw;        /* 1: arrive on nav_goal_t.yaw (avoid / none tasks; approach unless face_target) */
    int32_t face_target;         /* 1: approach arrives facing the target person */
    double yaw_tolerance_deg;    /* (0, 180]: arrival heading tolerance */
    double arrival_leg_m;        /* > 0: shortest straight final leg on the arrival heading */
    /* [planner]: the core's configuration (config.h); memory fields fixed at start-up */
    gmmrrt_planner_config_t cfg;
    /* [log] */
    char log_level[16];          /* error, warn, info, debug */
    double log_interval_ms;      /* one line per reason per interval, >= 0 */

    /* Not settable in the file */
    char config_path[GMMRRTD_PATH_MAX];
} gmmrrtd_settings_t;

/* Defaults: the values in docs/daemon.md. */
void gmmrrtd_settings_default(gmmrrtd_settings_t *s);

/* Reads `path` into *s (keys not in the file keep their value). 0 on success; -1 with
 * "path:line: reason" (or "path: reason") in err[errcap]. */
int gmmrrtd_settings_load_ini(gmmrrtd_settings_t *s, const char *path, char *err, size_t errcap);

/* The full command line: finds --config (loaded first), then applies every flag over it.
 * Returns 0 to run, 1 when --help/--version was printed (exit 0), -1 on error (message in
 * err, exit 2). argv is not modified beyond getopt's permutation. */
int gmmrrtd_settings_from_args(gmmrrtd_settings_t *s, int argc, char **argv, char *err, size_t errcap);

/* Cross-field checks and the planner config's own validation. 0 or -1 with the reason. */
int gmmrrtd_settings_validate(const gmmrrtd_settings_t *s, char *err, size_t errcap);

/* The clock mode after resolving "auto" against the URL. */
gmmrrtd_clock_mode_t gmmrrtd_settings_clock(const gmmrrtd_settings_t *s);

/* The name of a planner (GMMRRT_PLANNER_*, config.h) as [planner] planner takes it; "?" for none. */
const char *gmmrrtd_planner_name(int32_t planner);

void gmmrrtd_settings_print_help(const char *argv0);

#endif /* GMMRRTD_SETTINGS_H */
