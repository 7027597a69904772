/*
 * gmmrrt_learn.h - a small C API over the learner (EM fit of learner/src/em.cpp) and the C
 * core's model code (model.h codec, gmm.h density and sampler, model_file.h atomic save and
 * validating load), for bindings such as the Python module tools/gmmrrt_tools/learn.py
 * (ctypes). Library: build/lib/libgmmrrt_learn.so. Nothing here re-implements a rule: the fit
 * is FitMixture, the density gmmrrt_gmm_log_density, the file format model.c.
 *
 * Models are opaque handles (the caller never needs gmmrrt_model_t's layout, which follows the
 * overridable limits of limits.h). Every function checks its arguments; a status other than
 * GMMRRT_OK leaves *out untouched and writes the reason to err[errcap] (may be NULL).
 */
#ifndef GMMRRT_LEARN_C_H
#define GMMRRT_LEARN_C_H

#include <stddef.h>
#include <stdint.h>

#include "gmmrrt/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gmmrrt_learn_model gmmrrt_learn_model_t;

/* Options of a fit; gmmrrt_learn_options_default() gives the learner's defaults. */
typedef struct {
    int32_t k;              /* components, 1..GMMRRT_MAX_K */
    uint64_t seed;          /* same seed, same model */
    int32_t threads;        /* E-step threads; 0: the cores available (any value: same result) */
    int32_t max_iter;       /* EM iteration cap */
    double tol;             /* convergence tolerance on the mean log-likelihood per point [nats] */
    int32_t restarts;       /* candidate starts */
    int32_t accelerate;     /* 1: SQUAREM, 0: plain EM */
} gmmrrt_learn_options_t;

/* What a fit did. */
typedef struct {
    double mean_log_likelihood; /* per point, on the training points */
    double bic;                 /* -2 N meanLL + p ln N */
    int32_t iterations;
    int32_t converged;          /* 1 when the tolerance stopped it, 0 at the cap */
    int32_t k_final;            /* K after dropped degenerate components */
} gmmrrt_learn_summary_t;

gmmrrt_learn_options_t gmmrrt_learn_options_default(void);

/* Fits a mixture to n points of dimension dim (row-major n x dim, finite; angle dimensions
 * flagged in angle_mask are wrapped). *out: a new model (kind generic, delta the paper's), to
 * be freed with gmmrrt_learn_free. summary may be NULL. GMMRRT_ERR_INVALID_ARGUMENT for bad
 * arguments, options or data (too few points for K, a constant dimension, a non-finite value:
 * the reason in err); GMMRRT_ERR_MODEL_* when the fitted mixture does not make a valid model. */
gmmrrt_status_t gmmrrt_learn_fit(const double *points, int64_t n, int32_t dim, uint32_t angle_mask,
                                 const gmmrrt_learn_options_t *options, gmmrrt_learn_model_t **out,
                                 gmmrrt_learn_summary_t *summary, char *err, size_t errcap);

/* Loads and validates a model file (gmmrrt_model_load_file) into a new handle. */
gmmrrt_status_t gmmrrt_learn_load(const char *path, gmmrrt_learn_model_t **out, char *err, size_t errcap);

/* Writes the model atomically (gmmrrt_model_save_file: the same file format as gmmrrt-learn). */
gmmrrt_status_t gmmrrt_learn_save(const gmmrrt_learn_model_t *model, const char *path, char *err, size_t errcap);

void gmmrrt_learn_free(gmmrrt_learn_model_t *model);

int32_t gmmrrt_learn_dim(const gmmrrt_learn_model_t *model);
int32_t gmmrrt_learn_k(const gmmrrt_learn_model_t *model);
uint32_t gmmrrt_learn_angle_mask(const gmmrrt_learn_model_t *model);

/* Component i (0 <= i < K): its weight, mean (dim) and covariance (dim x dim, row-major). */
gmmrrt_status_t gmmrrt_learn_component(const gmmrrt_learn_model_t *model, int32_t i, double *weight,
                                       double *mean, double *covariance);

/* out[p] = log p(point p) by gmmrrt_gmm_log_density for n row-major points of the model's dim. */
gmmrrt_status_t gmmrrt_learn_log_density(const gmmrrt_learn_model_t *model, const double *points, int64_t n,
                                         double *out);

/* n draws by gmmrrt_gmm_sample with a generator seeded by seed: out (n x dim, row-major) and,
 * if labels is not NULL, the component of each draw. */
gmmrrt_status_t gmmrrt_learn_sample(const gmmrrt_learn_model_t *model, uint64_t seed, int64_t n, double *out,
                                    int32_t *labels);

#ifdef __cplusplus
}
#endif

#endif /* GMMRRT_LEARN_C_H */
