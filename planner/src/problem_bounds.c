/*
 * problem_bounds.c - the planning bounds of a scene (problem_bounds.h): the box around start and
 * goal grown by the margin.
 */
#include "gmmrrt/problem_bounds.h"

#include <math.h>

gmmrrt_status_t gmmrrt_problem_bounds(double start_x, double start_y, double goal_x, double goal_y, double margin_m,
                                      gmmrrt_bounds_t *out)
{
    if (out == NULL || !isfinite(start_x) || !isfinite(start_y) || !isfinite(goal_x) || !isfinite(goal_y) ||
        !(margin_m >= GMMRRT_MIN_BOUNDS_MARGIN_M && margin_m <= GMMRRT_MAX_BOUNDS_MARGIN_M))
        return GMMRRT_ERR_INVALID_ARGUMENT;
    out->xmin = fmin(start_x, goal_x) - margin_m;
    out->xmax = fmax(start_x, goal_x) + margin_m;
    out->ymin = fmin(start_y, goal_y) - margin_m;
    out->ymax = fmax(start_y, goal_y) + margin_m;
    return GMMRRT_OK;
}
