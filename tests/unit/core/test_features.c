/* planner.features: distance and bearing in the person's frame on known geometry,
 * across the +-pi seam, and the round trip features -> xy -> features. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "gmmrrt/features.h"

static void assert_near(double a, double b, double tol)
{
    if (!(fabs(a - b) <= tol))
        fail_msg("%.15g != %.15g (tol %g)", a, b, tol);
}

/* The wrap's definition written plainly (fmod), as the oracle of gmmrrt_wrap_angle and of its
 * inline form, which skips fmod for |v| < 2 pi (k-means wraps one difference per point). */
static double wrap_by_fmod(double v)
{
    if (v > -M_PI && v <= M_PI)
        return v;
    double a = fmod(v + M_PI, 2.0 * M_PI);
    if (a <= 0.0)
        a += 2.0 * M_PI;
    return a - M_PI;
}

static uint64_t g_rng = 0x9E3779B97F4A7C15u;
static double uniform_angle(void)
{
    g_rng ^= g_rng << 13; /* xorshift64: any spread of angles will do */
    g_rng ^= g_rng >> 7;
    g_rng ^= g_rng << 17;
    return ((double)(g_rng >> 11) * (1.0 / 9007199254740992.0) * 2.0 - 1.0) * M_PI;
}

static void check_wrap_bits(double v, int *mismatches)
{
    const double want = wrap_by_fmod(v), got = gmmrrt_wrap_angle(v), inl = gmmrrt_wrap_angle_inline(v);
    if (memcmp(&got, &want, sizeof got) != 0 || memcmp(&inl, &want, sizeof inl) != 0)
        ++*mismatches;
}

/* Bit for bit: random differences of two wrapped angles, the edges (+-pi, +-2 pi and their
 * neighbours, values whose v + pi rounds onto 2 pi), and values outside (-2 pi, 2 pi). */
static void test_wrap_is_the_fmod_definition_bit_for_bit(void **state)
{
    (void)state;
    int mismatches = 0;
    const double fixed[] = {0.0, -0.0, M_PI, -M_PI, 2.0 * M_PI, -2.0 * M_PI, 3.0 * M_PI, -7.5, 1e6, -1e6};
    for (size_t i = 0; i < sizeof fixed / sizeof fixed[0]; ++i)
        check_wrap_bits(fixed[i], &mismatches);
    const double edges[] = {M_PI, -M_PI, 2.0 * M_PI, -2.0 * M_PI};
    for (size_t i = 0; i < 4; ++i) {
        double up = edges[i], down = edges[i];
        for (int u = 0; u < 4; ++u) {
            up = nextafter(up, HUGE_VAL);
            down = nextafter(down, -HUGE_VAL);
            check_wrap_bits(up, &mismatches);
            check_wrap_bits(down, &mismatches);
        }
    }
    for (int i = 0; i < 200000; ++i)
        check_wrap_bits(gmmrrt_wrap_angle(uniform_angle()) - gmmrrt_wrap_angle(uniform_angle()), &mismatches);
    assert_int_equal(mismatches, 0);
    assert_true(isnan(gmmrrt_wrap_angle_inline(NAN)) && isnan(gmmrrt_wrap_angle(NAN)));
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
        cmocka_unit_test(test_wrap_is_the_fmod_definition_bit_for_bit),
        cmocka_unit_test(test_robot_in_front_has_theta_zero),
        cmocka_unit_test(test_left_of_person_is_positive_theta),
        cmocka_unit_test(test_behind_person_is_on_the_seam),
        cmocka_unit_test(test_wrap_angle_range),
        cmocka_unit_test(test_features_round_trip),
        cmocka_unit_test(test_matches_real_data_convention),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
