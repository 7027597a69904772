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

/* gmmrrt_wrap_angle, inline for loops that wrap one angle difference per point (the learner's
 * k-means): the same bits for every input. The wrap is
 *   a = fmod(angle + pi, 2 pi); a <= 0 ? a + 2 pi : a; minus pi.
 * For |angle| < 2 pi, angle + pi lies in (-pi, 3 pi) and fmod subtracts 2 pi at most once,
 * exactly (Sterbenz's lemma): that case is written out here; the library function does the
 * rest (and calls this for |angle| < 2 pi, so the two cannot disagree). */
static inline double gmmrrt_wrap_angle_inline(double angle_rad)
{
    const double pi = 3.14159265358979323846, two_pi = 2.0 * pi;
    if (angle_rad > -pi && angle_rad <= pi)
        return angle_rad;
    if (!(angle_rad > -two_pi && angle_rad < two_pi))
        return gmmrrt_wrap_angle(angle_rad); /* far from the range, or NaN */
    double a = angle_rad + pi;               /* (-pi, 3 pi) */
    if (a >= two_pi)
        a -= two_pi;
    if (a <= 0.0)
        a += two_pi; /* (0, 2 pi] */
    return a - pi;   /* (-pi, pi] */
}

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
