/*
 * model_background.c - the background section of a model file (model.h,
 * docs/model-format.md): a second, complete model encoding after the task model, for the
 * background task cost (config.h GMMRRT_TASK_COST_BACKGROUND). Framing checks, encoding of a
 * whole file (model, background, provenance) and decoding the background back.
 *
 * The section carries its own CRC-32 and the embedded model its own, so a damaged section is
 * reported as the background's damage and the task model's bytes are exactly those of a file
 * without it.
 */
#include <string.h>

#include "error_text.h"
#include "gmmrrt/model.h"
#include "model_frame.h"

#define SECTION_HEAD 16u /* magic, version, reserved, length */

static uint32_t get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static void put_u32(uint8_t *p, uint32_t v)
{
    for (int b = 0; b < 4; ++b)
        p[b] = (uint8_t)((v >> (8 * b)) & 0xFFu);
}

gmmrrt_status_t gmmrrt_background_check(const uint8_t *buf, size_t len, size_t at, size_t *section_len,
                                        size_t *inner_off, size_t *inner_len, char *err, size_t errcap)
{
    *section_len = 0;
    *inner_off = 0;
    *inner_len = 0;
    if (len < GMMRRT_BACKGROUND_OVERHEAD)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_TRUNCATED, err, errcap,
                                "background section at byte %zu: %zu bytes, shorter than its %d-byte frame", at,
                                len, GMMRRT_BACKGROUND_OVERHEAD);
    const unsigned version = (unsigned)(buf[8] | (buf[9] << 8));
    if (version != GMMRRT_BACKGROUND_VERSION)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_VERSION, err, errcap,
                                "background section at byte %zu: version %u is not one this build reads (%d)", at,
                                version, GMMRRT_BACKGROUND_VERSION);
    const unsigned reserved = (unsigned)(buf[10] | (buf[11] << 8));
    if (reserved != 0)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_FIELD, err, errcap,
                                "background section at byte %zu: reserved = %u, must be 0", at, reserved);
    const uint32_t n = get_u32(buf + 12);
    const size_t min_model = GMMRRT_MODEL_HEADER_BYTES + 4u;
    if (n < min_model || n > gmmrrt_model_max_encoded_size())
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_SIZE, err, errcap,
                                "background section at byte %zu: model length %u is outside %zu..%zu", at,
                                (unsigned)n, min_model, gmmrrt_model_max_encoded_size());
    const size_t want = (size_t)GMMRRT_BACKGROUND_OVERHEAD + n;
    if (len < want)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_TRUNCATED, err, errcap,
                                "background section at byte %zu: %zu bytes, but its %u-byte model needs %zu: the "
                                "file is truncated",
                                at, len, (unsigned)n, want);
    const uint32_t stored = get_u32(buf + SECTION_HEAD + n);
    const uint32_t crc = gmmrrt_crc32(buf, SECTION_HEAD + n);
    if (crc != stored)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_CHECKSUM, err, errcap,
                                "background section at byte %zu: CRC-32 stored 0x%08X, computed 0x%08X: the "
                                "background model is corrupt",
                                at, (unsigned)stored, (unsigned)crc);
    /* The embedded model must fill the section exactly: its own D and K give its length, and
     * nothing (no section or trailer of its own) may follow it. */
    const uint8_t *inner = buf + SECTION_HEAD;
    const size_t own = gmmrrt_model_encoded_size(inner[15], (int32_t)(inner[16] | (inner[17] << 8)));
    if (memcmp(inner, GMMRRT_MODEL_MAGIC, 8) == 0 && own != 0 && own != n)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_SIZE, err, errcap,
                                "background section at byte %zu: the section holds %u bytes, but the embedded "
                                "model's D and K need %zu",
                                at, (unsigned)n, own);
    gmmrrt_model_frame_t frame;
    char why[200];
    const gmmrrt_status_t st = gmmrrt_model_check_frame(inner, n, &frame, why, sizeof why);
    if (st != GMMRRT_OK)
        return gmmrrt_set_error(st, err, errcap, "background section at byte %zu: the background model: %s", at,
                                why);
    *section_len = want;
    *inner_off = SECTION_HEAD;
    *inner_len = n;
    return GMMRRT_OK;
}

/* The background serves the task model's cost: the same features, so the same kind, task,
 * dimension and angles. */
static gmmrrt_status_t check_match(int32_t kind, int32_t task, int32_t dim, uint32_t angle_mask,
                                   const gmmrrt_model_t *bg, char *err, size_t errcap)
{
    if (bg->kind != kind || bg->task != task || bg->dim != dim || bg->angle_mask != angle_mask)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_MISMATCH, err, errcap,
                                "the background model (kind %d, task %d, D %d, angle mask 0x%X) does not match the "
                                "task model (kind %d, task %d, D %d, angle mask 0x%X)",
                                (int)bg->kind, (int)bg->task, (int)bg->dim, (unsigned)bg->angle_mask,
                                (int)kind, (int)task, (int)dim, (unsigned)angle_mask);
    return GMMRRT_OK;
}

gmmrrt_status_t gmmrrt_model_encode_file(const gmmrrt_model_t *model, const gmmrrt_model_t *background,
                                         const char *text, size_t text_len, uint8_t *buf, size_t cap,
                                         size_t *out_len, char *err, size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (model == NULL || out_len == NULL || (buf == NULL && cap > 0))
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "model, buf or out_len is NULL");
    *out_len = 0;
    gmmrrt_status_t st;
    if (text != NULL && (st = gmmrrt_provenance_text_check(text, text_len, err, errcap)) != GMMRRT_OK)
        return st;
    if (background != NULL && (st = check_match(model->kind, model->task, model->dim, model->angle_mask, background, err,
                                                      errcap)) != GMMRRT_OK)
        return st;
    size_t len = 0;
    if ((st = gmmrrt_model_encode(model, buf, cap, &len, err, errcap)) != GMMRRT_OK)
        return st;
    if (background != NULL) {
        const size_t n = gmmrrt_model_encoded_size(background->dim, background->k);
        if (n == 0 || cap < len + GMMRRT_BACKGROUND_OVERHEAD + n)
            return gmmrrt_set_error(GMMRRT_ERR_BUFFER_TOO_SMALL, err, errcap,
                                    "the model with its background needs %zu bytes, the buffer has %zu",
                                    len + GMMRRT_BACKGROUND_OVERHEAD + n, cap);
        uint8_t *p = buf + len;
        size_t got = 0;
        char why[200];
        st = gmmrrt_model_encode(background, p + SECTION_HEAD, n, &got, why, sizeof why);
        if (st != GMMRRT_OK)
            return gmmrrt_set_error(st, err, errcap, "the background model: %s", why);
        memcpy(p, GMMRRT_BACKGROUND_MAGIC, 8);
        p[8] = (uint8_t)(GMMRRT_BACKGROUND_VERSION & 0xFF);
        p[9] = (uint8_t)(GMMRRT_BACKGROUND_VERSION >> 8);
        p[10] = 0;
        p[11] = 0;
        put_u32(p + 12, (uint32_t)n);
        put_u32(p + SECTION_HEAD + n, gmmrrt_crc32(p, SECTION_HEAD + n));
        len += GMMRRT_BACKGROUND_OVERHEAD + n;
    }
    if (text != NULL) {
        if (cap < len + GMMRRT_PROVENANCE_OVERHEAD + text_len)
            return gmmrrt_set_error(GMMRRT_ERR_BUFFER_TOO_SMALL, err, errcap,
                                    "the model with its provenance needs %zu bytes, the buffer has %zu",
                                    len + GMMRRT_PROVENANCE_OVERHEAD + text_len, cap);
        gmmrrt_provenance_write(buf + len, text, text_len);
        len += GMMRRT_PROVENANCE_OVERHEAD + text_len;
    }
    *out_len = len;
    return GMMRRT_OK;
}

gmmrrt_status_t gmmrrt_model_background(const uint8_t *buf, size_t len, gmmrrt_model_t *out, int *has_background,
                                        char *err, size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (out == NULL || has_background == NULL || (buf == NULL && len > 0))
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "buf, out or has_background is NULL");
    *has_background = 0;
    gmmrrt_model_frame_t frame;
    gmmrrt_status_t st = gmmrrt_model_check_frame(buf, len, &frame, err, errcap);
    if (st != GMMRRT_OK)
        return st;
    if (frame.background_len == 0)
        return GMMRRT_OK;
    char why[200];
    st = gmmrrt_model_decode(buf + frame.background_off, frame.background_len, out, why, sizeof why);
    if (st != GMMRRT_OK)
        return gmmrrt_set_error(st, err, errcap, "background model at byte %zu: %s", frame.background_off, why);
    /* The task model's stored fields, for the match (its numbers are decode's business). */
    if ((st = check_match(buf[12], buf[13], buf[15], get_u32(buf + 20), out, err, errcap)) != GMMRRT_OK)
        return st;
    *has_background = 1;
    return GMMRRT_OK;
}
