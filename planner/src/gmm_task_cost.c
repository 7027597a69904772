/*
 * gmm_task_cost.c - the paper's task cost c(f) = delta / max(p(f), delta) (Sect. 4; p the
 * mixture of eq. 1) and the inward variant (gmm.h) for many points at once
 * (gmmrrt_gmm_task_cost_batch, gmmrrt_gmm_inward_task_cost_batch): the planner's
 * edge-cost quadrature calls it for every edge it weighs, which made it the hot path of the
 * social first solution (perf: the mixture terms and libm exp were 60 % of it).
 *
 * D = 2 models go through a vector kernel (gmm_task_cost_kernel.inc) with its own exp, 2
 * points per instruction on any x86-64 (SSE2) or ARM (NEON), 4 when the CPU has AVX2 (checked
 * at run time). Both give the same bits (lanes never mix), so a plan does not depend on the
 * machine's vector width. It agrees with gmm.c's one-point gmmrrt_gmm_task_cost (libm's exp)
 * to a few units in the last place (tests/unit/gmm checks 1e-13 relative).
 * A delta below 1e-290 (densities that small are under the kernel's e^-700 floor) takes the
 * scalar path. Nothing here allocates.
 */
#include <assert.h>
#include <math.h>

#include "gmmrrt/features.h"
#include "gmmrrt/gmm.h"
#include "gmm_task_cost.h"

/* The 256-bit vectors are passed only between this file's inlined static functions; on the
 * baseline target GCC notes that such a signature would differ under AVX (no ABI is crossed). */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

#define TC_NEGLIGIBLE (-40.0) /* e^-40 = 4e-18 of the largest term (1): 57 such add < 3e-16 */
#define TC_EXP_HIGH 700.0     /* e^m is taken at most e^700 (Exp's bits stay in range); its floor: e^-700 */
#define TC_MIN_KERNEL_DELTA 1e-290

#define KW 2
#define KATTR
#define KNAME(x) x##_w2
#include "gmm_task_cost_kernel.inc"
#undef KW
#undef KATTR
#undef KNAME

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define GMMRRT_TASK_COST_HAVE_AVX2 1
#define KW 4
#define KATTR __attribute__((target("avx2")))
#define KNAME(x) x##_w4
#include "gmm_task_cost_kernel.inc"
#undef KW
#undef KATTR
#undef KNAME
#endif

static int use_avx2(void)
{
#ifdef GMMRRT_TASK_COST_HAVE_AVX2
    return __builtin_cpu_supports("avx2") ? 1 : 0; /* a load and a test: no state of ours */
#else
    return 0;
#endif
}

/* One point on the scalar path (delta below the kernel's floor). */
static double task_cost_scalar(const gmmrrt_model_t *model, const double *f, double delta)
{
    const double p = gmmrrt_gmm_density(model, f);
    return (p > delta) ? delta / p : 1.0; /* a NaN density (NaN features) costs 1 */
}

int gmmrrt_gmm_task_cost_batch_lanes(const gmmrrt_model_t *model, const double *f0, const double *f1, int32_t n,
                                     double delta, double *cost, int lanes, int inward)
{
    assert(model != NULL && model->dim == 2 && n >= 0 && (n == 0 || (f0 && f1 && cost)) && delta > 0.0);
    if (lanes != 0 && lanes != 2 && !(lanes == 4 && use_avx2()))
        return 0; /* that width is not available here: nothing written */
    inward = inward && model->angle_mask == 2u; /* other models: the paper's cost (gmm.h) */
    if (!(delta >= TC_MIN_KERNEL_DELTA)) {
        for (int32_t i = 0; i < n; ++i) {
            const double f[2] = {f0[i], f1[i]};
            cost[i] = inward ? gmmrrt_gmm_inward_task_cost(model, f, delta) : task_cost_scalar(model, f, delta);
        }
        return 1;
    }
    if (lanes == 0)
        lanes = use_avx2() ? 4 : 2;
    const int wide = lanes == 4;
    (void)wide; /* without the AVX2 kernel (not x86-64) only the baseline runs */
    for (int32_t start = 0; start < n; start += lanes) {
        /* Wrapped angles; NaN points get a finite stand-in and cost 1 afterwards. The last
         * block is padded with copies of its first point. */
        double a[4], b[4], out[4];
        int nan_lane[4] = {0, 0, 0, 0};
        for (int32_t q = 0; q < lanes; ++q) {
            const int32_t src = start + q < n ? start + q : start;
            a[q] = (model->angle_mask & 1u) ? gmmrrt_wrap_angle(f0[src]) : f0[src];
            b[q] = (model->angle_mask & 2u) ? gmmrrt_wrap_angle(f1[src]) : f1[src];
            if (isnan(a[q]) || isnan(b[q]) || isinf(a[q]) || isinf(b[q])) {
                nan_lane[q] = 1;
                a[q] = b[q] = 0.0;
            }
        }
#ifdef GMMRRT_TASK_COST_HAVE_AVX2
        if (wide)
            kernel_block_w4(model, a, b, delta, inward, out);
        else
#endif
            kernel_block_w2(model, a, b, delta, inward, out);
        for (int32_t q = 0; q < lanes && start + q < n; ++q)
            cost[start + q] = nan_lane[q] ? 1.0 : out[q];
    }
    return 1;
}

void gmmrrt_gmm_task_cost_batch(const gmmrrt_model_t *model, const double *f0, const double *f1, int32_t n,
                                double delta, double *cost)
{
    (void)gmmrrt_gmm_task_cost_batch_lanes(model, f0, f1, n, delta, cost, 0, 0); /* 0: always available */
}

void gmmrrt_gmm_density_batch(const gmmrrt_model_t *model, const double *f0, const double *f1, int32_t n, double *p)
{
    const double floor = 1e-280; /* above the kernel's floor (TC_MIN_KERNEL_DELTA): the vector path */
    (void)gmmrrt_gmm_task_cost_batch_lanes(model, f0, f1, n, floor, p, 0, 0);
    for (int32_t i = 0; i < n; ++i)
        p[i] = p[i] < 1.0 ? floor / p[i] : 0.0; /* c = floor / p where p > floor, else 1 */
}

void gmmrrt_gmm_inward_task_cost_batch(const gmmrrt_model_t *model, const double *f0, const double *f1, int32_t n,
                                       double delta, double *cost)
{
    (void)gmmrrt_gmm_task_cost_batch_lanes(model, f0, f1, n, delta, cost, 0, 1);
}
