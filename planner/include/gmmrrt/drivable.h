/*
 * drivable.h - the path a wheeled robot can drive, made from the planner's best path
 * (planner.h) after planning: shortcut without raising the planner's cost, corners rounded by
 * circular arcs of at least the minimum turning radius (yaw = the tangent everywhere), an
 * arrival on the requested heading, and the escape from a start in collision in front. Every
 * new chord is checked with the planner's own free tests (the same clearance rule as the tree's
 * edges, walking people included). Fixed memory (the caller's gmmrrt_path_t and a bounded stack
 * frame of about 97 KB), no allocation. docs/planner.md, "Drivable paths".
 */
#ifndef GMMRRT_DRIVABLE_H
#define GMMRRT_DRIVABLE_H

#include <stdint.h>

#include "gmmrrt/planner.h"
#include "gmmrrt/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Vertices of a tree path the smoother takes (the tree path, the escape and the arrival leg). */
#define GMMRRT_DRIVE_MAX_VERTICES 512

typedef enum {
    GMMRRT_ARRIVAL_ANY = 0,         /* the heading the path arrives with */
    GMMRRT_ARRIVAL_YAW = 1,         /* goal_yaw */
    GMMRRT_ARRIVAL_FACE_TARGET = 2  /* facing the approach target person (the default for approach) */
} gmmrrt_arrival_t;

typedef struct {
    double min_turn_radius_m;      /* >= 0, finite; 0: turning in place is allowed (no arcs) */
    int32_t arrival;               /* gmmrrt_arrival_t */
    double goal_yaw;               /* rad, finite, for GMMRRT_ARRIVAL_YAW */
    double goal_yaw_tolerance_rad; /* (0, pi]: the arrival heading may be off by this much */
    double arrival_leg_m;          /* > 0: shortest straight final leg on the heading */
    int32_t shortcut;              /* 1: shortcut vertices (never raising the planner's cost); 0: keep them */
} gmmrrt_drive_options_t;

/* Defaults: radius 0.3 m, arrival ANY, tolerance 15 degrees, leg 0.4 m, shortcut on. */
void gmmrrt_drive_options_default(gmmrrt_drive_options_t *opt);

typedef struct {
    gmmrrt_status_t status;     /* GMMRRT_OK; GMMRRT_ESCAPE when the path starts with the escape;
                                   else GMMRRT_TIGHT_TURNS when min_turn_radius_m > 0 and some corner
                                   is tight or turned in place */
    double arrival_yaw;         /* rad, heading at the goal */
    double arrival_error_rad;   /* |arrival_yaw - requested| (0 for ARRIVAL_ANY) */
    int32_t arrival_met;        /* 1: within goal_yaw_tolerance_rad (always 1 for ARRIVAL_ANY) */
    double max_curvature;       /* 1/m over the arcs; turns in place are counted, not in this */
    int32_t turns_in_place;     /* corners turned on the spot (radius 0, or the escape's end) */
    int32_t tight_turns;        /* corners whose arc had to be tighter than min_turn_radius_m */
    int32_t vertices_in, vertices_out; /* before and after shortcutting (arrival leg included) */
    double cost;                /* the planner's cost of the shortcut polyline (arcs not re-costed) */
    double min_walker_clearance_m; /* clearance to the walkers at each waypoint's time; +inf none */
    int32_t walker_conflict;    /* 1: some waypoint meets a walker where they are predicted then */
    int32_t side_kept;          /* 1: the path passes every person on the side the tree path does
                                   (the same swept bearing angle around each, smooth.c); the
                                   shortcut, the arrival leg and the corner cuts never change a side */
} gmmrrt_drive_report_t;

/* Fills *out with the drivable version of the planner's best path, resampled like
 * gmmrrt_planner_best_path (waypoint spacing, at most GMMRRT_MAX_WAYPOINTS), yaw = tangent. Every
 * chord between consecutive waypoints after the escape passes the planner's segment test: where
 * equally spaced ones would not, the arcs are published at their own checked chords (smooth.c).
 * report may be NULL. Statuses: GMMRRT_OK / GMMRRT_ESCAPE / GMMRRT_TIGHT_TURNS (path made; see
 * report: a path that turns tighter than min_turn_radius_m is flagged, not withheld, because a
 * stop would freeze the robot while a differential drive can slow down and turn on the spot);
 * GMMRRT_NO_PATH_YET (no path); GMMRRT_ERR_INVALID_ARGUMENT (NULL, an option out of range,
 * FACE_TARGET without an approach target); GMMRRT_ERR_BUFFER_TOO_SMALL (the tree path has more
 * than GMMRRT_DRIVE_MAX_VERTICES vertices, or the arcs' own chords exceed GMMRRT_MAX_WAYPOINTS). */
gmmrrt_status_t gmmrrt_planner_drivable_path(const gmmrrt_planner_t *p, const gmmrrt_drive_options_t *opt,
                                             gmmrrt_path_t *out, gmmrrt_drive_report_t *report);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_DRIVABLE_H */
