/*
 * gmm.c - density, log-density, task cost and sampling of a Gaussian mixture (gmm.h):
 * paper eq. 1 (the mixture) and Sect. 4 (the task cost c(f) = delta / max(p(f), delta)).
 *
 * Angle dimensions (model->angle_mask) use the wrapped normal of gmm.h: the difference
 * f_j - mu_j is first wrapped into (-pi, pi], then the images n in {-1, 0, 1} (times 2 pi)
 * of every angle dimension are summed. All component-image terms are combined by
 * log-sum-exp, so nothing underflows before the sum (far from the data log p stays
 * finite); a term more than LSE_CUTOFF below the maximum adds less than e^-40 (4e-18)
 * relative and its exp() is skipped, which is what makes the hot path cheap.
 *
 * D = 2 (the paper's (d, theta) features) has its own log-density path: all 3K exponents
 * first (plain arithmetic, no libm calls), then exp() only for the terms near the maximum;
 * tests/bench/gmm measures it. This is the one-point task cost (OMPL's state cost in the
 * benchmark calls it); the planner's quadrature uses the batch of gmm_task_cost.c, which
 * agrees with it to about 1e-14. Other D use a streaming log-sum-exp per component and
 * image. Nothing here allocates or does I/O; the model must be prepared
 * (gmmrrt_model_prepare). NaN features give a NaN log-density (task cost 1).
 */
#include "gmmrrt/gmm.h"

#include <assert.h>
#include <math.h>

#include "gmmrrt/features.h"

#define TWO_PI (2.0 * M_PI)
#define LSE_CUTOFF 40.0

/* Streaming log-sum-exp: value = max + log(sum). Callers keep NaN out. */
typedef struct {
    double max;
    double sum;
} lse_t;

static inline void lse_add(lse_t *acc, double x)
{
    if (x <= acc->max) {
        if (x > acc->max - LSE_CUTOFF)
            acc->sum += exp(x - acc->max);
    } else { /* new maximum (or NaN, which then propagates) */
        acc->sum = (acc->max > x - LSE_CUTOFF) ? acc->sum * exp(acc->max - x) + 1.0 : 1.0;
        acc->max = x;
    }
}

static inline double lse_value(const lse_t *acc)
{
    return (acc->max == -INFINITY) ? -INFINITY : acc->max + log(acc->sum);
}

/* max without fmax(): a libm call unless fast-math; inputs here are never NaN. */
static inline double max2(double a, double b)
{
    return a > b ? a : b;
}

/* f_j - mu_j into (-pi, pi] for f_j already in (-pi, pi] and mu_j in [-pi, pi]. */
static inline double wrap_diff(double d)
{
    if (d > M_PI)
        return d - TWO_PI;
    if (d <= -M_PI)
        return d + TWO_PI;
    return d;
}

/* ------------------------------------------------------------------ D = 2 */

/* Exponents log w_i - q/2 of every component and image at f = (f0, f1) (angles already
 * wrapped into (-pi, pi]) into x[], returning their count; *max_out gets the largest.
 * Branch-light arithmetic only: the exp() calls happen in one later pass, and only for
 * terms within LSE_CUTOFF of the final maximum. */
static int terms_2d(const gmmrrt_model_t *m, double f0, double f1, double *x, double *max_out)
{
    const unsigned a0 = m->angle_mask & 1u, a1 = (m->angle_mask >> 1) & 1u;
    const int32_t k = m->k;
    double mx = -INFINITY;
    int n = 0;
    if (!a0 && a1) { /* the paper's features: d linear, theta an angle */
        for (int32_t i = 0; i < k; ++i) {
            const double *inv = m->inv_chol[i];
            const double c = m->log_coef[i];
            const double d0 = f0 - m->mean[i][0];
            const double d1 = wrap_diff(f1 - m->mean[i][1]);
            const double z0 = inv[0] * d0;
            const double z1 = inv[1] * d0 + inv[2] * d1, step = inv[2] * TWO_PI;
            const double base = c - 0.5 * z0 * z0;
            const double zm = z1 - step, zp = z1 + step;
            const double x0 = base - 0.5 * z1 * z1, xm = base - 0.5 * zm * zm, xp = base - 0.5 * zp * zp;
            x[n] = x0;
            x[n + 1] = xm;
            x[n + 2] = xp;
            n += 3;
            mx = max2(mx, max2(x0, max2(xm, xp)));
        }
        *max_out = mx;
        return n;
    }
    const int n0 = a0 ? 1 : 0, n1 = a1 ? 1 : 0;
    for (int32_t i = 0; i < k; ++i) {
        const double *inv = m->inv_chol[i];
        const double c = m->log_coef[i];
        double d0 = f0 - m->mean[i][0], d1 = f1 - m->mean[i][1];
        if (a0)
            d0 = wrap_diff(d0);
        if (a1)
            d1 = wrap_diff(d1);
        for (int k0 = -n0; k0 <= n0; ++k0) {
            const double y0 = d0 + TWO_PI * k0;
            const double z0 = inv[0] * y0, part = inv[1] * y0;
            for (int k1 = -n1; k1 <= n1; ++k1) {
                const double z1 = part + inv[2] * (d1 + TWO_PI * k1);
                const double t = c - 0.5 * (z0 * z0 + z1 * z1);
                x[n++] = t;
                mx = max2(mx, t);
            }
        }
    }
    *max_out = mx;
    return n;
}

static double log_density_2d(const gmmrrt_model_t *m, const double *f)
{
    double x[GMMRRT_MAX_K * 9];
    const double f0 = (m->angle_mask & 1u) ? gmmrrt_wrap_angle(f[0]) : f[0];
    const double f1 = (m->angle_mask & 2u) ? gmmrrt_wrap_angle(f[1]) : f[1];
    if (isnan(f0) || isnan(f1))
        return NAN; /* max2() below would drop NaN terms silently */
    double mx;
    const int n = terms_2d(m, f0, f1, x, &mx);
    if (!(mx > -INFINITY))
        return -INFINITY; /* every term underflowed (or infinite input) */
    const double cut = mx - LSE_CUTOFF;
    double s = 0.0;
    for (int t = 0; t < n; ++t)
        if (x[t] > cut)
            s += exp(x[t] - mx);
    return mx + log(s);
}

/* delta / max(p(f), delta) for D = 2 without the log/exp round trip: p = e^max * sum of
 * e^(x - max). Far from the data (e^max * n < delta, so p < delta) it costs 1 after a
 * single exp(), which is most of the map; only near the data does the sum run. */
static double task_cost_2d(const gmmrrt_model_t *m, const double *f, double delta)
{
    double x[GMMRRT_MAX_K * 9];
    const double f0 = (m->angle_mask & 1u) ? gmmrrt_wrap_angle(f[0]) : f[0];
    const double f1 = (m->angle_mask & 2u) ? gmmrrt_wrap_angle(f[1]) : f[1];
    if (isnan(f0) || isnan(f1))
        return 1.0; /* a NaN density costs the maximum */
    double mx;
    const int n = terms_2d(m, f0, f1, x, &mx);
    if (!(mx > -INFINITY))
        return 1.0;
    const double top = exp(mx);
    if (top * (double)n <= delta)
        return 1.0; /* every term is at most e^max: p <= n e^max <= delta */
    const double cut = mx - LSE_CUTOFF;
    double s = 0.0;
    for (int t = 0; t < n; ++t)
        if (x[t] > cut)
            s += exp(x[t] - mx);
    const double p = top * s;
    return (p > delta) ? delta / p : 1.0;
}

/* The largest held term of the inward density (gmm.h) at f = (d, theta) (theta wrapped), for
 * a (d linear, theta angle) model: per component and image of theta, log w_i - q/2 with
 * d - mu_d held at the ridge -b c y1 / (a^2 + b^2) (L^-1 = [[a, 0], [b, c]]: the d that
 * minimises the quadratic form q at that theta offset y1) where it lies beyond it. */
static double inward_held_max(const gmmrrt_model_t *m, double f0, double f1)
{
    double mx = -INFINITY;
    for (int32_t i = 0; i < m->k; ++i) {
        const double *inv = m->inv_chol[i];
        const double ridge = -(inv[1] * inv[2]) / (inv[0] * inv[0] + inv[1] * inv[1]);
        const double d0 = f0 - m->mean[i][0];
        const double d1 = wrap_diff(f1 - m->mean[i][1]);
        for (int img = 0; img < 3; ++img) {
            const double y1 = d1 + (img == 0 ? 0.0 : img == 1 ? -TWO_PI : TWO_PI);
            const double r = ridge * y1;
            const double y0 = d0 > r ? r : d0;
            const double z0 = inv[0] * y0, z1 = inv[1] * y0 + inv[2] * y1;
            mx = max2(mx, m->log_coef[i] - 0.5 * (z0 * z0) - 0.5 * (z1 * z1));
        }
    }
    return mx;
}

double gmmrrt_gmm_inward_task_cost(const gmmrrt_model_t *model, const double *f, double delta)
{
    assert(model != NULL && f != NULL && delta > 0.0);
    if (model->dim != 2 || model->angle_mask != 2u)
        return gmmrrt_gmm_task_cost(model, f, delta);
    const double f0 = f[0], f1 = gmmrrt_wrap_angle(f[1]);
    if (isnan(f0) || isnan(f1) || isinf(f0))
        return 1.0;
    const double p = gmmrrt_gmm_density(model, f);
    const double held = exp(inward_held_max(model, f0, f1));
    const double pt = p > held ? p : held;
    return (pt > delta) ? delta / pt : 1.0;
}

/* ------------------------------------------------------------------ any D */

/* fw: f with its angle entries already wrapped into (-pi, pi]. */
static void add_component_nd(const gmmrrt_model_t *m, int32_t i, const double *fw, lse_t *acc)
{
    const int32_t dim = m->dim;
    const double *inv = m->inv_chol[i];
    const double c = m->log_coef[i];
    double diff[GMMRRT_MAX_DIM];
    int32_t angle_dim[GMMRRT_MAX_DIM];
    int image[GMMRRT_MAX_DIM];
    int32_t n_angles = 0;
    for (int32_t j = 0; j < dim; ++j) {
        diff[j] = fw[j] - m->mean[i][j];
        if ((m->angle_mask >> j) & 1u) {
            diff[j] = wrap_diff(diff[j]);
            angle_dim[n_angles] = j;
            image[n_angles] = -1;
            ++n_angles;
        }
    }
    for (;;) {
        double x[GMMRRT_MAX_DIM];
        for (int32_t j = 0; j < dim; ++j)
            x[j] = diff[j];
        for (int32_t a = 0; a < n_angles; ++a)
            x[angle_dim[a]] += TWO_PI * image[a];
        double q = 0.0;
        for (int32_t r = 0; r < dim; ++r) {
            const double *row = inv + GMMRRT_TRI(r);
            double z = 0.0;
            for (int32_t s = 0; s <= r; ++s)
                z += row[s] * x[s];
            q += z * z;
        }
        lse_add(acc, c - 0.5 * q);
        /* Next image combination (an odometer over {-1, 0, 1}^A). */
        int32_t a = 0;
        while (a < n_angles && image[a] == 1)
            image[a++] = -1;
        if (a == n_angles)
            break;
        ++image[a];
    }
}

/* fw = f with angle entries wrapped into (-pi, pi]; returns 0 when f holds a NaN (the
 * streaming log-sum-exp would not carry a NaN term through to the result). */
static int wrap_angles(const gmmrrt_model_t *m, const double *f, double *fw)
{
    int ok = 1;
    for (int32_t j = 0; j < m->dim; ++j) {
        fw[j] = ((m->angle_mask >> j) & 1u) ? gmmrrt_wrap_angle(f[j]) : f[j];
        ok &= !isnan(fw[j]);
    }
    return ok;
}

/* ------------------------------------------------------------------ public */

double gmmrrt_gmm_log_density(const gmmrrt_model_t *model, const double *f)
{
    assert(model != NULL && f != NULL);
    if (model->dim == 2)
        return log_density_2d(model, f);
    lse_t acc = {-INFINITY, 0.0};
    const int32_t k = model->k;
    double fw[GMMRRT_MAX_DIM];
    if (!wrap_angles(model, f, fw))
        return NAN;
    for (int32_t i = 0; i < k; ++i)
        add_component_nd(model, i, fw, &acc);
    return lse_value(&acc);
}

double gmmrrt_gmm_density(const gmmrrt_model_t *model, const double *f)
{
    return exp(gmmrrt_gmm_log_density(model, f));
}

double gmmrrt_gmm_component_log_density(const gmmrrt_model_t *model, int32_t i, const double *f)
{
    assert(model != NULL && f != NULL);
    if (i < 0 || i >= model->k)
        return NAN;
    lse_t acc = {-INFINITY, 0.0};
    double fw[GMMRRT_MAX_DIM];
    if (!wrap_angles(model, f, fw))
        return NAN;
    add_component_nd(model, i, fw, &acc);
    return lse_value(&acc);
}

double gmmrrt_gmm_task_cost(const gmmrrt_model_t *model, const double *f, double delta)
{
    assert(model != NULL && f != NULL && delta > 0.0);
    if (model->dim == 2)
        return task_cost_2d(model, f, delta);
    const double p = gmmrrt_gmm_density(model, f);
    /* delta / max(p, delta); a NaN density (NaN features) costs the maximum, 1. */
    return (p > delta) ? delta / p : 1.0;
}

void gmmrrt_gmm_sample_component(const gmmrrt_model_t *model, int32_t i, gmmrrt_rng_t *rng, double *f_out)
{
    assert(model != NULL && rng != NULL && f_out != NULL && i >= 0 && i < model->k);
    const int32_t dim = model->dim;
    const double *l = model->chol[i];
    double z[GMMRRT_MAX_DIM];
    for (int32_t j = 0; j < dim; ++j)
        z[j] = gmmrrt_rng_normal(rng);
    for (int32_t r = 0; r < dim; ++r) {
        const double *row = l + GMMRRT_TRI(r);
        double v = model->mean[i][r];
        for (int32_t s = 0; s <= r; ++s)
            v += row[s] * z[s];
        f_out[r] = ((model->angle_mask >> r) & 1u) ? gmmrrt_wrap_angle(v) : v;
    }
}

int32_t gmmrrt_gmm_sample(const gmmrrt_model_t *model, gmmrrt_rng_t *rng, double *f_out)
{
    assert(model != NULL && rng != NULL && f_out != NULL);
    const double u = gmmrrt_rng_uniform(rng); /* [0, 1); cum_weight[k-1] == 1 */
    int32_t i = 0;
    while (i < model->k - 1 && !(u < model->cum_weight[i]))
        ++i;
    gmmrrt_gmm_sample_component(model, i, rng, f_out);
    return i;
}
