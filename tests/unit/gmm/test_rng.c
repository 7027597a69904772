/* planner.rng: the explicit random-number state (rng.h).
 * Against the reference algorithms (xoshiro256** from state {1,2,3,4}, splitmix64 from
 * 0: the published first outputs), reproducibility from a seed, and the moments of the
 * uniform and normal draws (tolerances of five standard errors; fixed seeds). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gmmrrt/rng.h"

#define N_DRAWS 1000000

static void assert_within(double value, double want, double tol, const char *what)
{
    if (!(fabs(value - want) <= tol))
        fail_msg("%s = %.10g, expected %.10g +- %.3g", what, value, want, tol);
}

static void test_xoshiro256starstar_reference_outputs(void **state)
{
    (void)state;
    /* First outputs of the reference C implementation from s = {1, 2, 3, 4}. */
    gmmrrt_rng_t rng = {{1, 2, 3, 4}, 0.0, 0};
    assert_true(gmmrrt_rng_next_u64(&rng) == 11520ull);
    assert_true(gmmrrt_rng_next_u64(&rng) == 0ull);
    assert_true(gmmrrt_rng_next_u64(&rng) == 1509978240ull);
    assert_true(gmmrrt_rng_next_u64(&rng) == 1215971899390074240ull);
}

static void test_seed_goes_through_splitmix64(void **state)
{
    (void)state;
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, 0);
    /* splitmix64's first output from state 0. */
    assert_true(rng.s[0] == 0xE220A8397B1DCDAFull);
    assert_true(rng.s[1] != 0 && rng.s[2] != 0 && rng.s[3] != 0);
}

static void test_same_seed_same_stream_other_seed_other_stream(void **state)
{
    (void)state;
    gmmrrt_rng_t a, b, c;
    gmmrrt_rng_seed(&a, 42);
    gmmrrt_rng_seed(&b, 42);
    gmmrrt_rng_seed(&c, 43);
    int same_as_other = 0;
    for (int i = 0; i < 1000; ++i) {
        const uint64_t x = gmmrrt_rng_next_u64(&a);
        assert_true(x == gmmrrt_rng_next_u64(&b));
        same_as_other += (x == gmmrrt_rng_next_u64(&c));
    }
    assert_int_equal(same_as_other, 0);
    /* Re-seeding also forgets a pending Box-Muller value. */
    gmmrrt_rng_seed(&a, 7);
    const double first = gmmrrt_rng_normal(&a);
    (void)gmmrrt_rng_normal(&b); /* b now holds a spare */
    assert_int_equal(b.has_spare_normal, 1);
    gmmrrt_rng_seed(&b, 7);
    assert_true(gmmrrt_rng_normal(&b) == first);
}

static void test_uniform_is_in_unit_interval_with_uniform_moments(void **state)
{
    (void)state;
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, 2026);
    double sum = 0.0, sum2 = 0.0;
    long bins[10] = {0};
    for (int i = 0; i < N_DRAWS; ++i) {
        const double u = gmmrrt_rng_uniform(&rng);
        assert_true(u >= 0.0 && u < 1.0);
        sum += u;
        sum2 += u * u;
        ++bins[(int)(u * 10.0)];
    }
    const double mean = sum / N_DRAWS, var = sum2 / N_DRAWS - mean * mean;
    assert_within(mean, 0.5, 5.0 * sqrt(1.0 / 12.0 / N_DRAWS), "uniform mean");
    assert_within(var, 1.0 / 12.0, 5.0 * sqrt(1.0 / 180.0 / N_DRAWS), "uniform variance");
    double chi2 = 0.0;
    for (int b = 0; b < 10; ++b)
        chi2 += ((double)bins[b] - N_DRAWS / 10.0) * ((double)bins[b] - N_DRAWS / 10.0) / (N_DRAWS / 10.0);
    if (!(chi2 < 33.7)) /* chi-square, 9 degrees of freedom, p = 1e-4 */
        fail_msg("uniform histogram chi2 = %g", chi2);
}

static void test_normal_has_standard_moments(void **state)
{
    (void)state;
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, 7);
    double s1 = 0.0, s2 = 0.0, s3 = 0.0, s4 = 0.0;
    long tail = 0;
    for (int i = 0; i < N_DRAWS; ++i) {
        const double z = gmmrrt_rng_normal(&rng);
        assert_true(isfinite(z));
        s1 += z;
        s2 += z * z;
        s3 += z * z * z;
        s4 += z * z * z * z;
        tail += fabs(z) > 1.959963984540054;
    }
    const double n = N_DRAWS;
    assert_within(s1 / n, 0.0, 5.0 / sqrt(n), "normal mean");
    assert_within(s2 / n, 1.0, 5.0 * sqrt(2.0 / n), "normal variance");
    assert_within(s3 / n, 0.0, 5.0 * sqrt(15.0 / n), "normal third moment");
    assert_within(s4 / n, 3.0, 5.0 * sqrt(96.0 / n), "normal fourth moment");
    assert_within((double)tail / n, 0.05, 5.0 * sqrt(0.05 * 0.95 / n), "P(|z| > 1.96)");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_xoshiro256starstar_reference_outputs),
        cmocka_unit_test(test_seed_goes_through_splitmix64),
        cmocka_unit_test(test_same_seed_same_stream_other_seed_other_stream),
        cmocka_unit_test(test_uniform_is_in_unit_interval_with_uniform_moments),
        cmocka_unit_test(test_normal_has_standard_moments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
