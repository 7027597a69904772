/*
 * model_provenance.c - the provenance trailer of a model file (model.h, docs/model-format.md):
 * framing checks, encoding after the model, and reading the text back. The trailer follows
 * the model's own CRC-32 and carries its own, so the model bytes are those of a file without
 * provenance and a damaged trailer is reported as such.
 */
#include <string.h>

#include "error_text.h"
#include "gmmrrt/model.h"
#include "model_frame.h"

#define TRAILER_HEAD 16u /* magic, version, reserved, length */

static uint32_t get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static void put_u32(uint8_t *p, uint32_t v)
{
    for (int b = 0; b < 4; ++b)
        p[b] = (uint8_t)((v >> (8 * b)) & 0xFFu);
}

size_t gmmrrt_model_max_file_size(void)
{
    return gmmrrt_model_max_encoded_size() + GMMRRT_BACKGROUND_OVERHEAD + gmmrrt_model_max_encoded_size() +
           GMMRRT_PROVENANCE_OVERHEAD + GMMRRT_MAX_PROVENANCE_BYTES;
}

/* Offset of the first byte of s[0..n) that is not valid UTF-8 (RFC 3629: no overlong forms,
 * no surrogates, nothing above U+10FFFF) or is NUL; n when all are valid. */
static size_t utf8_bad_offset(const uint8_t *s, size_t n)
{
    size_t i = 0;
    while (i < n) {
        const uint8_t c = s[i];
        size_t more;
        uint32_t cp, min;
        if (c == 0)
            return i;
        if (c < 0x80) {
            ++i;
            continue;
        }
        if (c >= 0xC2 && c <= 0xDF) {
            more = 1; cp = c & 0x1Fu; min = 0x80;
        } else if (c >= 0xE0 && c <= 0xEF) {
            more = 2; cp = c & 0x0Fu; min = 0x800;
        } else if (c >= 0xF0 && c <= 0xF4) {
            more = 3; cp = c & 0x07u; min = 0x10000;
        } else {
            return i;
        }
        if (n - i <= more)
            return i;
        for (size_t m = 1; m <= more; ++m) {
            if ((s[i + m] & 0xC0u) != 0x80u)
                return i;
            cp = (cp << 6) | (s[i + m] & 0x3Fu);
        }
        if (cp < min || cp > 0x10FFFFu || (cp >= 0xD800u && cp <= 0xDFFFu))
            return i;
        i += more + 1;
    }
    return n;
}

gmmrrt_status_t gmmrrt_provenance_check(const uint8_t *buf, size_t len, size_t at, size_t *text_off,
                                        size_t *text_len, char *err, size_t errcap)
{
    *text_off = 0;
    *text_len = 0;
    /* A cut inside the magic is a truncated trailer; other bytes are not a trailer at all
     * (then the model's own length is what is wrong). */
    if (len < 8 && memcmp(buf, GMMRRT_PROVENANCE_MAGIC, len) == 0)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_TRUNCATED, err, errcap,
                                "provenance trailer at byte %zu: %zu bytes, shorter than its %d-byte frame", at,
                                len, GMMRRT_PROVENANCE_OVERHEAD);
    if (len < 8 || memcmp(buf, GMMRRT_PROVENANCE_MAGIC, 8) != 0)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_SIZE, err, errcap,
                                "%zu bytes follow the model's %zu bytes (D and K need exactly %zu), and they "
                                "are not a provenance trailer (magic \"GMMRRTPV\")",
                                len, at, at);
    if (len < GMMRRT_PROVENANCE_OVERHEAD)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_TRUNCATED, err, errcap,
                                "provenance trailer at byte %zu: %zu bytes, shorter than its %d-byte frame", at,
                                len, GMMRRT_PROVENANCE_OVERHEAD);
    const unsigned version = (unsigned)(buf[8] | (buf[9] << 8));
    if (version != GMMRRT_PROVENANCE_VERSION)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_VERSION, err, errcap,
                                "provenance trailer at byte %zu: version %u is not one this build reads (%d)", at,
                                version, GMMRRT_PROVENANCE_VERSION);
    const unsigned reserved = (unsigned)(buf[10] | (buf[11] << 8));
    if (reserved != 0)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_FIELD, err, errcap,
                                "provenance trailer at byte %zu: reserved = %u, must be 0", at, reserved);
    const uint32_t n = get_u32(buf + 12);
    if (n > GMMRRT_MAX_PROVENANCE_BYTES)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_TOO_LARGE, err, errcap,
                                "provenance trailer at byte %zu: text length %u exceeds %d bytes", at, (unsigned)n,
                                GMMRRT_MAX_PROVENANCE_BYTES);
    const size_t want = (size_t)GMMRRT_PROVENANCE_OVERHEAD + n;
    if (len < want)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_TRUNCATED, err, errcap,
                                "provenance trailer at byte %zu: %zu bytes, but its %u-byte text needs %zu: "
                                "the file is truncated",
                                at, len, (unsigned)n, want);
    if (len > want)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_SIZE, err, errcap,
                                "provenance trailer at byte %zu: %zu bytes, but its %u-byte text needs exactly %zu "
                                "(trailing bytes)",
                                at, len, (unsigned)n, want);
    const uint32_t stored = get_u32(buf + TRAILER_HEAD + n);
    const uint32_t crc = gmmrrt_crc32(buf, TRAILER_HEAD + n);
    if (crc != stored)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_CHECKSUM, err, errcap,
                                "provenance trailer at byte %zu: CRC-32 stored 0x%08X, computed 0x%08X: the "
                                "provenance is corrupt",
                                at, (unsigned)stored, (unsigned)crc);
    const size_t bad = utf8_bad_offset(buf + TRAILER_HEAD, n);
    if (bad != n)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_FIELD, err, errcap,
                                "provenance trailer at byte %zu: text byte %zu is NUL or not valid UTF-8", at,
                                bad);
    *text_off = TRAILER_HEAD;
    *text_len = n;
    return GMMRRT_OK;
}

gmmrrt_status_t gmmrrt_provenance_text_check(const char *text, size_t text_len, char *err, size_t errcap)
{
    if (text_len > GMMRRT_MAX_PROVENANCE_BYTES)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_TOO_LARGE, err, errcap,
                                "provenance text of %zu bytes exceeds %d bytes", text_len,
                                GMMRRT_MAX_PROVENANCE_BYTES);
    const size_t bad = utf8_bad_offset((const uint8_t *)text, text_len);
    if (bad != text_len)
        return gmmrrt_set_error(GMMRRT_ERR_MODEL_BAD_FIELD, err, errcap,
                                "provenance text byte %zu is NUL or not valid UTF-8", bad);
    return GMMRRT_OK;
}

void gmmrrt_provenance_write(uint8_t *p, const char *text, size_t text_len)
{
    memcpy(p, GMMRRT_PROVENANCE_MAGIC, 8);
    p[8] = (uint8_t)(GMMRRT_PROVENANCE_VERSION & 0xFF);
    p[9] = (uint8_t)(GMMRRT_PROVENANCE_VERSION >> 8);
    p[10] = 0;
    p[11] = 0;
    put_u32(p + 12, (uint32_t)text_len);
    if (text_len > 0)
        memcpy(p + TRAILER_HEAD, text, text_len);
    put_u32(p + TRAILER_HEAD + text_len, gmmrrt_crc32(p, TRAILER_HEAD + text_len));
}

gmmrrt_status_t gmmrrt_model_encode_provenance(const gmmrrt_model_t *model, const char *text, size_t text_len,
                                               uint8_t *buf, size_t cap, size_t *out_len, char *err,
                                               size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (out_len == NULL || (text == NULL && text_len > 0))
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "out_len or text is NULL");
    /* An empty text still writes an (empty) trailer: "" stands for text NULL, length 0. */
    return gmmrrt_model_encode_file(model, NULL, text != NULL ? text : "", text_len, buf, cap, out_len, err,
                                    errcap);
}

gmmrrt_status_t gmmrrt_model_provenance(const uint8_t *buf, size_t len, char *text, size_t cap, size_t *text_len,
                                        int *has_trailer, char *err, size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (text_len == NULL || (buf == NULL && len > 0) || (text == NULL && cap > 0))
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "buf, text or text_len is NULL");
    *text_len = 0;
    if (has_trailer != NULL)
        *has_trailer = 0;
    gmmrrt_model_frame_t frame;
    const gmmrrt_status_t st = gmmrrt_model_check_frame(buf, len, &frame, err, errcap);
    if (st != GMMRRT_OK)
        return st;
    const size_t off = frame.text_off, n = frame.text_len;
    if (cap < n + 1)
        return gmmrrt_set_error(GMMRRT_ERR_BUFFER_TOO_SMALL, err, errcap,
                                "the provenance text needs %zu bytes with its terminator, the buffer has %zu",
                                n + 1, cap);
    if (n > 0)
        memcpy(text, buf + off, n);
    text[n] = '\0';
    *text_len = n;
    if (has_trailer != NULL)
        *has_trailer = frame.has_provenance;
    return GMMRRT_OK;
}
