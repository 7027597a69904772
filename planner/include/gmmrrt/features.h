/*
 * features.h - the paper's interaction features (Sect. 3), defined once.
 *
 * The robot's position in the person's frame, as ../shared/data/real/README.md defines it:
 *   (dx, dy) = robot - person
 *   x' =  dx cos(yaw) + dy sin(yaw)
 *   y' = -dx sin(yaw) + dy cos(yaw)
 *   d = |(x', y')| [m],  theta = atan2(y', x') [rad] in (-pi, pi]
 * theta = 0 straight in front of the person, theta > 0 on the person's left, and the
 * person's back is theta = +-pi. Models treat theta as a wrapped (circular) coordinate:
 * see gmm.h and docs/model-format.md. The learner calls these functions too.
 */
#ifndef GMMRRT_FEATURES_H
#define GMMRRT_FEATURES_H

#ifdef __cplusplus
extern "C" {
#endif

/* A planar pose: x, y in metres, yaw in radians (counter-clockwise from world x).
 * For a person, yaw is the direction they face. */
typedef struct {
    double x;
    double y;
    double yaw;
} gmmrrt_pose_t;

/* Wraps an angle to (-pi, pi]. Finite input gives finite output; NaN stays NaN. */
double gmmrrt_wrap_angle(double angle_rad);

/* Robot position (x, y) [m, world] -> features relative to `person`:
 * *d_m = distance, *theta_rad = bearing in the person's frame, in (-pi, pi].
 * At d = 0 theta is 0. */
void gmmrrt_features_from_xy(const gmmrrt_pose_t *person, double x, double y, double *d_m,
                             double *theta_rad);

/* The same with the person's cos(yaw) and sin(yaw) given, for callers that take the features
 * of many points around one person (the planner's edge quadrature): the same bits. */
void gmmrrt_features_from_xy_cs(const gmmrrt_pose_t *person, double cos_yaw, double sin_yaw, double x, double y,
                                double *d_m, double *theta_rad);

/* Inverse: features (d [m], theta [rad]) around `person` -> world position (x, y) [m].
 * Any theta is accepted (it is a direction); d < 0 mirrors through the person. */
void gmmrrt_features_to_xy(const gmmrrt_pose_t *person, double d_m, double theta_rad, double *x,
                           double *y);

/* World point -> person frame (x', y') [m], and back. */
void gmmrrt_world_to_person(const gmmrrt_pose_t *person, double x, double y, double *xp, double *yp);
void gmmrrt_person_to_world(const gmmrrt_pose_t *person, double xp, double yp, double *x, double *y);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_FEATURES_H */
