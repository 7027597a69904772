/* path_side.c - the side a path goes round a person (paper Sect. 2 homotopy classes); contracts
 * in gmmrrt/path_side.h. */
#include "gmmrrt/path_side.h"

#include <math.h>

double gmmrrt_path_swept_angle(const gmmrrt_pose_t *person, const double *xy, size_t n)
{
    double swept = 0.0;
    if (n < 2)
        return 0.0;
    double prev = atan2(xy[1] - person->y, xy[0] - person->x);
    for (size_t i = 1; i < n; ++i) {
        const double b = atan2(xy[2 * i + 1] - person->y, xy[2 * i] - person->x);
        swept += gmmrrt_wrap_angle(b - prev);
        prev = b;
    }
    return swept;
}

int gmmrrt_path_passing_side(const gmmrrt_pose_t *person, const double *xy, size_t n)
{
    if (n == 0)
        return 0;
    size_t best = 0;
    double best_d = INFINITY;
    for (size_t i = 0; i < n; ++i) {
        const double d = hypot(xy[2 * i] - person->x, xy[2 * i + 1] - person->y);
        if (d < best_d) {
            best_d = d;
            best = i;
        }
    }
    double d_m, theta_rad;
    gmmrrt_features_from_xy(person, xy[2 * best], xy[2 * best + 1], &d_m, &theta_rad);
    return theta_rad > 0.0 ? 1 : -1;
}
