/*
 * features.c - distance and bearing of the robot in the person's frame (paper Sect. 3;
 * conventions of ../shared/data/real/README.md). See features.h.
 */
#include "gmmrrt/features.h"

#include <math.h>

double gmmrrt_wrap_angle(double angle_rad)
{
    if (angle_rad > -2.0 * M_PI && angle_rad < 2.0 * M_PI)
        return gmmrrt_wrap_angle_inline(angle_rad);
    double a = fmod(angle_rad + M_PI, 2.0 * M_PI); /* (-2pi, 2pi); NaN stays NaN */
    if (a <= 0.0)
        a += 2.0 * M_PI; /* (0, 2pi] */
    return a - M_PI;     /* (-pi, pi] */
}

/* World point -> person frame with the yaw's cos c and sin s given. */
static void to_person_cs(const gmmrrt_pose_t *person, double c, double s, double x, double y, double *xp, double *yp)
{
    const double dx = x - person->x, dy = y - person->y;
    *xp = dx * c + dy * s;
    *yp = -dx * s + dy * c;
}

void gmmrrt_world_to_person(const gmmrrt_pose_t *person, double x, double y, double *xp, double *yp)
{
    to_person_cs(person, cos(person->yaw), sin(person->yaw), x, y, xp, yp);
}

void gmmrrt_person_to_world(const gmmrrt_pose_t *person, double xp, double yp, double *x, double *y)
{
    const double c = cos(person->yaw), s = sin(person->yaw);
    *x = person->x + xp * c - yp * s;
    *y = person->y + xp * s + yp * c;
}

void gmmrrt_features_from_xy(const gmmrrt_pose_t *person, double x, double y, double *d_m, double *theta_rad)
{
    gmmrrt_features_from_xy_cs(person, cos(person->yaw), sin(person->yaw), x, y, d_m, theta_rad);
}

void gmmrrt_features_from_xy_cs(const gmmrrt_pose_t *person, double cos_yaw, double sin_yaw, double x, double y,
                                double *d_m, double *theta_rad)
{
    double xp, yp;
    to_person_cs(person, cos_yaw, sin_yaw, x, y, &xp, &yp);
    /* plain sqrt on map-sized numbers (hypot is several times slower); hypot where x'^2 could overflow */
    *d_m = (fabs(xp) < 1e150 && fabs(yp) < 1e150) ? sqrt(xp * xp + yp * yp) : hypot(xp, yp);
    /* atan2 gives [-pi, pi]; -pi (exactly behind, y' = -0) is folded onto +pi. */
    *theta_rad = (*d_m > 0.0) ? gmmrrt_wrap_angle(atan2(yp, xp)) : 0.0;
}

void gmmrrt_features_to_xy(const gmmrrt_pose_t *person, double d_m, double theta_rad, double *x, double *y)
{
    gmmrrt_person_to_world(person, d_m * cos(theta_rad), d_m * sin(theta_rad), x, y);
}
