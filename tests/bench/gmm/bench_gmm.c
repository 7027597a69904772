/*
 * bench_gmm - micro-benchmark of the mixture (gmm.h; paper eq. 1 and the task cost of
 * Sect. 4) at the paper's size, K = 19 components of (d, theta) features (D = 2).
 *
 * Reports evaluations per second of gmmrrt_gmm_log_density, gmmrrt_gmm_task_cost and
 * gmmrrt_gmm_sample, and, as a peer on the same machine in the same run, a plain
 * evaluation that takes every component's wrapped log-density through the general
 * D-dimensional path (gmmrrt_gmm_component_log_density) and log-sum-exps them without
 * skipping far terms. The ratio is what to quote; absolute numbers depend on the machine.
 * Asserts nothing. Usage: bench_gmm [--evaluations N] [--seed S]
 */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "gmmrrt/gmm.h"

#define N_POINTS 4096
#define K 19

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts); /* CPU time: the machine is shared */
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A K = 19 avoid-like model: components spread over d in [0.5, 4] m, theta around the circle. */
static int make_model(gmmrrt_model_t *m, uint64_t seed)
{
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, seed);
    memset(m, 0, sizeof *m);
    m->kind = GMMRRT_MODEL_KIND_FEATURES;
    m->task = GMMRRT_TASK_AVOID;
    m->dim = 2;
    m->k = K;
    m->angle_mask = 0x2u;
    m->delta = GMMRRT_MODEL_DEFAULT_DELTA;
    double sum = 0.0;
    for (int i = 0; i < K; ++i) {
        m->weight[i] = 0.5 + gmmrrt_rng_uniform(&rng);
        sum += m->weight[i];
        m->mean[i][0] = 0.5 + 3.5 * gmmrrt_rng_uniform(&rng);
        m->mean[i][1] = -M_PI + 2.0 * M_PI * gmmrrt_rng_uniform(&rng);
        m->chol[i][0] = 0.2 + 0.4 * gmmrrt_rng_uniform(&rng);
        m->chol[i][1] = 0.2 * (gmmrrt_rng_uniform(&rng) - 0.5);
        m->chol[i][2] = 0.15 + 0.5 * gmmrrt_rng_uniform(&rng);
    }
    for (int i = 0; i < K; ++i)
        m->weight[i] /= sum;
    char err[256];
    if (gmmrrt_model_prepare(m, err, sizeof err) != GMMRRT_OK) {
        fprintf(stderr, "bench_gmm: model: %s\n", err);
        return -1;
    }
    return 0;
}

static double plain_log_density(const gmmrrt_model_t *m, const double *f)
{
    double c[K], mx = -INFINITY, s = 0.0;
    for (int i = 0; i < K; ++i) {
        c[i] = gmmrrt_gmm_component_log_density(m, i, f);
        mx = fmax(mx, c[i]);
    }
    for (int i = 0; i < K; ++i)
        s += exp(c[i] - mx);
    return mx + log(s);
}

static void usage(FILE *out)
{
    fprintf(out, "usage: bench_gmm [--evaluations N] [--seed S]\n"
                 "  Evaluations per second of the mixture (K = 19, D = 2): log-density, task cost,\n"
                 "  sampling, and a plain general-path evaluation as the peer. Asserts nothing.\n"
                 "  --evaluations N  evaluations per measurement (default 4000000)\n"
                 "  --seed S         model and point seed (default 1)\n");
}

int main(int argc, char **argv)
{
    long n_eval = 4000000;
    unsigned long long seed = 1;
    static const struct option opts[] = {{"evaluations", required_argument, NULL, 'n'},
                                         {"seed", required_argument, NULL, 's'},
                                         {"help", no_argument, NULL, 'h'},
                                         {NULL, 0, NULL, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "n:s:h", opts, NULL)) != -1) {
        char *end = NULL;
        switch (c) {
        case 'n':
            n_eval = strtol(optarg, &end, 10);
            if (end == optarg || *end != '\0' || n_eval < N_POINTS) {
                fprintf(stderr, "bench_gmm: --evaluations '%s' must be an integer >= %d\n", optarg, N_POINTS);
                return 2;
            }
            break;
        case 's':
            seed = strtoull(optarg, &end, 10);
            if (end == optarg || *end != '\0') {
                fprintf(stderr, "bench_gmm: --seed '%s' must be a non-negative integer\n", optarg);
                return 2;
            }
            break;
        case 'h': usage(stdout); return 0;
        default: usage(stderr); return 2;
        }
    }
    if (optind != argc) {
        fprintf(stderr, "bench_gmm: unexpected argument '%s'\n", argv[optind]);
        return 2;
    }

    static gmmrrt_model_t model;
    if (make_model(&model, seed) != 0)
        return 1;
    static double pts[N_POINTS][2];
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, seed + 1);
    for (int p = 0; p < N_POINTS; ++p) { /* where a planner samples: d in [0, 8] m, any theta */
        pts[p][0] = 8.0 * gmmrrt_rng_uniform(&rng);
        pts[p][1] = -M_PI + 2.0 * M_PI * gmmrrt_rng_uniform(&rng);
    }

    /* The same points as two arrays, for the batch (an edge of the planner: 10 points). */
    static double pts_d[N_POINTS], pts_theta[N_POINTS];
    for (int p = 0; p < N_POINTS; ++p) {
        pts_d[p] = pts[p][0];
        pts_theta[p] = pts[p][1];
    }
    enum { EDGE_POINTS = 10 };

    double sink = 0.0, t0, dt_log, dt_cost, dt_batch, dt_sample, dt_plain;
    t0 = now_s();
    for (long e = 0; e < n_eval; ++e)
        sink += gmmrrt_gmm_log_density(&model, pts[e % N_POINTS]);
    dt_log = now_s() - t0;
    t0 = now_s();
    for (long e = 0; e < n_eval; ++e)
        sink += gmmrrt_gmm_task_cost(&model, pts[e % N_POINTS], model.delta);
    dt_cost = now_s() - t0;
    t0 = now_s();
    for (long e = 0; e + EDGE_POINTS <= n_eval; e += EDGE_POINTS) {
        const long at = e % (N_POINTS - EDGE_POINTS);
        double cost[EDGE_POINTS];
        gmmrrt_gmm_task_cost_batch(&model, pts_d + at, pts_theta + at, EDGE_POINTS, model.delta, cost);
        for (int i = 0; i < EDGE_POINTS; ++i)
            sink += cost[i];
    }
    dt_batch = now_s() - t0;
    t0 = now_s();
    for (long e = 0; e < n_eval; ++e) {
        double f[2];
        sink += gmmrrt_gmm_sample(&model, &rng, f) + f[0];
    }
    dt_sample = now_s() - t0;
    const long n_plain = n_eval / 4;
    t0 = now_s();
    for (long e = 0; e < n_plain; ++e)
        sink += plain_log_density(&model, pts[e % N_POINTS]);
    dt_plain = now_s() - t0;

    const double r_log = (double)n_eval / dt_log, r_plain = (double)n_plain / dt_plain;
    printf("bench_gmm: K = %d, D = 2 (d, theta wrapped), %ld evaluations each, seed %llu\n", K, n_eval, seed);
    printf("  log_density       %12.3e /s  (%.1f ns each)\n", r_log, 1e9 / r_log);
    printf("  task_cost         %12.3e /s  (%.1f ns each)\n", (double)n_eval / dt_cost, 1e9 * dt_cost / (double)n_eval);
    const double n_batched = (double)(n_eval / EDGE_POINTS * EDGE_POINTS);
    printf("  task_cost_batch   %12.3e /s  (%.1f ns each, %d points per call)\n", n_batched / dt_batch,
           1e9 * dt_batch / n_batched, (int)EDGE_POINTS);
    printf("  sample            %12.3e /s  (%.1f ns each)\n", (double)n_eval / dt_sample, 1e9 * dt_sample / (double)n_eval);
    printf("  peer: plain general-path log_density %12.3e /s\n", r_plain);
    printf("  ratio log_density / plain = %.2f\n", r_log / r_plain);
    printf("  (checksum %.6g)\n", sink);
    return 0;
}
