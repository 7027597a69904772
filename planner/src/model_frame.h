/*
 * model_frame.h - the framing rules of a model file shared by gmmrrt_model_decode (model.c)
 * and gmmrrt_model_provenance (model_provenance.c): private to the core.
 */
#ifndef GMMRRT_MODEL_FRAME_H
#define GMMRRT_MODEL_FRAME_H

#include <stddef.h>
#include <stdint.h>

#include "gmmrrt/model.h"

/* Rules 1-9 of docs/model-format.md on buf[0..len): length bounds, magic, version, byte
 * order, D and K, reserved, length against D and K, the provenance trailer when bytes follow
 * the model, the model's CRC-32. On GMMRRT_OK: *model_len = the model's encoded size, and
 * the provenance text is buf[*text_off .. *text_off + *text_len) (both 0 without a trailer;
 * *model_len < len tells a trailer is present). Not the model's numbers (gmmrrt_model_prepare). */
gmmrrt_status_t gmmrrt_model_check_frame(const uint8_t *buf, size_t len, size_t *model_len, size_t *text_off,
                                         size_t *text_len, char *err, size_t errcap);

#endif /* GMMRRT_MODEL_FRAME_H */
