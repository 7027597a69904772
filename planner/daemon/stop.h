/*
 * stop.h - why gmmrrtd published a stop (an empty plan) without asking the planner, as the
 * code in waypoints_t.status and planner_status_t.last_error. These belong to the daemon, not
 * to the planner library: the library's own codes (gmmrrt/status.h) stay below 50, the
 * daemon's start at 50. The numbers are stable on the wire.
 */
#ifndef GMMRRTD_STOP_H
#define GMMRRTD_STOP_H

typedef enum {
    GMMRRTD_STOP_POSE_STALE = 50,      /* no robot pose newer than pose_timeout_ms */
    GMMRRTD_STOP_NO_MODEL = 51,        /* no usable model for the goal's task */
    GMMRRTD_STOP_UNKNOWN_TARGET = 52,  /* the person to approach is not among the tracked people */
    GMMRRTD_STOP_OBSTACLES_STALE = 53, /* no obstacle list newer than obstacles_timeout_ms */
    GMMRRTD_STOP_PLANNING_BOX = 54,    /* the planning box needs more cells than grid_max_cells */
    GMMRRTD_STOP_GOAL_REACHED = 55,    /* the goal was reached (published once) */
    GMMRRTD_STOP_GOAL_CANCELLED = 56,  /* the goal was cancelled (published once) */
    GMMRRTD_STOP_SCAN_STALE = 57,      /* scans seen, none newer than scan_timeout_ms (scan_stale_stop) */
    GMMRRTD_STOP_GRID_STALE = 58       /* a grid in use, none newer than grid_timeout_ms */
} gmmrrtd_stop_code_t;

/* A short static description of `code`: the daemon's own codes, else gmmrrt_status_str(). */
const char *gmmrrtd_stop_str(int code);

#endif /* GMMRRTD_STOP_H */
