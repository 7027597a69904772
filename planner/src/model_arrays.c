/*
 * model_arrays.c - a gmmrrt_model_t to and from flat arrays (model.h), for writers and
 * readers in other languages (the Python tools through ctypes) that must not mirror the
 * struct's layout or the file format: they hand the numbers over and the core validates,
 * encodes and decodes them with the one implementation of the format (model.c).
 */
#include <string.h>

#include "gmmrrt/model.h"

#include "error_text.h"

size_t gmmrrt_model_sizeof(void)
{
    return sizeof(gmmrrt_model_t);
}

gmmrrt_status_t gmmrrt_model_from_arrays(int32_t kind, int32_t task, int32_t homotopy, int32_t dim, int32_t k,
                                         uint32_t angle_mask, double delta, const double *weight,
                                         const double *mean, const double *chol, gmmrrt_model_t *out, char *err,
                                         size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (out == NULL || weight == NULL || mean == NULL || chol == NULL)
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "model, weight, mean or chol is NULL");
    if (dim < 1 || dim > GMMRRT_MAX_DIM || k < 1 || k > GMMRRT_MAX_K)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_SIZE, err, errcap,
                                "D = %d, K = %d: this build takes D in 1..%d and K in 1..%d", (int)dim, (int)k,
                                GMMRRT_MAX_DIM, GMMRRT_MAX_K);
    memset(out, 0, sizeof *out);
    out->kind = kind;
    out->task = task;
    out->homotopy = homotopy;
    out->dim = dim;
    out->k = k;
    out->angle_mask = angle_mask;
    out->delta = delta;
    const int32_t tri = GMMRRT_TRI(dim);
    for (int32_t i = 0; i < k; ++i) {
        out->weight[i] = weight[i];
        memcpy(out->mean[i], mean + (size_t)i * (size_t)dim, (size_t)dim * sizeof(double));
        memcpy(out->chol[i], chol + (size_t)i * (size_t)tri, (size_t)tri * sizeof(double));
    }
    return gmmrrt_model_prepare(out, err, errcap);
}

void gmmrrt_model_to_arrays(const gmmrrt_model_t *model, int32_t *header, double *delta, double *weight,
                            double *mean, double *chol)
{
    const int32_t dim = model->dim, k = model->k, tri = GMMRRT_TRI(dim);
    header[0] = model->kind;
    header[1] = model->task;
    header[2] = model->homotopy;
    header[3] = dim;
    header[4] = k;
    header[5] = (int32_t)model->angle_mask;
    *delta = model->delta;
    for (int32_t i = 0; i < k; ++i) {
        weight[i] = model->weight[i];
        memcpy(mean + (size_t)i * (size_t)dim, model->mean[i], (size_t)dim * sizeof(double));
        memcpy(chol + (size_t)i * (size_t)tri, model->chol[i], (size_t)tri * sizeof(double));
    }
}
