/*
 * model_set.h - approach models as a set of 8, one per direction the robot comes from, selected
 * by the robot's bearing theta in the person's frame (features.h: +left, 0 = in front). The
 * directions and their names are those of the UPO lab's published approach models
 * (../shared/data/real/upo_approach_gmms.json, "tasks"): 1-front (theta = 0), 2-45_right (-45 deg),
 * 3-90_right, 4-135_right, 5-back (180 deg), 6-135_left (+135 deg), 7-90_left, 8-45_left.
 * Each direction owns the 45-degree sector centred on it.
 */
#ifndef GMMRRT_MODEL_SET_H
#define GMMRRT_MODEL_SET_H

#include <stddef.h>
#include <stdint.h>

#include "gmmrrt/features.h"
#include "gmmrrt/model.h"
#include "gmmrrt/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define GMMRRT_APPROACH_DIRECTIONS 8

/* "1-front", "2-45_right", ... "8-45_left" for direction 0..7; NULL outside. */
const char *gmmrrt_approach_direction_name(int32_t direction);

/* Direction 0..7 of a robot at (x, y) (world) approaching `person`: the sector of its bearing in
 * the person's frame; -1 for NULL or non-finite input. */
int32_t gmmrrt_approach_direction(const gmmrrt_pose_t *person, double x, double y);

/* Borrowed models, one per direction (index = direction). */
typedef struct {
    const gmmrrt_model_t *model[GMMRRT_APPROACH_DIRECTIONS];
} gmmrrt_model_set_t;

/* GMMRRT_OK when every direction has a (d, theta) FEATURES model for APPROACH; else
 * GMMRRT_ERR_MODEL_MISMATCH with the first missing or unfit direction named in err[errcap]. */
gmmrrt_status_t gmmrrt_model_set_validate(const gmmrrt_model_set_t *set, char *err, size_t errcap);

/* The model of the robot's direction (NULL on bad input); *direction gets it when non-NULL. */
const gmmrrt_model_t *gmmrrt_model_set_select(const gmmrrt_model_set_t *set, const gmmrrt_pose_t *person,
                                              double x, double y, int32_t *direction);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_MODEL_SET_H */
