/*
 * model.c - the Gaussian mixture model of paper eq. 1 and its binary file format
 * (model.h; byte layout and validation order in docs/model-format.md).
 *
 * One implementation of the format for the writer (learner) and the reader (planner).
 * Every multi-byte field is little-endian and is assembled byte by byte, so the code does
 * not depend on the host's byte order or alignment. Decoding checks, in this fixed order:
 *   length >= header + CRC (TRUNCATED), length <= largest valid file (TOO_LARGE), magic,
 *   version, byte-order mark, D and K within limits.h (BAD_SIZE), reserved == 0
 *   (BAD_FIELD), length >= encoded size (TRUNCATED), CRC-32, then any bytes after the
 *   model's CRC-32 as an optional background section (model_background.c) followed by an
 *   optional provenance trailer (model_provenance.c; anything else BAD_SIZE),
 * then the stored fields as gmmrrt_model_prepare() does:
 *   kind/task/homotopy/angle_mask/delta (BAD_FIELD), finite numbers (NOT_FINITE),
 *   weights (BAD_WEIGHTS), Cholesky factors (NOT_POSITIVE_DEFINITE), angle means in
 *   [-pi, pi] (BAD_FIELD).
 * Derived fields (inverse factors, log normalisers, cumulative weights) are always
 * recomputed here, never read from a file.
 */
#include "gmmrrt/model.h"

#include <math.h>
#include <string.h>

#include "error_text.h"
#include "model_frame.h"

#define CRC_BYTES 4u
#define WEIGHT_SUM_TOL 1e-9
#define MAX_DIAG_RATIO 1e8

/* ------------------------------------------------------------------ sizes */

static size_t doubles_per_component(int32_t dim)
{
    return 1u + (size_t)dim + (size_t)GMMRRT_TRI(dim);
}

size_t gmmrrt_model_encoded_size(int32_t dim, int32_t k)
{
    if (dim < 1 || dim > GMMRRT_MAX_DIM || k < 1 || k > GMMRRT_MAX_K)
        return 0;
    return GMMRRT_MODEL_HEADER_BYTES + (size_t)k * doubles_per_component(dim) * 8u + CRC_BYTES;
}

size_t gmmrrt_model_max_encoded_size(void)
{
    return gmmrrt_model_encoded_size(GMMRRT_MAX_DIM, GMMRRT_MAX_K);
}

/* ------------------------------------------------------------------ little-endian bytes */

static uint16_t get_u16(const uint8_t *p)
{
    return (uint16_t)(p[0] | (p[1] << 8));
}

static uint32_t get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static double get_f64(const uint8_t *p)
{
    uint64_t u = 0;
    for (int b = 7; b >= 0; --b)
        u = (u << 8) | p[b];
    double v;
    memcpy(&v, &u, sizeof v);
    return v;
}

static void put_u16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)(v >> 8);
}

static void put_u32(uint8_t *p, uint32_t v)
{
    for (int b = 0; b < 4; ++b)
        p[b] = (uint8_t)((v >> (8 * b)) & 0xFFu);
}

static void put_f64(uint8_t *p, double v)
{
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    for (int b = 0; b < 8; ++b)
        p[b] = (uint8_t)((u >> (8 * b)) & 0xFFu);
}

/* ------------------------------------------------------------------ validation */

/* L^-1 of the packed lower-triangular factor `l` (dim x dim) into `inv` (packed the same
 * way) by forward substitution, and sum_j log L_jj into *log_det_half. Returns 0 when an
 * entry of the inverse overflows (a factor too small to invert in double precision). */
static int invert_lower(const double *l, int32_t dim, double *inv, double *log_det_half)
{
    double s = 0.0;
    for (int32_t c = 0; c < dim; ++c) {
        /* Column c of L^-1: rows r >= c. */
        for (int32_t r = c; r < dim; ++r) {
            double acc = (r == c) ? 1.0 : 0.0;
            for (int32_t m = c; m < r; ++m)
                acc -= l[GMMRRT_TRI(r) + m] * inv[GMMRRT_TRI(m) + c];
            const double v = acc / l[GMMRRT_TRI(r) + r];
            if (!isfinite(v))
                return 0;
            inv[GMMRRT_TRI(r) + c] = v;
        }
        s += log(l[GMMRRT_TRI(c) + c]);
    }
    *log_det_half = s;
    return 1;
}

/* Stored fields of `m`, in the order of the file comment above. */
static gmmrrt_status_t validate(const gmmrrt_model_t *m, char *err, size_t errcap)
{
    if (m->dim < 1 || m->dim > GMMRRT_MAX_DIM)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_SIZE, err, errcap, "dimension D = %d is outside 1..%d",
                                (int)m->dim, GMMRRT_MAX_DIM);
    if (m->k < 1 || m->k > GMMRRT_MAX_K)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_SIZE, err, errcap,
                                "component count K = %d is outside 1..%d", (int)m->k, GMMRRT_MAX_K);
    const int32_t dim = m->dim, k = m->k, tri = GMMRRT_TRI(dim);

    /* Header fields. */
    switch (m->kind) {
    case GMMRRT_MODEL_KIND_FEATURES:
        if (dim != 2 || m->angle_mask != 0x2u)
            return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_FIELD, err, errcap,
                                    "kind features needs D = 2 and angle_mask = 0x2 (theta), got D = %d, "
                                    "angle_mask = 0x%x",
                                    (int)dim, (unsigned)m->angle_mask);
        break;
    case GMMRRT_MODEL_KIND_XY:
        if (dim != 3 || m->angle_mask != 0u)
            return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_FIELD, err, errcap,
                                    "kind xy needs D = 3 and angle_mask = 0, got D = %d, angle_mask = 0x%x",
                                    (int)dim, (unsigned)m->angle_mask);
        break;
    case GMMRRT_MODEL_KIND_GENERIC: break;
    default:
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_FIELD, err, errcap,
                                "kind = %d is unknown (1 features, 2 xy, 3 generic)", (int)m->kind);
    }
    if (m->task < GMMRRT_TASK_NONE || m->task > GMMRRT_TASK_APPROACH)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_FIELD, err, errcap,
                                "task = %d is unknown (0 none, 1 avoid, 2 approach)", (int)m->task);
    if (m->homotopy < GMMRRT_HOMOTOPY_ALL || m->homotopy > GMMRRT_HOMOTOPY_FRONTAL)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_FIELD, err, errcap,
                                "homotopy = %d is unknown (0 all, 1 left, 2 right, 3 frontal)",
                                (int)m->homotopy);
    if (dim < 32 && (m->angle_mask >> dim) != 0u)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_FIELD, err, errcap,
                                "angle_mask = 0x%x flags a dimension >= D = %d", (unsigned)m->angle_mask,
                                (int)dim);
    if (!isfinite(m->delta) || !(m->delta > 0.0))
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_FIELD, err, errcap, "delta = %g must be finite and > 0",
                                m->delta);

    /* Finite numbers. */
    for (int32_t i = 0; i < k; ++i) {
        if (!isfinite(m->weight[i]))
            return gmmrrt_set_error(GMMRRT_ERR_MODEL_NOT_FINITE, err, errcap, "component %d: weight is %g",
                                    (int)i, m->weight[i]);
        for (int32_t j = 0; j < dim; ++j)
            if (!isfinite(m->mean[i][j]))
                return gmmrrt_set_error(GMMRRT_ERR_MODEL_NOT_FINITE, err, errcap,
                                        "component %d: mean[%d] is %g", (int)i, (int)j, m->mean[i][j]);
        for (int32_t t = 0; t < tri; ++t)
            if (!isfinite(m->chol[i][t]))
                return gmmrrt_set_error(GMMRRT_ERR_MODEL_NOT_FINITE, err, errcap,
                                        "component %d: Cholesky factor entry %d is %g", (int)i, (int)t,
                                        m->chol[i][t]);
    }

    /* Weights: a distribution. */
    double sum = 0.0;
    for (int32_t i = 0; i < k; ++i) {
        if (!(m->weight[i] > 0.0 && m->weight[i] <= 1.0))
            return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_WEIGHTS, err, errcap,
                                    "component %d: weight %.17g is outside (0, 1]", (int)i, m->weight[i]);
        sum += m->weight[i];
    }
    if (!(fabs(sum - 1.0) <= WEIGHT_SUM_TOL))
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_WEIGHTS, err, errcap,
                                "weights sum to %.17g, not 1 (tolerance %g)", sum, WEIGHT_SUM_TOL);

    /* Cholesky factors: positive diagonal, bounded conditioning, invertible. */
    for (int32_t i = 0; i < k; ++i) {
        double dmin = INFINITY, dmax = 0.0;
        for (int32_t j = 0; j < dim; ++j) {
            const double d = m->chol[i][GMMRRT_TRI(j) + j];
            if (!(d > 0.0))
                return gmmrrt_set_error(GMMRRT_ERR_MODEL_NOT_POSITIVE_DEFINITE, err, errcap,
                                        "component %d: Cholesky diagonal L[%d][%d] = %g is not > 0", (int)i,
                                        (int)j, (int)j, d);
            dmin = fmin(dmin, d);
            dmax = fmax(dmax, d);
        }
        if (!(dmax <= MAX_DIAG_RATIO * dmin))
            return gmmrrt_set_error(GMMRRT_ERR_MODEL_NOT_POSITIVE_DEFINITE, err, errcap,
                                    "component %d: Cholesky diagonal ratio max/min = %g exceeds %g "
                                    "(ill-conditioned covariance)",
                                    (int)i, dmax / dmin, MAX_DIAG_RATIO);
        double inv[GMMRRT_MAX_TRI], log_det_half;
        if (!invert_lower(m->chol[i], dim, inv, &log_det_half) || !isfinite(log_det_half))
            return gmmrrt_set_error(GMMRRT_ERR_MODEL_NOT_POSITIVE_DEFINITE, err, errcap,
                                    "component %d: Cholesky factor cannot be inverted in double precision",
                                    (int)i);
    }

    /* Angle means in [-pi, pi]. */
    for (int32_t i = 0; i < k; ++i)
        for (int32_t j = 0; j < dim; ++j)
            if (((m->angle_mask >> j) & 1u) && !(m->mean[i][j] >= -M_PI && m->mean[i][j] <= M_PI))
                return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_FIELD, err, errcap,
                                        "component %d: mean[%d] = %.17g is an angle outside [-pi, pi]",
                                        (int)i, (int)j, m->mean[i][j]);
    return GMMRRT_OK;
}

gmmrrt_status_t gmmrrt_model_prepare(gmmrrt_model_t *model, char *err, size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (model == NULL)
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "model is NULL");
    const gmmrrt_status_t st = validate(model, err, errcap);
    if (st != GMMRRT_OK)
        return st;

    const int32_t dim = model->dim, k = model->k;
    const double half_d_log_2pi = 0.5 * (double)dim * log(2.0 * M_PI);
    memset(model->inv_chol, 0, sizeof model->inv_chol);
    memset(model->log_coef, 0, sizeof model->log_coef);
    memset(model->cum_weight, 0, sizeof model->cum_weight);
    double cum = 0.0;
    for (int32_t i = 0; i < k; ++i) {
        double log_det_half = 0.0;
        (void)invert_lower(model->chol[i], dim, model->inv_chol[i], &log_det_half); /* checked */
        model->log_coef[i] = log(model->weight[i]) - half_d_log_2pi - log_det_half;
        cum += model->weight[i];
        model->cum_weight[i] = cum;
    }
    model->cum_weight[k - 1] = 1.0; /* the sum is 1 within 1e-9; sampling relies on the end */
    return GMMRRT_OK;
}

/* ------------------------------------------------------------------ encode / decode */

gmmrrt_status_t gmmrrt_model_encode(const gmmrrt_model_t *model, uint8_t *buf, size_t cap,
                                    size_t *out_len, char *err, size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (model == NULL || out_len == NULL || (buf == NULL && cap > 0))
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "model, buf or out_len is NULL");
    *out_len = 0;
    const gmmrrt_status_t st = validate(model, err, errcap);
    if (st != GMMRRT_OK)
        return st;
    const int32_t dim = model->dim, k = model->k, tri = GMMRRT_TRI(dim);
    const size_t len = gmmrrt_model_encoded_size(dim, k);
    if (buf == NULL || cap < len)
        return gmmrrt_set_error(GMMRRT_ERR_BUFFER_TOO_SMALL, err, errcap,
                                "the encoded model needs %zu bytes, the buffer has %zu", len, cap);

    memcpy(buf, GMMRRT_MODEL_MAGIC, 8);
    put_u16(buf + 8, GMMRRT_MODEL_FORMAT_VERSION);
    put_u16(buf + 10, 0xFEFFu);
    buf[12] = (uint8_t)model->kind;
    buf[13] = (uint8_t)model->task;
    buf[14] = (uint8_t)model->homotopy;
    buf[15] = (uint8_t)dim;
    put_u16(buf + 16, (uint16_t)k);
    put_u16(buf + 18, 0);
    put_u32(buf + 20, model->angle_mask);
    put_f64(buf + 24, model->delta);
    uint8_t *p = buf + GMMRRT_MODEL_HEADER_BYTES;
    for (int32_t i = 0; i < k; ++i, p += 8)
        put_f64(p, model->weight[i]);
    for (int32_t i = 0; i < k; ++i)
        for (int32_t j = 0; j < dim; ++j, p += 8)
            put_f64(p, model->mean[i][j]);
    for (int32_t i = 0; i < k; ++i)
        for (int32_t t = 0; t < tri; ++t, p += 8)
            put_f64(p, model->chol[i][t]);
    put_u32(p, gmmrrt_crc32(buf, (size_t)(p - buf)));
    *out_len = len;
    return GMMRRT_OK;
}

gmmrrt_status_t gmmrrt_model_check_frame(const uint8_t *buf, size_t len, gmmrrt_model_frame_t *frame, char *err,
                                         size_t errcap)
{
    memset(frame, 0, sizeof *frame);
    const size_t min_len = GMMRRT_MODEL_HEADER_BYTES + CRC_BYTES;
    const size_t max_len = gmmrrt_model_max_file_size();
    if (len < min_len)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_TRUNCATED, err, errcap,
                                "%zu bytes is shorter than the %zu-byte header and checksum", len, min_len);
    if (len > max_len)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_TOO_LARGE, err, errcap,
                                "%zu bytes is larger than any valid model file "
                                "(at most %zu bytes, D <= %d, K <= %d, a background model, provenance <= %d "
                                "bytes)",
                                len, max_len, GMMRRT_MAX_DIM, GMMRRT_MAX_K, GMMRRT_MAX_PROVENANCE_BYTES);
    if (memcmp(buf, GMMRRT_MODEL_MAGIC, 8) != 0)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_MAGIC, err, errcap,
                                "bytes 0..7 are not the magic \"GMMRRTMD\": not a gmmrrt model file");
    const uint16_t version = get_u16(buf + 8);
    if (version != GMMRRT_MODEL_FORMAT_VERSION)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_VERSION, err, errcap,
                                "format version %u is not one this build reads (%d)", (unsigned)version,
                                GMMRRT_MODEL_FORMAT_VERSION);
    const uint16_t bom = get_u16(buf + 10);
    if (bom == 0xFFFEu)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_BYTE_ORDER, err, errcap,
                                "bytes 10..11: byte-order mark reads 0xFFFE: the file is big-endian");
    if (bom != 0xFEFFu)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_BYTE_ORDER, err, errcap,
                                "bytes 10..11: byte-order mark is 0x%04X, not 0xFEFF", (unsigned)bom);
    const int32_t dim = buf[15];
    const int32_t k = get_u16(buf + 16);
    if (dim < 1 || dim > GMMRRT_MAX_DIM)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_SIZE, err, errcap,
                                "byte 15: dimension D = %d is outside 1..%d", (int)dim, GMMRRT_MAX_DIM);
    if (k < 1 || k > GMMRRT_MAX_K)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_SIZE, err, errcap,
                                "bytes 16..17: component count K = %d is outside 1..%d", (int)k,
                                GMMRRT_MAX_K);
    const uint16_t reserved = get_u16(buf + 18);
    if (reserved != 0)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_FIELD, err, errcap,
                                "bytes 18..19: reserved = %u, must be 0", (unsigned)reserved);
    const size_t want = gmmrrt_model_encoded_size(dim, k);
    if (len < want)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_TRUNCATED, err, errcap,
                                "%zu bytes, but D = %d, K = %d needs %zu", len, (int)dim, (int)k, want);
    /* Bytes after the model's CRC-32: a background section, then a provenance trailer; anything
     * else and the file is refused. */
    size_t at = want;
    /* The section's magic and the trailer's share "GMMRRT": 7 bytes tell them apart, fewer are
     * left to the trailer's check (a truncated trailer or section alike). */
    const size_t magic_len = sizeof GMMRRT_BACKGROUND_MAGIC - 1;
    const size_t rest = len - at;
    if (rest >= 7 && memcmp(buf + at, GMMRRT_BACKGROUND_MAGIC, rest < magic_len ? rest : magic_len) == 0) {
        size_t section_len, inner_off, inner_len;
        const gmmrrt_status_t st =
            gmmrrt_background_check(buf + at, rest, at, &section_len, &inner_off, &inner_len, err, errcap);
        if (st != GMMRRT_OK)
            return st;
        frame->background_off = at + inner_off;
        frame->background_len = inner_len;
        at += section_len;
    }
    if (len > at) {
        size_t text_off, text_len;
        const gmmrrt_status_t st =
            gmmrrt_provenance_check(buf + at, len - at, at, &text_off, &text_len, err, errcap);
        if (st != GMMRRT_OK)
            return st;
        frame->text_off = at + text_off;
        frame->text_len = text_len;
        frame->has_provenance = 1;
    }
    const uint32_t stored_crc = get_u32(buf + want - CRC_BYTES);
    const uint32_t crc = gmmrrt_crc32(buf, want - CRC_BYTES);
    if (crc != stored_crc)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_CHECKSUM, err, errcap,
                                "CRC-32 stored 0x%08X, computed 0x%08X: the file is corrupt",
                                (unsigned)stored_crc, (unsigned)crc);
    frame->model_len = want;
    return GMMRRT_OK;
}

gmmrrt_status_t gmmrrt_model_decode(const uint8_t *buf, size_t len, gmmrrt_model_t *out, char *err,
                                    size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (out == NULL || (buf == NULL && len > 0))
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "buf or out is NULL");
    gmmrrt_model_frame_t frame;
    const gmmrrt_status_t framed = gmmrrt_model_check_frame(buf, len, &frame, err, errcap);
    if (framed != GMMRRT_OK)
        return framed;
    const int32_t dim = buf[15];
    const int32_t k = get_u16(buf + 16);

    memset(out, 0, sizeof *out);
    out->kind = buf[12];
    out->task = buf[13];
    out->homotopy = buf[14];
    out->dim = dim;
    out->k = k;
    out->angle_mask = get_u32(buf + 20);
    out->delta = get_f64(buf + 24);
    const int32_t tri = GMMRRT_TRI(dim);
    const uint8_t *p = buf + GMMRRT_MODEL_HEADER_BYTES;
    for (int32_t i = 0; i < k; ++i, p += 8)
        out->weight[i] = get_f64(p);
    for (int32_t i = 0; i < k; ++i)
        for (int32_t j = 0; j < dim; ++j, p += 8)
            out->mean[i][j] = get_f64(p);
    for (int32_t i = 0; i < k; ++i)
        for (int32_t t = 0; t < tri; ++t, p += 8)
            out->chol[i][t] = get_f64(p);
    return gmmrrt_model_prepare(out, err, errcap);
}

gmmrrt_status_t gmmrrt_model_task_fits(const gmmrrt_model_t *model, int32_t task)
{
    if (!model)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    return (model->task == GMMRRT_TASK_NONE || model->task == task) ? GMMRRT_OK : GMMRRT_ERR_MODEL_MISMATCH;
}
