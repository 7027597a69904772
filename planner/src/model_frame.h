/*
 * model_frame.h - the framing rules of a model file shared by gmmrrt_model_decode (model.c),
 * gmmrrt_model_provenance (model_provenance.c) and gmmrrt_model_background
 * (model_background.c): private to the core.
 */
#ifndef GMMRRT_MODEL_FRAME_H
#define GMMRRT_MODEL_FRAME_H

#include <stddef.h>
#include <stdint.h>

#include "gmmrrt/model.h"

/* Where the parts of a well-framed file lie (byte offsets into the file). */
typedef struct {
    size_t model_len;      /* the task model's encoded size E */
    size_t background_off; /* the embedded background model's first byte; 0 without a section */
    size_t background_len; /* its encoded size; 0 without a section */
    size_t text_off;       /* the provenance text; 0 without a trailer */
    size_t text_len;
    int has_provenance;    /* a provenance trailer is present (its text may be empty) */
} gmmrrt_model_frame_t;

/* Rules 1-9 of docs/model-format.md on buf[0..len): length bounds, magic, version, byte
 * order, D and K, reserved, length against D and K, the background section and the provenance
 * trailer when bytes follow the model, the model's CRC-32. On GMMRRT_OK *frame says where each
 * part is. Not the numbers of either model (gmmrrt_model_prepare). */
gmmrrt_status_t gmmrrt_model_check_frame(const uint8_t *buf, size_t len, gmmrrt_model_frame_t *frame, char *err,
                                         size_t errcap);

/* The background section at buf[0..len) (the bytes after the task model; `at` is their offset
 * in the file, for messages): its framing, its CRC-32 and the embedded model's own framing
 * (which must end exactly where the section says). On GMMRRT_OK *section_len is the section's
 * whole length and *inner_off / *inner_len locate the embedded model in buf. A buffer that does
 * not start with the section's magic is not examined: callers test the magic first. */
gmmrrt_status_t gmmrrt_background_check(const uint8_t *buf, size_t len, size_t at, size_t *section_len,
                                        size_t *inner_off, size_t *inner_len, char *err, size_t errcap);

/* Writes a provenance trailer holding text[0..text_len) (already checked: UTF-8, no NUL, at
 * most GMMRRT_MAX_PROVENANCE_BYTES) at p, which has room for GMMRRT_PROVENANCE_OVERHEAD +
 * text_len bytes. */
void gmmrrt_provenance_write(uint8_t *p, const char *text, size_t text_len);

/* Checks a provenance text for writing: BAD_FIELD (NUL or not UTF-8) or TOO_LARGE. */
gmmrrt_status_t gmmrrt_provenance_text_check(const char *text, size_t text_len, char *err, size_t errcap);

#endif /* GMMRRT_MODEL_FRAME_H */
