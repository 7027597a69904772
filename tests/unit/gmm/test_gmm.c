/* planner.gmm: density, log-density, task cost and sampling of the mixture (gmm.h).
 * Oracles: a closed form; a brute-force wrapped normal written here (forward substitution
 * with L, images n in -3..3 of the raw difference); the shared test vectors of
 * tests/data/model_vectors/ made with numpy/scipy; numerical quadrature (the density
 * integrates to 1); and sample moments against the model (five standard errors). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "gmmrrt/features.h"
#include "gmmrrt/gmm.h"
#include "gmm_task_cost.h" /* planner/src: the batch with a chosen vector width */
#include "../model/model_fixture.h"

static void prepare_or_fail(gmmrrt_model_t *m)
{
    char err[256];
    if (gmmrrt_model_prepare(m, err, sizeof err) != GMMRRT_OK)
        fail_msg("prepare: %s", err);
}

static void assert_rel(double got, double want, double rel, const char *what)
{
    if (!(fabs(got - want) <= rel * fmax(1.0, fabs(want))))
        fail_msg("%s: got %.17g, want %.17g (tolerance %g relative)", what, got, want, rel);
}

/* log sum_i w_i sum_n N(x_i + 2 pi n; 0, L L^T), by direct forward substitution on L (not
 * the prepared inverse), accumulated in log space. `images` = 3: x_i = f - mu_i and
 * n in -3..3 per angle dimension (closer to the exact wrapped normal than gmm.h);
 * `images` = 1: gmm.h's truncation, x_i wrapped into (-pi, pi] and n in -1..1. */
static double brute_log_density_images(const gmmrrt_model_t *m, const double *f, int images)
{
    const int d = m->dim;
    int angle[GMMRRT_MAX_DIM], na = 0;
    for (int j = 0; j < d; ++j)
        if ((m->angle_mask >> j) & 1u)
            angle[na++] = j;
    const int span = 2 * images + 1;
    int combos = 1;
    for (int a = 0; a < na; ++a)
        combos *= span;
    double terms[4096];
    int nt = 0;
    for (int i = 0; i < m->k; ++i) {
        double log_det_half = 0.0;
        for (int j = 0; j < d; ++j)
            log_det_half += log(m->chol[i][GMMRRT_TRI(j) + j]);
        for (int c = 0; c < combos; ++c) {
            double x[GMMRRT_MAX_DIM], z[GMMRRT_MAX_DIM];
            for (int j = 0; j < d; ++j)
                x[j] = f[j] - m->mean[i][j];
            int rest = c;
            for (int a = 0; a < na; ++a) {
                if (images == 1)
                    x[angle[a]] = gmmrrt_wrap_angle(x[angle[a]]);
                x[angle[a]] += 2.0 * M_PI * (rest % span - images);
                rest /= span;
            }
            double q = 0.0;
            for (int r = 0; r < d; ++r) {
                double acc = x[r];
                for (int s = 0; s < r; ++s)
                    acc -= m->chol[i][GMMRRT_TRI(r) + s] * z[s];
                z[r] = acc / m->chol[i][GMMRRT_TRI(r) + r];
                q += z[r] * z[r];
            }
            assert_true(nt < 4096);
            terms[nt++] = log(m->weight[i]) - 0.5 * d * log(2.0 * M_PI) - log_det_half - 0.5 * q;
        }
    }
    double mx = -INFINITY, s = 0.0;
    for (int t = 0; t < nt; ++t)
        mx = fmax(mx, terms[t]);
    for (int t = 0; t < nt; ++t)
        s += exp(terms[t] - mx);
    return mx + log(s);
}

static double brute_log_density(const gmmrrt_model_t *m, const double *f)
{
    return brute_log_density_images(m, f, 3);
}

/* ------------------------------------------------------------------ density */

static void test_single_gaussian_matches_closed_form(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    memset(&m, 0, sizeof m);
    m.kind = GMMRRT_MODEL_KIND_GENERIC;
    m.dim = 1;
    m.k = 1;
    m.delta = 1e-3;
    m.weight[0] = 1.0;
    m.mean[0][0] = 0.5;
    m.chol[0][0] = 2.0;
    prepare_or_fail(&m);
    for (double x = -10.0; x <= 10.0; x += 0.37) {
        const double want = -0.5 * ((x - 0.5) / 2.0) * ((x - 0.5) / 2.0) - log(2.0) - 0.5 * log(2.0 * M_PI);
        assert_rel(gmmrrt_gmm_log_density(&m, &x), want, 1e-14, "log N");
        assert_rel(gmmrrt_gmm_density(&m, &x), exp(want), 1e-14, "N");
        assert_rel(gmmrrt_gmm_component_log_density(&m, 0, &x), want, 1e-14, "component");
    }
}

static void test_features_log_density_matches_brute_force_wrapped_sum(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    fixture_features_model(&m);
    prepare_or_fail(&m);
    for (double d = 0.0; d <= 5.0; d += 0.25)
        for (double th = -M_PI + 1e-9; th <= M_PI; th += 0.13) {
            const double f[2] = {d, th};
            assert_rel(gmmrrt_gmm_log_density(&m, f), brute_log_density(&m, f), 1e-11, "log p(d, theta)");
        }
}

static void test_generic_d4_log_density_matches_brute_force(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    fixture_generic_d4_model(&m);
    prepare_or_fail(&m);
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, 11);
    for (int t = 0; t < 2000; ++t) {
        double f[4];
        for (int j = 0; j < 4; ++j)
            f[j] = 3.0 * gmmrrt_rng_normal(&rng);
        f[2] = gmmrrt_wrap_angle(f[2]);
        assert_rel(gmmrrt_gmm_log_density(&m, f), brute_log_density(&m, f), 1e-11, "log p(f), D = 4");
    }
}

/* The unrolled D = 2 path against the general path (component by component). */
static void test_2d_fast_path_agrees_with_general_path_for_every_angle_mask(void **state)
{
    (void)state;
    for (uint32_t mask = 0; mask < 4; ++mask) {
        gmmrrt_model_t m;
        fixture_features_model(&m);
        m.kind = GMMRRT_MODEL_KIND_GENERIC;
        m.angle_mask = mask;
        m.mean[0][0] = 0.5; /* an angle too when bit 0 is set */
        prepare_or_fail(&m);
        gmmrrt_rng_t rng;
        gmmrrt_rng_seed(&rng, 100 + mask);
        for (int t = 0; t < 500; ++t) {
            const double f[2] = {4.0 * gmmrrt_rng_uniform(&rng) - 1.0, 7.0 * gmmrrt_rng_uniform(&rng) - 3.5};
            double mx = -INFINITY, s = 0.0, c[3];
            for (int i = 0; i < 3; ++i) {
                c[i] = gmmrrt_gmm_component_log_density(&m, i, f);
                mx = fmax(mx, c[i]);
            }
            for (int i = 0; i < 3; ++i)
                s += exp(c[i] - mx);
            assert_rel(gmmrrt_gmm_log_density(&m, f), mx + log(s), 1e-12, "2-D path vs general");
            assert_rel(gmmrrt_gmm_log_density(&m, f), brute_log_density(&m, f), 1e-11, "2-D path vs brute");
        }
    }
}

static void test_density_is_continuous_across_the_seam(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    fixture_features_model(&m);
    prepare_or_fail(&m);
    for (double d = 0.2; d < 5.0; d += 0.1) {
        const double at_pi[2] = {d, M_PI}, just_below[2] = {d, M_PI - 1e-10},
                     just_above[2] = {d, -M_PI + 1e-10}, at_minus_pi[2] = {d, -M_PI},
                     three_pi[2] = {d, 3.0 * M_PI}, near_seam[2] = {d, M_PI - 0.01};
        const double p = gmmrrt_gmm_density(&m, at_pi);
        assert_true(p > 0.0);
        assert_rel(gmmrrt_gmm_density(&m, just_below) / p, 1.0, 1e-8, "theta -> pi from below");
        assert_rel(gmmrrt_gmm_density(&m, just_above) / p, 1.0, 1e-8, "theta -> -pi from above");
        assert_rel(gmmrrt_gmm_density(&m, at_minus_pi) / p, 1.0, 1e-12, "theta = -pi");
        assert_rel(gmmrrt_gmm_density(&m, three_pi) / p, 1.0, 1e-12, "theta = 3 pi");
        /* Component 1 straddles the seam: the density there is not small. */
        assert_true(gmmrrt_gmm_density(&m, near_seam) > 0.0);
    }
    const double f[2] = {2.5, M_PI};
    assert_true(gmmrrt_gmm_density(&m, f) > 0.05);
}

/* Quadrature over d in [0, 9] (Simpson) x theta in (-pi, pi] (rectangle rule, exact to
 * spectral accuracy for a periodic integrand). */
static double integrate_features_density(const gmmrrt_model_t *m)
{
    const int nd = 900, nt = 720;
    const double d_max = 9.0, hd = d_max / nd, ht = 2.0 * M_PI / nt;
    double total = 0.0;
    for (int a = 0; a <= nd; ++a) {
        const double w = (a == 0 || a == nd) ? 1.0 : (a % 2 ? 4.0 : 2.0);
        double row = 0.0;
        for (int b = 0; b < nt; ++b) {
            const double f[2] = {a * hd, -M_PI + (b + 1) * ht};
            row += gmmrrt_gmm_density(m, f);
        }
        total += w * row * ht;
    }
    return total * hd / 3.0;
}

static void test_density_integrates_to_one(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    fixture_features_model(&m);
    prepare_or_fail(&m);
    /* Mass below d = 0 is below 1e-6 for the fixture (means >= 5 sigma_d from 0). */
    assert_rel(integrate_features_density(&m), 1.0, 2e-6, "integral of p over d >= 0, theta");
    /* The widest angle gmm.h allows (sigma_theta = pi/2), centred on the seam. */
    fixture_features_model(&m);
    m.mean[1][1] = M_PI;
    m.chol[1][1] = 0.0;
    m.chol[1][2] = M_PI / 2;
    prepare_or_fail(&m);
    assert_rel(integrate_features_density(&m), 1.0, 1e-6, "integral with sigma_theta = pi/2");
}

static void test_far_points_keep_a_finite_log_density(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    fixture_features_model(&m);
    prepare_or_fail(&m);
    const double f[2] = {300.0, 0.3};
    const double lp = gmmrrt_gmm_log_density(&m, f);
    assert_true(isfinite(lp) && lp < -1e5);
    /* So far out, d and theta's correlation makes images beyond n = +-1 dominate: compare
     * with the truncation gmm.h documents, not with the exact wrapped normal. */
    assert_rel(lp, brute_log_density_images(&m, f, 1), 1e-12, "far log-density");
    assert_true(gmmrrt_gmm_density(&m, f) == 0.0);
    assert_true(gmmrrt_gmm_task_cost(&m, f, m.delta) == 1.0);
    assert_true(isnan(gmmrrt_gmm_component_log_density(&m, 3, f)));
}

static void test_task_cost_is_delta_over_max_p_delta(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    fixture_features_model(&m);
    prepare_or_fail(&m);
    int below = 0, above = 0;
    for (double d = 0.0; d <= 6.0; d += 0.1)
        for (double th = -M_PI + 0.05; th <= M_PI; th += 0.1) {
            const double f[2] = {d, th};
            const double p = gmmrrt_gmm_density(&m, f);
            for (int t = 0; t < 3; ++t) {
                const double delta = (t == 0) ? m.delta : (t == 1 ? 1e-6 : 0.05);
                const double c = gmmrrt_gmm_task_cost(&m, f, delta);
                assert_true(c > 0.0 && c <= 1.0);
                assert_rel(c, delta / fmax(p, delta), 1e-14, "c = delta / max(p, delta)");
                below += (p < delta);
                above += (p > delta);
            }
        }
    assert_true(below > 0 && above > 0); /* both branches were exercised */
    const double nan_f[2] = {NAN, 0.0};
    assert_true(gmmrrt_gmm_task_cost(&m, nan_f, m.delta) == 1.0);
}

/* Points for the batch tests: inside and around the fixture's mixture, far away, on the seam,
 * and non-finite ones mixed in (they cost 1 without disturbing the points sharing a vector). */
static int batch_points(double *f0, double *f1, int cap, uint64_t seed)
{
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, seed);
    int n = 0;
    while (n < cap - 8) {
        f0[n] = 6.0 * gmmrrt_rng_uniform(&rng) - 0.5;
        f1[n] = 7.0 * gmmrrt_rng_uniform(&rng) - 3.5;
        ++n;
    }
    const double extra0[8] = {300.0, 1.0, NAN, 1.0, INFINITY, 2.0, 1.5, -1e300};
    const double extra1[8] = {0.3, M_PI, 0.0, NAN, 0.0, -INFINITY, -M_PI + 1e-12, 0.0};
    for (int e = 0; e < 8; ++e, ++n) {
        f0[n] = extra0[e];
        f1[n] = extra1[e];
    }
    return n;
}

static void test_task_cost_batch_agrees_with_one_point_calls_and_the_density(void **state)
{
    (void)state;
    for (uint32_t mask = 0; mask < 4; ++mask) {
        gmmrrt_model_t m;
        fixture_features_model(&m);
        if (mask != 2u) { /* the planner's (d, theta) models have mask 2; the batch takes any 2-D one */
            m.kind = GMMRRT_MODEL_KIND_GENERIC;
            m.angle_mask = mask;
            m.mean[0][0] = 0.5;
        }
        prepare_or_fail(&m);
        double f0[200], f1[200], batch[200];
        const int n = batch_points(f0, f1, 200, 7 + mask);
        int below = 0, above = 0;
        for (int t = 0; t < 2; ++t) {
            const double delta = t == 0 ? m.delta : 1e-6;
            /* Lengths that are not multiples of the vector width, from every start. */
            for (int start = 0; start < 5; ++start) {
                const int count = n - start - (start % 3);
                gmmrrt_gmm_task_cost_batch(&m, f0 + start, f1 + start, count, delta, batch);
                for (int i = 0; i < count; ++i) {
                    const double f[2] = {f0[start + i], f1[start + i]};
                    const double one = gmmrrt_gmm_task_cost(&m, f, delta);
                    if (!(fabs(one - batch[i]) <= 1e-13 * one))
                        fail_msg("mask %u point (%g, %g): batch %.17g, one-point call %.17g", mask, f[0], f[1],
                                 batch[i], one);
                    const double p = gmmrrt_gmm_density(&m, f);
                    if (!isfinite(f[0]) || !isfinite(f[1]) || isnan(p)) {
                        assert_true(batch[i] == 1.0);
                        continue;
                    }
                    assert_rel(batch[i], delta / fmax(p, delta), 1e-13, "batch vs delta / max(p, delta)");
                    below += p < delta;
                    above += p > delta;
                }
            }
        }
        assert_true(below > 0 && above > 0);
    }
}

/* The fixture model with angle mask `mask` (2: the planner's (d, theta); others as generic). */
static void masked_fixture(gmmrrt_model_t *m, uint32_t mask)
{
    fixture_features_model(m);
    if (mask != 2u) {
        m->kind = GMMRRT_MODEL_KIND_GENERIC;
        m->angle_mask = mask;
        m->mean[0][0] = 0.5;
    }
    prepare_or_fail(m);
}

static void test_task_cost_vector_widths_give_the_same_bits(void **state)
{
    (void)state;
    for (int inward = 0; inward < 2; ++inward)
    for (uint32_t mask = 0; mask < 4; ++mask) { /* the unrolled (d, theta) branch and the generic one */
        gmmrrt_model_t m;
        masked_fixture(&m, mask);
        double f0[300], f1[300], w2[300], w4[300], wide[300];
        const int n = batch_points(f0, f1, 300, 99 + mask);
        assert_int_equal(gmmrrt_gmm_task_cost_batch_lanes(&m, f0, f1, n, m.delta, w2, 2, inward), 1);
        assert_int_equal(gmmrrt_gmm_task_cost_batch_lanes(&m, f0, f1, n, m.delta, wide, 0, inward), 1);
        assert_memory_equal(w2, wide, sizeof(double) * (size_t)n);
        assert_int_equal(gmmrrt_gmm_task_cost_batch_lanes(&m, f0, f1, n, m.delta, w2, 3, inward), 0); /* no such width */
        assert_int_equal(gmmrrt_gmm_task_cost_batch_lanes(&m, f0, f1, n, 1e-300, w2, 3, inward), 0); /* scalar path too */
        if (gmmrrt_gmm_task_cost_batch_lanes(&m, f0, f1, n, m.delta, w4, 4, inward) == 1) {
            assert_memory_equal(w2, w4, sizeof(double) * (size_t)n);
        } else if (mask == 0) {
            print_message("this CPU has no AVX2: the 4-lane kernel was not compared (the 2-lane one was)\n");
        }
    }
}

/* The inward cost (gmm.h): the batch agrees with the one-point call; it never exceeds the
 * paper's cost; it equals it at points inside every component's ridge; beyond the data, far
 * from the person at a bearing the data covers, it is below 1 where the paper's cost is 1, and
 * constant along d, and no cheaper than a component's own best point. Models other than
 * (d, theta) get the paper's cost. */
static void test_inward_task_cost_charges_only_the_fall_off_towards_the_person(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    masked_fixture(&m, 2u);
    double f0[200], f1[200], batch[200];
    const int n = batch_points(f0, f1, 200, 31);
    gmmrrt_gmm_inward_task_cost_batch(&m, f0, f1, n, m.delta, batch);
    int equal = 0, lower = 0;
    for (int i = 0; i < n; ++i) {
        const double f[2] = {f0[i], f1[i]};
        const double one = gmmrrt_gmm_inward_task_cost(&m, f, m.delta);
        if (!(fabs(one - batch[i]) <= 1e-13 * one))
            fail_msg("point (%g, %g): inward batch %.17g, one-point call %.17g", f[0], f[1], batch[i], one);
        const double paper = gmmrrt_gmm_task_cost(&m, f, m.delta);
        assert_true(one <= paper * (1.0 + 1e-13));
        int inside = 1; /* at or inside every component's ridge, for every image */
        for (int k = 0; k < m.k && isfinite(f[0]) && isfinite(f[1]); ++k) {
            const double *inv = m.inv_chol[k];
            const double ridge = -(inv[1] * inv[2]) / (inv[0] * inv[0] + inv[1] * inv[1]);
            const double y1 = remainder(gmmrrt_wrap_angle(f[1]) - m.mean[k][1], 2.0 * M_PI);
            for (int img = -1; img <= 1; ++img)
                inside &= f[0] - m.mean[k][0] <= ridge * (y1 + 2.0 * M_PI * img);
        }
        if (inside && isfinite(f[0]) && isfinite(f[1])) {
            assert_rel(one, paper, 1e-13, "inside every ridge the inward cost is the paper's");
            ++equal;
        }
        lower += one < paper * (1.0 - 1e-6);
    }
    assert_true(equal > 0 && lower > 0);
    /* Far out at the bearing of a component: the paper's cost is 1, the inward cost is not. */
    const double far[2] = {m.mean[0][0] + 50.0, m.mean[0][1]};
    assert_true(gmmrrt_gmm_task_cost(&m, far, m.delta) == 1.0);
    assert_true(gmmrrt_gmm_inward_task_cost(&m, far, m.delta) < 1.0);
    /* Far out along d at a fixed bearing, past every ridge and the mixture's own tail: the
     * cost no longer changes with d (the held terms do not depend on it). */
    for (double theta = -3.0; theta <= 3.0; theta += 0.5) {
        const double f10[2] = {10.0, theta};
        const double c10 = gmmrrt_gmm_inward_task_cost(&m, f10, m.delta);
        for (double d = 10.0; d <= 30.0; d += 0.5) {
            const double f[2] = {d, theta};
            assert_true(gmmrrt_gmm_inward_task_cost(&m, f, m.delta) == c10);
        }
    }
    /* Never below the cost at the best distance of the single strongest component at that
     * bearing: at a component's mean, far out costs at least what the mean costs. */
    for (int k = 0; k < m.k; ++k) {
        const double at[2] = {m.mean[k][0], m.mean[k][1]}, out[2] = {m.mean[k][0] + 40.0, m.mean[k][1]};
        assert_true(gmmrrt_gmm_inward_task_cost(&m, out, m.delta) >= gmmrrt_gmm_inward_task_cost(&m, at, m.delta));
    }
    /* The density batch (the background cost's p) agrees with the scalar density. */
    double dens[200];
    gmmrrt_gmm_density_batch(&m, f0, f1, n, dens);
    for (int i = 0; i < n; ++i) {
        const double f[2] = {f0[i], f1[i]};
        const double p = gmmrrt_gmm_density(&m, f);
        if (!isfinite(f[0]) || !isfinite(f[1]) || !(p > 1e-270))
            continue;
        assert_rel(dens[i], p, 1e-13, "density batch vs gmmrrt_gmm_density");
    }
    /* A generic model gets the paper's cost. */
    gmmrrt_model_t g;
    masked_fixture(&g, 0u);
    for (int i = 0; i < n; ++i) {
        const double f[2] = {f0[i], f1[i]};
        const double a = gmmrrt_gmm_inward_task_cost(&g, f, g.delta), b = gmmrrt_gmm_task_cost(&g, f, g.delta);
        assert_true(a == b || (isnan(a) && isnan(b)));
    }
}

/* The kernel returns 1 without the sum where n e^max <= delta for every lane (n terms, each at
 * most e^max). Where the largest term is below delta but the mixture is above it (several
 * components add up), the cost must still be delta / p < 1: an exit on e^max <= delta alone
 * would give 1 there. */
static void test_task_cost_early_exit_needs_every_term(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    masked_fixture(&m, 2u);
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, 21);
    int checked = 0;
    for (int t = 0; t < 4000 && checked < 50; ++t) {
        const double f[2] = {6.0 * gmmrrt_rng_uniform(&rng) - 0.5, 7.0 * gmmrrt_rng_uniform(&rng) - 3.5};
        const double p = gmmrrt_gmm_density(&m, f);
        double top = 0.0; /* the largest component (all its images): at least the largest term */
        for (int i = 0; i < m.k; ++i)
            top = fmax(top, exp(gmmrrt_gmm_component_log_density(&m, i, f)));
        if (!(p > 0.0) || !(top < 0.85 * p))
            continue;
        const double delta = 0.9 * p; /* above every term, below p */
        double c[4], fd[4] = {f[0], f[0], f[0], f[0]}, ft[4] = {f[1], f[1], f[1], f[1]};
        for (int lanes = 2; lanes <= 4; lanes += 2) {
            if (gmmrrt_gmm_task_cost_batch_lanes(&m, fd, ft, 4, delta, c, lanes, 0) == 0)
                continue; /* no AVX2 here */
            for (int q = 0; q < 4; ++q)
                assert_rel(c[q], 0.9, 1e-12, "cost where every term is below delta but p is not");
        }
        ++checked;
    }
    assert_true(checked >= 10); /* such points exist in the fixture (components overlap) */
}

/* A point whose density is below the kernel's floor (e^-700) but above delta = 1e-320 must get
 * delta / p (the scalar path), not the 1 the kernel's floor would give. The point is found by
 * bisection on d for log p = -720 (a double holds down to about e^-744). */
static void test_task_cost_below_the_kernel_floor_uses_the_exact_density(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    masked_fixture(&m, 2u);
    const double theta = 0.3;
    double lo = 2.0, hi = 200.0; /* log p(lo) > -720 > log p(hi), decreasing beyond the data */
    for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi), f[2] = {mid, theta};
        if (gmmrrt_gmm_log_density(&m, f) > -720.0)
            lo = mid;
        else
            hi = mid;
    }
    const double d[3] = {lo, lo, 1.0}, th[3] = {theta, theta, theta};
    const double f[2] = {lo, theta};
    const double lp = gmmrrt_gmm_log_density(&m, f);
    if (!(lp < -710.0 && lp > -730.0))
        fail_msg("set-up: log p = %g at d = %g, wanted about -720", lp, lo);
    const double delta = 1e-320, p = gmmrrt_gmm_density(&m, f);
    double c[3];
    gmmrrt_gmm_task_cost_batch(&m, d, th, 3, delta, c);
    assert_true(c[0] < 1e-5 && c[0] == delta / p); /* about 5e-8 */
    assert_true(c[1] == c[0]);
    const double near[2] = {1.0, theta};
    assert_true(c[2] == delta / gmmrrt_gmm_density(&m, near));
}

static void test_nan_features_give_nan_log_density_in_every_path(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    fixture_features_model(&m);
    prepare_or_fail(&m);
    const double nan_d[2] = {NAN, 0.5}, nan_theta[2] = {1.0, NAN};
    assert_true(isnan(gmmrrt_gmm_log_density(&m, nan_d)));
    assert_true(isnan(gmmrrt_gmm_log_density(&m, nan_theta)));
    assert_true(isnan(gmmrrt_gmm_component_log_density(&m, 1, nan_theta)));
    fixture_generic_d4_model(&m);
    prepare_or_fail(&m);
    for (int j = 0; j < 4; ++j) {
        double f[4] = {0.0, 1.0, 3.0, 2.0};
        f[j] = NAN;
        assert_true(isnan(gmmrrt_gmm_log_density(&m, f)));
        assert_true(gmmrrt_gmm_task_cost(&m, f, m.delta) == 1.0);
    }
}

/* ------------------------------------------------------------------ shared vectors */

static void check_vector_file(const char *name)
{
    const char *dir = getenv("GMMRRT_TEST_DATA_DIR");
    if (dir == NULL)
        fail_msg("GMMRRT_TEST_DATA_DIR is not set (run through ctest)");
    char path[1024];
    snprintf(path, sizeof path, "%s/model_vectors/%s.gmm", dir, name);
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        fail_msg("cannot open %s", path);
    static uint8_t buf[1 << 16];
    const size_t len = fread(buf, 1, sizeof buf, fp);
    fclose(fp);
    static gmmrrt_model_t m;
    char err[256];
    if (gmmrrt_model_decode(buf, len, &m, err, sizeof err) != GMMRRT_OK)
        fail_msg("%s: %s", path, err);

    snprintf(path, sizeof path, "%s/model_vectors/%s.csv", dir, name);
    fp = fopen(path, "r");
    if (fp == NULL)
        fail_msg("cannot open %s", path);
    char line[4096];
    assert_non_null(fgets(line, sizeof line, fp)); /* header */
    int rows = 0, seam_rows = 0;
    double worst = 0.0;
    while (fgets(line, sizeof line, fp) != NULL) {
        double v[GMMRRT_MAX_DIM + 1];
        char *p = line, *end;
        for (int j = 0; j <= m.dim; ++j) {
            v[j] = strtod(p, &end);
            if (end == p)
                fail_msg("%s:%d: bad number", path, rows + 2);
            p = end + 1;
        }
        const double got = gmmrrt_gmm_log_density(&m, v), want = v[m.dim];
        const double rel = fabs(got - want) / fmax(1.0, fabs(want));
        worst = fmax(worst, rel);
        if (!(rel <= 1e-9))
            fail_msg("%s:%d: log p = %.17g, expected %.17g", path, rows + 2, got, want);
        for (int j = 0; j < m.dim; ++j)
            seam_rows += ((m.angle_mask >> j) & 1u) && fabs(v[j]) > M_PI - 1e-6;
        ++rows;
    }
    fclose(fp);
    assert_true(rows >= 100);
    if (m.angle_mask != 0)
        assert_true(seam_rows > 0);
    print_message("%s: %d points, worst relative error %.2g\n", name, rows, worst);
}

static void test_shared_vectors_features_seam(void **state)
{
    (void)state;
    check_vector_file("features_seam");
}

static void test_shared_vectors_xy(void **state)
{
    (void)state;
    check_vector_file("xy");
}

static void test_shared_vectors_generic_d4(void **state)
{
    (void)state;
    check_vector_file("generic_d4");
}

/* ------------------------------------------------------------------ sampling */

#define N_SAMPLES 200000

/* Mean and covariance of component i's samples (angle coordinates as wrapped differences
 * from the mean) against mu_i and L L^T, within five standard errors. */
static void check_component_moments(const gmmrrt_model_t *m, int i, uint64_t seed)
{
    const int d = m->dim;
    double sigma[GMMRRT_MAX_DIM][GMMRRT_MAX_DIM] = {{0}};
    for (int r = 0; r < d; ++r)
        for (int c = 0; c < d; ++c)
            for (int s = 0; s <= (r < c ? r : c); ++s)
                sigma[r][c] += m->chol[i][GMMRRT_TRI(r) + s] * m->chol[i][GMMRRT_TRI(c) + s];
    double s1[GMMRRT_MAX_DIM] = {0}, s2[GMMRRT_MAX_DIM][GMMRRT_MAX_DIM] = {{0}};
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, seed);
    for (int n = 0; n < N_SAMPLES; ++n) {
        double f[GMMRRT_MAX_DIM], e[GMMRRT_MAX_DIM];
        gmmrrt_gmm_sample_component(m, i, &rng, f);
        for (int j = 0; j < d; ++j) {
            const int is_angle = (m->angle_mask >> j) & 1u;
            if (is_angle && !(f[j] > -M_PI && f[j] <= M_PI))
                fail_msg("sample angle %g outside (-pi, pi]", f[j]);
            e[j] = is_angle ? gmmrrt_wrap_angle(f[j] - m->mean[i][j]) : f[j] - m->mean[i][j];
            s1[j] += e[j];
        }
        for (int r = 0; r < d; ++r)
            for (int c = 0; c < d; ++c)
                s2[r][c] += e[r] * e[c];
    }
    for (int r = 0; r < d; ++r) {
        const double mean = s1[r] / N_SAMPLES;
        if (!(fabs(mean) <= 5.0 * sqrt(sigma[r][r] / N_SAMPLES)))
            fail_msg("component %d: mean[%d] off by %g", i, r, mean);
        for (int c = 0; c < d; ++c) {
            const double cov = s2[r][c] / N_SAMPLES - mean * s1[c] / N_SAMPLES;
            const double se = sqrt((sigma[r][r] * sigma[c][c] + sigma[r][c] * sigma[r][c]) / N_SAMPLES);
            if (!(fabs(cov - sigma[r][c]) <= 5.0 * se))
                fail_msg("component %d: cov[%d][%d] = %g, model %g", i, r, c, cov, sigma[r][c]);
        }
    }
}

static void test_component_samples_match_mean_and_covariance(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    fixture_features_model(&m);
    prepare_or_fail(&m);
    for (int i = 0; i < m.k; ++i)
        check_component_moments(&m, i, 500 + (uint64_t)i);
    fixture_generic_d4_model(&m);
    prepare_or_fail(&m);
    for (int i = 0; i < m.k; ++i)
        check_component_moments(&m, i, 600 + (uint64_t)i);
}

/* A wide component on the seam: circular moments of the wrapped normal,
 * E[cos theta] = cos(mu) exp(-sigma^2 / 2), E[sin theta] = sin(mu) exp(-sigma^2 / 2). */
static void test_seam_samples_are_wrapped_with_circular_moments(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    fixture_features_model(&m);
    m.mean[1][1] = M_PI - 0.1;
    m.chol[1][1] = 0.0;
    m.chol[1][2] = 1.0; /* sigma_theta = 1 */
    prepare_or_fail(&m);
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, 99);
    double sc = 0.0, ss = 0.0;
    long pos = 0, neg = 0;
    for (int n = 0; n < N_SAMPLES; ++n) {
        double f[2];
        gmmrrt_gmm_sample_component(&m, 1, &rng, f);
        assert_true(f[1] > -M_PI && f[1] <= M_PI);
        sc += cos(f[1]);
        ss += sin(f[1]);
        pos += f[1] > 2.0;
        neg += f[1] < -2.0;
    }
    const double shrink = exp(-0.5);
    const double tol = 5.0 * sqrt(0.5 / N_SAMPLES); /* var(cos), var(sin) <= 1/2 here */
    if (!(fabs(sc / N_SAMPLES - cos(m.mean[1][1]) * shrink) <= tol))
        fail_msg("E[cos theta] = %g, want %g", sc / N_SAMPLES, cos(m.mean[1][1]) * shrink);
    if (!(fabs(ss / N_SAMPLES - sin(m.mean[1][1]) * shrink) <= tol))
        fail_msg("E[sin theta] = %g, want %g", ss / N_SAMPLES, sin(m.mean[1][1]) * shrink);
    assert_true(pos > N_SAMPLES / 10 && neg > N_SAMPLES / 10); /* both sides of the seam */
}

static void test_mixture_samples_pick_components_by_weight(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    fixture_features_model(&m);
    prepare_or_fail(&m);
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, 5);
    long count[3] = {0};
    for (int n = 0; n < N_SAMPLES; ++n) {
        double f[2];
        const int32_t i = gmmrrt_gmm_sample(&m, &rng, f);
        assert_true(i >= 0 && i < 3);
        ++count[i];
        assert_true(isfinite(f[0]) && f[1] > -M_PI && f[1] <= M_PI);
    }
    for (int i = 0; i < 3; ++i) {
        const double w = m.weight[i], frac = (double)count[i] / N_SAMPLES;
        if (!(fabs(frac - w) <= 5.0 * sqrt(w * (1.0 - w) / N_SAMPLES)))
            fail_msg("component %d drawn %.4f of the time, weight %.4f", i, frac, w);
    }
}

static void test_same_seed_same_samples(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    fixture_generic_d4_model(&m);
    prepare_or_fail(&m);
    gmmrrt_rng_t a, b, c;
    gmmrrt_rng_seed(&a, 31337);
    gmmrrt_rng_seed(&b, 31337);
    gmmrrt_rng_seed(&c, 31338);
    int differ = 0;
    for (int n = 0; n < 1000; ++n) {
        double fa[4], fb[4], fc[4];
        const int32_t ia = gmmrrt_gmm_sample(&m, &a, fa), ib = gmmrrt_gmm_sample(&m, &b, fb);
        (void)gmmrrt_gmm_sample(&m, &c, fc);
        assert_int_equal(ia, ib);
        assert_memory_equal(fa, fb, sizeof fa);
        differ += memcmp(fa, fc, sizeof fa) != 0;
    }
    assert_true(differ > 990);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_single_gaussian_matches_closed_form),
        cmocka_unit_test(test_features_log_density_matches_brute_force_wrapped_sum),
        cmocka_unit_test(test_generic_d4_log_density_matches_brute_force),
        cmocka_unit_test(test_2d_fast_path_agrees_with_general_path_for_every_angle_mask),
        cmocka_unit_test(test_density_is_continuous_across_the_seam),
        cmocka_unit_test(test_density_integrates_to_one),
        cmocka_unit_test(test_far_points_keep_a_finite_log_density),
        cmocka_unit_test(test_task_cost_is_delta_over_max_p_delta),
        cmocka_unit_test(test_task_cost_batch_agrees_with_one_point_calls_and_the_density),
        cmocka_unit_test(test_task_cost_vector_widths_give_the_same_bits),
        cmocka_unit_test(test_task_cost_early_exit_needs_every_term),
        cmocka_unit_test(test_task_cost_below_the_kernel_floor_uses_the_exact_density),
        cmocka_unit_test(test_nan_features_give_nan_log_density_in_every_path),
        cmocka_unit_test(test_shared_vectors_features_seam),
        cmocka_unit_test(test_shared_vectors_xy),
        cmocka_unit_test(test_shared_vectors_generic_d4),
        cmocka_unit_test(test_inward_task_cost_charges_only_the_fall_off_towards_the_person),
        cmocka_unit_test(test_component_samples_match_mean_and_covariance),
        cmocka_unit_test(test_seam_samples_are_wrapped_with_circular_moments),
        cmocka_unit_test(test_mixture_samples_pick_components_by_weight),
        cmocka_unit_test(test_same_seed_same_samples),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
