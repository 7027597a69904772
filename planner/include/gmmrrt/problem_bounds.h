/*
 * problem_bounds.h - the one rule that turns a scene into the planning bounds of its problem,
 * used by gmmrrtd (every cycle), gmmrrt-plan (without --bounds) and the Python tools
 * (gmmrrt_tools.core.problem_bounds).
 *
 * The bounds are the box around the start and the goal grown by margin_m on every side. People
 * and obstacles are not in the rule: those outside the box cannot touch a path inside it, and a
 * far obstacle list or a large map would otherwise grow the box, and with it the clearance grid,
 * without bound. A scene that needs a wider search area gives its bounds explicitly (gmmrrt-plan
 * --bounds; the experiments' workspace around all demonstrations).
 */
#ifndef GMMRRT_PROBLEM_BOUNDS_H
#define GMMRRT_PROBLEM_BOUNDS_H

#include "gmmrrt/collision.h"
#include "gmmrrt/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Default margin around start and goal, m: a detour of 3 m round a person or an obstacle near
 * the straight line fits (gmmrrtd's [world] bounds_margin_m, gmmrrt-plan's --bounds-margin). */
#define GMMRRT_DEFAULT_BOUNDS_MARGIN_M 3.0
/* The margins accepted, m: below 0.1 m a robot disc has no room round start or goal; above 10 km
 * the box is no longer a local planning area. */
#define GMMRRT_MIN_BOUNDS_MARGIN_M 0.1
#define GMMRRT_MAX_BOUNDS_MARGIN_M 1e4

/* The bounds of the problem from (start_x, start_y) to (goal_x, goal_y) with margin_m (in
 * [GMMRRT_MIN_BOUNDS_MARGIN_M, GMMRRT_MAX_BOUNDS_MARGIN_M]) into *out. GMMRRT_OK, or
 * GMMRRT_ERR_INVALID_ARGUMENT (out untouched) for a point that is not finite, a margin outside
 * that range (NaN included) or a NULL out. */
gmmrrt_status_t gmmrrt_problem_bounds(double start_x, double start_y, double goal_x, double goal_y, double margin_m,
                                      gmmrrt_bounds_t *out);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_PROBLEM_BOUNDS_H */
