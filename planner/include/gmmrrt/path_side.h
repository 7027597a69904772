/*
 * path_side.h - which way a path goes round a person: the homotopy class of a demonstration or a
 * plan (paper Sect. 2: avoiding on the person's left or right; Sect. 5.1: the demonstrations are
 * labelled by it). Defined once: the learner's segmenter labels raw recordings with these, and the
 * Python metrics call them through the core's binding.
 *
 * A path is n points (x, y) [m, world], interleaved: xy[2 i], xy[2 i + 1].
 */
#ifndef GMMRRT_PATH_SIDE_H
#define GMMRRT_PATH_SIDE_H

#include <stddef.h>

#include "gmmrrt/features.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Signed angle [rad] swept by the bearing from the person to the path point along the path,
 * counter-clockwise positive: the sum of the wrapped (gmmrrt_wrap_angle) bearing changes between
 * consecutive points, in order. Going once round the person's left is about +pi, round the right
 * about -pi; two paths between the same start and goal pass on the same side iff their swept
 * angles differ by less than pi. 0 for n < 2. A point on the person adds bearing 0. */
double gmmrrt_path_swept_angle(const gmmrrt_pose_t *person, const double *xy, size_t n);

/* The side of the person the path passes, judged at its point closest to the person (the first
 * such point on ties): +1 when that point's theta (gmmrrt_features_from_xy) is > 0, the person's
 * left as ../shared/data/real/README.md defines homotopy; -1 otherwise (right); 0 for n == 0. */
int gmmrrt_path_passing_side(const gmmrrt_pose_t *person, const double *xy, size_t n);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_PATH_SIDE_H */
