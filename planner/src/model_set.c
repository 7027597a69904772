/* model_set.c - approach model sets by direction (model_set.h). */
#include "gmmrrt/model_set.h"

#include <math.h>

#include "error_text.h"

static const char *const names[GMMRRT_APPROACH_DIRECTIONS] = {
    "1-front", "2-45_right", "3-90_right", "4-135_right", "5-back", "6-135_left", "7-90_left", "8-45_left"};

const char *gmmrrt_approach_direction_name(int32_t direction)
{
    return direction >= 0 && direction < GMMRRT_APPROACH_DIRECTIONS ? names[direction] : NULL;
}

int32_t gmmrrt_approach_direction(const gmmrrt_pose_t *person, double x, double y)
{
    if (!person || !isfinite(person->x) || !isfinite(person->y) || !isfinite(person->yaw) || !isfinite(x) ||
        !isfinite(y))
        return -1;
    double d, theta;
    gmmrrt_features_from_xy(person, x, y, &d, &theta);
    /* Directions run clockwise (towards the right, theta < 0) from the front in 45-degree steps. */
    const long k = lround(-theta / (M_PI / 4.0));
    return (int32_t)(((k % 8) + 8) % 8);
}

gmmrrt_status_t gmmrrt_model_set_validate(const gmmrrt_model_set_t *set, char *err, size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (!set)
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "model set is NULL");
    for (int32_t i = 0; i < GMMRRT_APPROACH_DIRECTIONS; ++i) {
        const gmmrrt_model_t *m = set->model[i];
        if (!m)
            return gmmrrt_set_error(GMMRRT_ERR_MODEL_MISMATCH, err, errcap, "approach direction %s has no model",
                                    names[i]);
        if (m->kind != GMMRRT_MODEL_KIND_FEATURES || m->dim != 2 || m->task != GMMRRT_TASK_APPROACH)
            return gmmrrt_set_error(GMMRRT_ERR_MODEL_MISMATCH, err, errcap,
                                    "approach direction %s: not a (d, theta) approach model", names[i]);
    }
    return GMMRRT_OK;
}

const gmmrrt_model_t *gmmrrt_model_set_select(const gmmrrt_model_set_t *set, const gmmrrt_pose_t *person,
                                              double x, double y, int32_t *direction)
{
    const int32_t k = set ? gmmrrt_approach_direction(person, x, y) : -1;
    if (direction)
        *direction = k;
    return k >= 0 ? set->model[k] : NULL;
}
