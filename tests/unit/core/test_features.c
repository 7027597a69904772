/* planner.features: distance and bearing in the person's frame on known geometry,
 * across the +-pi seam, and the round trip features -> xy -> features. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "gmmrrt/features.h"

static void assert_near(double a, double b, double tol)
{
    if (!(fabs(a - b) <= tol))
        fail_msg("%.15g != %.15g (tol %g)", a, b, tol);
}

static void test_robot_in_front_has_theta_zero(void **state)
{
    (void)state;
    const gmmrrt_pose_t person = {1.0, 2.0, 0.0};
    double d, th;
    gmmrrt_features_from_xy(&person, 4.0, 2.0, &d, &th);
    assert_near(d, 3.0, 1e-12);
    assert_near(th, 0.0, 1e-12);
}

static void test_left_of_person_is_positive_theta(void **state)
{
    (void)state;
    /* Person at the origin facing +y: their left is -x. */
    const gmmrrt_pose_t person = {0.0, 0.0, M_PI / 2};
    double d, th;
    gmmrrt_features_from_xy(&person, -2.0, 0.0, &d, &th);
    assert_near(d, 2.0, 1e-12);
    assert_near(th, M_PI / 2, 1e-12);
    gmmrrt_features_from_xy(&person, 2.0, 0.0, &d, &th);
    assert_near(th, -M_PI / 2, 1e-12);
}

static void test_behind_person_is_on_the_seam(void **state)
{
    (void)state;
    const gmmrrt_pose_t person = {0.0, 0.0, 0.0};
    double d, th;
    /* Exactly behind: +pi, never -pi (range is (-pi, pi]). */
    gmmrrt_features_from_xy(&person, -1.0, 0.0, &d, &th);
    assert_near(th, M_PI, 1e-15);
    /* Just left of behind and just right of behind sit on opposite ends of the range. */
    gmmrrt_features_from_xy(&person, -1.0, 1e-3, &d, &th);
    assert_true(th > M_PI - 2e-3 && th <= M_PI);
    gmmrrt_features_from_xy(&person, -1.0, -1e-3, &d, &th);
    assert_true(th < -M_PI + 2e-3 && th > -M_PI);
}

static void test_wrap_angle_range(void **state)
{
    (void)state;
    assert_near(gmmrrt_wrap_angle(-M_PI), M_PI, 1e-15);
    assert_near(gmmrrt_wrap_angle(3 * M_PI), M_PI, 1e-12);
    assert_near(gmmrrt_wrap_angle(-3 * M_PI / 2), M_PI / 2, 1e-12);
    assert_near(gmmrrt_wrap_angle(7.0), 7.0 - 2 * M_PI, 1e-12);
    assert_near(gmmrrt_wrap_angle(0.25), 0.25, 0.0);
    assert_true(isnan(gmmrrt_wrap_angle(NAN)));
    for (double a = -50.0; a < 50.0; a += 0.37) {
        const double w = gmmrrt_wrap_angle(a);
        assert_true(w > -M_PI && w <= M_PI);
        assert_near(remainder(w - a, 2 * M_PI), 0.0, 1e-9);
    }
}

static void test_features_round_trip(void **state)
{
    (void)state;
    const gmmrrt_pose_t person = {-3.5, 7.25, 2.8};
    for (double d = 0.1; d < 6.0; d += 0.7) {
        for (double th = -M_PI + 0.05; th <= M_PI; th += 0.3) {
            double x, y, d2, th2;
            gmmrrt_features_to_xy(&person, d, th, &x, &y);
            gmmrrt_features_from_xy(&person, x, y, &d2, &th2);
            assert_near(d2, d, 1e-12);
            assert_near(th2, th, 1e-12);
        }
    }
}

static void test_matches_real_data_convention(void **state)
{
    (void)state;
    /* README of the real data: x' = dx cos + dy sin, y' = -dx sin + dy cos. */
    const gmmrrt_pose_t person = {2.9645, -0.1506, -3.1312};
    const double rx = 5.0637, ry = -0.1161;
    const double dx = rx - person.x, dy = ry - person.y;
    const double xp = dx * cos(person.yaw) + dy * sin(person.yaw);
    const double yp = -dx * sin(person.yaw) + dy * cos(person.yaw);
    double d, th;
    gmmrrt_features_from_xy(&person, rx, ry, &d, &th);
    assert_near(d, hypot(xp, yp), 1e-12);
    assert_near(th, atan2(yp, xp), 1e-12);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_robot_in_front_has_theta_zero),
        cmocka_unit_test(test_left_of_person_is_positive_theta),
        cmocka_unit_test(test_behind_person_is_on_the_seam),
        cmocka_unit_test(test_wrap_angle_range),
        cmocka_unit_test(test_features_round_trip),
        cmocka_unit_test(test_matches_real_data_convention),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
