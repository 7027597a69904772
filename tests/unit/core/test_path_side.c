/*
 * test_path_side.c - planner.path_side: gmmrrt_path_swept_angle and gmmrrt_path_passing_side
 * (gmmrrt/path_side.h), the homotopy labels of the learner's segmenter and the Python metrics.
 * Cases with known answers: a straight pass on either side of a person facing +x sweeps -pi / +pi
 * (exactly in the limit; 2 atan(5) short of it for a 10 m line at 1 m), a closed loop round the
 * person sweeps 2 pi, an out-and-back detour 0 and a far path the change of its bearing, the side follows the person's
 * facing (a person facing -x sees the same path on the other side), and empty / one-point paths.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "gmmrrt/path_side.h"

static const double kPi = 3.14159265358979323846;

static void test_a_straight_pass_sweeps_the_angle_of_its_ends(void **state)
{
    (void)state;
    const gmmrrt_pose_t person = {0.0, 0.0, 0.0};
    double above[2 * 101], below[2 * 101];
    for (int i = 0; i <= 100; ++i) {
        const double x = -5.0 + 0.1 * i;
        above[2 * i] = below[2 * i] = x;
        above[2 * i + 1] = 1.0;
        below[2 * i + 1] = -1.0;
    }
    /* From bearing atan2(1, -5) to atan2(1, 5), clockwise: -(pi - 2 atan(1/5)). */
    const double want = -(kPi - 2.0 * atan(0.2));
    assert_true(fabs(gmmrrt_path_swept_angle(&person, above, 101) - want) < 1e-12);
    assert_true(fabs(gmmrrt_path_swept_angle(&person, below, 101) + want) < 1e-12);
    /* Facing +x, y > 0 is the person's left. */
    assert_int_equal(gmmrrt_path_passing_side(&person, above, 101), 1);
    assert_int_equal(gmmrrt_path_passing_side(&person, below, 101), -1);
    /* Facing -x, the same path is on their right; the swept angle does not depend on the facing. */
    const gmmrrt_pose_t turned = {0.0, 0.0, kPi};
    assert_int_equal(gmmrrt_path_passing_side(&turned, above, 101), -1);
    assert_true(fabs(gmmrrt_path_swept_angle(&turned, above, 101) - want) < 1e-12);
}

static void test_a_loop_sweeps_two_pi_and_a_detour_nothing(void **state)
{
    (void)state;
    const gmmrrt_pose_t person = {2.0, -1.0, 0.3};
    double loop[2 * 37], away[2 * 3];
    for (int i = 0; i <= 36; ++i) {
        loop[2 * i] = person.x + 1.5 * cos(2.0 * kPi * i / 36);
        loop[2 * i + 1] = person.y + 1.5 * sin(2.0 * kPi * i / 36);
    }
    assert_true(fabs(gmmrrt_path_swept_angle(&person, loop, 37) - 2.0 * kPi) < 1e-12);
    /* Out and back on one side: the bearing returns, the sum is 0 up to rounding. */
    const double out_back[] = {person.x + 3.0, person.y, person.x + 3.0, person.y + 2.0, person.x + 3.0, person.y};
    assert_true(fabs(gmmrrt_path_swept_angle(&person, out_back, 3)) < 1e-15);
    away[0] = 10.0, away[1] = 10.0, away[2] = 11.0, away[3] = 10.0, away[4] = 12.0, away[5] = 10.0;
    /* Far away: the bearing's change from the first point to the last. */
    const double far_want = atan2(11.0, 10.0) - atan2(11.0, 8.0);
    assert_true(fabs(gmmrrt_path_swept_angle(&person, away, 3) - far_want) < 1e-15);
}

static void test_the_side_is_taken_at_the_closest_point(void **state)
{
    (void)state;
    const gmmrrt_pose_t person = {0.0, 0.0, 0.0};
    /* Far on the left, then close on the right: the right counts; a tie keeps the first point. */
    const double path[] = {-1.0, 5.0, 0.0, -0.5, 1.0, 5.0};
    assert_int_equal(gmmrrt_path_passing_side(&person, path, 3), -1);
    const double tie[] = {0.0, 1.0, 0.0, -1.0};
    assert_int_equal(gmmrrt_path_passing_side(&person, tie, 2), 1);
}

static void test_empty_and_single_point_paths(void **state)
{
    (void)state;
    const gmmrrt_pose_t person = {0.0, 0.0, 0.0};
    const double one[] = {1.0, 1.0};
    assert_true(gmmrrt_path_swept_angle(&person, one, 0) == 0.0);
    assert_true(gmmrrt_path_swept_angle(&person, one, 1) == 0.0);
    assert_int_equal(gmmrrt_path_passing_side(&person, one, 0), 0);
    assert_int_equal(gmmrrt_path_passing_side(&person, one, 1), 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_straight_pass_sweeps_the_angle_of_its_ends),
        cmocka_unit_test(test_a_loop_sweeps_two_pi_and_a_detour_nothing),
        cmocka_unit_test(test_the_side_is_taken_at_the_closest_point),
        cmocka_unit_test(test_empty_and_single_point_paths),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
