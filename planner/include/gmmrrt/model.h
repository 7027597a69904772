/*
 * model.h - a Gaussian mixture model (paper eq. 1) and its binary file format.
 *
 *   p(f) = sum_i w_i N(f; mu_i, Sigma_i),   Sigma_i = L_i L_i^T
 *
 * Dimensions flagged in angle_mask are angles in radians, wrapped: their density is the
 * wrapped normal (the sum over the images f + 2 pi n, n in {-1, 0, 1}), their means lie
 * in [-pi, pi]. Density and sampling live in gmm.h; the byte layout is specified in
 * docs/model-format.md. The learner writes models with gmmrrt_model_encode() and the
 * planner reads them with gmmrrt_model_decode(): one implementation of the format.
 *
 * Memory: gmmrrt_model_t is a plain fixed-size struct (no pointers); callers own it.
 * Loading follows the cFE table pattern: decode into a scratch model, and only when
 * the call returns GMMRRT_OK copy it over the one in use.
 */
#ifndef GMMRRT_MODEL_H
#define GMMRRT_MODEL_H

#include <stddef.h>
#include <stdint.h>

#include "gmmrrt/limits.h"
#include "gmmrrt/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define GMMRRT_MODEL_MAGIC "GMMRRTMD"   /* 8 bytes, no terminator in the file */
#define GMMRRT_MODEL_FORMAT_VERSION 1
#define GMMRRT_MODEL_HEADER_BYTES 32
#define GMMRRT_MODEL_DEFAULT_DELTA 0.001 /* the paper's delta (Sect. 5.1) */

/* What the mixture's dimensions mean. */
typedef enum {
    GMMRRT_MODEL_KIND_FEATURES = 1, /* D = 2: (d [m], theta [rad, angle]) in the person's frame; GMM-RRT* */
    GMMRRT_MODEL_KIND_XY = 2,       /* D = 3: (s [progress 0..1], x' [m], y' [m]) in the person's frame;
                                       components sorted by mean s; the GMM-RRT baseline */
    GMMRRT_MODEL_KIND_GENERIC = 3   /* any D: user features (gmmrrt-learn --features-csv) */
} gmmrrt_model_kind_t;

/* Values equal nav_goal_t.TASK_* and demo_info_t.HOMOTOPY_* on the wire. */
typedef enum { GMMRRT_TASK_NONE = 0, GMMRRT_TASK_AVOID = 1, GMMRRT_TASK_APPROACH = 2 } gmmrrt_task_t;
typedef enum {
    GMMRRT_HOMOTOPY_ALL = 0,
    GMMRRT_HOMOTOPY_LEFT = 1,
    GMMRRT_HOMOTOPY_RIGHT = 2,
    GMMRRT_HOMOTOPY_FRONTAL = 3
} gmmrrt_homotopy_t;

typedef struct {
    /* Stored in the file. */
    int32_t kind;        /* gmmrrt_model_kind_t */
    int32_t task;        /* gmmrrt_task_t */
    int32_t homotopy;    /* gmmrrt_homotopy_t */
    int32_t dim;         /* D, 1..GMMRRT_MAX_DIM */
    int32_t k;           /* K, 1..GMMRRT_MAX_K */
    uint32_t angle_mask; /* bit j set: dimension j is a wrapped angle */
    double delta;        /* default delta of the task cost delta / max(p, delta); > 0 */
    double weight[GMMRRT_MAX_K];                /* w_i in (0, 1], sum 1 */
    double mean[GMMRRT_MAX_K][GMMRRT_MAX_DIM];  /* mu_i */
    double chol[GMMRRT_MAX_K][GMMRRT_MAX_TRI];  /* L_i packed row-major lower triangle:
                                                   L00, L10, L11, L20, L21, L22, ... */

    /* Derived by gmmrrt_model_prepare() (decode calls it); never stored. */
    double inv_chol[GMMRRT_MAX_K][GMMRRT_MAX_TRI]; /* L_i^-1, packed like chol */
    double log_coef[GMMRRT_MAX_K];  /* log w_i - D/2 log(2 pi) - sum_j log L_i,jj */
    double cum_weight[GMMRRT_MAX_K];/* running sum of w_i, last = 1, for sampling */
} gmmrrt_model_t;

/* Bytes of the encoded model: header + K (1 + D + D(D+1)/2) doubles + CRC-32.
 * 0 when dim or k is outside the limits. */
size_t gmmrrt_model_encoded_size(int32_t dim, int32_t k);

/* Largest valid file this build accepts (GMMRRT_MAX_DIM, GMMRRT_MAX_K). */
size_t gmmrrt_model_max_encoded_size(void);

/* Validates `model` (as gmmrrt_model_prepare would, on a copy) and writes its encoding
 * to buf[cap]; *out_len gets the byte count. GMMRRT_ERR_BUFFER_TOO_SMALL when cap is
 * short (nothing written beyond cap); a model-specific status when the model is invalid,
 * with a message in err[errcap] (err may be NULL). */
gmmrrt_status_t gmmrrt_model_encode(const gmmrrt_model_t *model, uint8_t *buf, size_t cap,
                                    size_t *out_len, char *err, size_t errcap);

/* Parses and validates len bytes at buf into *out: magic, version, byte order, sizes
 * against len, CRC-32, the framing of the background section and of the provenance trailer
 * when bytes follow the model (below; neither is stored in *out: gmmrrt_model_background and
 * gmmrrt_model_provenance read them), K and D within limits.h, kind/task/homotopy/angle flags known,
 * finite numbers, positive-definite factors, weights summing to 1 (|sum - 1| <= 1e-9),
 * then derives the prepared fields. Never reads outside buf[0..len). On failure returns
 * the specific GMMRRT_ERR_MODEL_* status, writes the reason into err[errcap], and leaves
 * *out unspecified: decode into a scratch model. */
gmmrrt_status_t gmmrrt_model_decode(const uint8_t *buf, size_t len, gmmrrt_model_t *out, char *err,
                                    size_t errcap);

/* Validates the stored fields of `model` and fills the derived ones. Used by decode and
 * by writers that build a model in memory (the learner, tests). */
gmmrrt_status_t gmmrrt_model_prepare(gmmrrt_model_t *model, char *err, size_t errcap);

/* sizeof(gmmrrt_model_t) in this build, for callers that allocate it without the header
 * (the Python tools through ctypes). */
size_t gmmrrt_model_sizeof(void);

/* Builds *out from flat arrays and prepares it (gmmrrt_model_prepare: every stored field is
 * validated): weight[k], mean[k * dim] row by row, chol[k * GMMRRT_TRI(dim)] each factor
 * packed as in gmmrrt_model_t. For writers in other languages, which then encode with
 * gmmrrt_model_encode or gmmrrt_model_save_file: the file format stays in model.c.
 * Returns GMMRRT_OK, GMMRRT_ERR_INVALID_ARGUMENT (a NULL pointer), GMMRRT_ERR_MODEL_BAD_SIZE
 * (dim or k outside limits.h) or the status of gmmrrt_model_prepare, with the reason in err. */
gmmrrt_status_t gmmrrt_model_from_arrays(int32_t kind, int32_t task, int32_t homotopy, int32_t dim, int32_t k,
                                         uint32_t angle_mask, double delta, const double *weight,
                                         const double *mean, const double *chol, gmmrrt_model_t *out, char *err,
                                         size_t errcap);

/* The stored fields of a valid model (decoded or prepared) into flat arrays laid out as for
 * gmmrrt_model_from_arrays: header[6] = kind, task, homotopy, dim, k, angle_mask; *delta;
 * weight[k], mean[k * dim], chol[k * GMMRRT_TRI(dim)] (caller-sized from header: call with
 * the sizes of GMMRRT_MAX_K and GMMRRT_MAX_DIM, or read dim and k first from a decoded model). */
void gmmrrt_model_to_arrays(const gmmrrt_model_t *model, int32_t *header, double *delta, double *weight,
                            double *mean, double *chol);

/* Whether a model may serve goals of `task` (gmmrrt_task_t; paper Sect. 5: one mixture per
 * task): a model learned for one task never plans the other, and a model without a task
 * (GMMRRT_TASK_NONE, e.g. an x-y or generic one) serves either. The rule of every caller that
 * pairs a model with a task (gmmrrtd's model slots, gmmrrt-plan's --task and --model).
 * GMMRRT_OK, GMMRRT_ERR_MODEL_MISMATCH, or GMMRRT_ERR_INVALID_ARGUMENT for a NULL model. */
gmmrrt_status_t gmmrrt_model_task_fits(const gmmrrt_model_t *model, int32_t task);

/* ------------------------------------------------------------------ provenance trailer
 *
 * A model file may end with a provenance trailer after the model's CRC-32: what the model was
 * learned from (the learner writes a JSON object: data hash, command line, seed, K, BIC,
 * log-likelihood, learner version, UTC time). The core treats the text as opaque UTF-8 and
 * checks only its framing; gmmrrt_model_t is unchanged (fixed memory), the text goes to a
 * caller's buffer. Layout (docs/model-format.md), E = gmmrrt_model_encoded_size(D, K):
 *   E      8  magic "GMMRRTPV"
 *   E + 8  2  u16 trailer version (1)
 *   E + 10 2  u16 reserved (0)
 *   E + 12 4  u32 text length n, 0..GMMRRT_MAX_PROVENANCE_BYTES
 *   E + 16 n  text: valid UTF-8, no NUL byte
 *   E+16+n 4  u32 CRC-32 of the trailer bytes E .. E + 16 + n
 * gmmrrt_model_decode accepts a file with or without a valid trailer and refuses a corrupt
 * one (TRUNCATED, BAD_SIZE, BAD_VERSION, BAD_FIELD or BAD_CHECKSUM, the message names the
 * provenance trailer). */
#define GMMRRT_PROVENANCE_MAGIC "GMMRRTPV" /* 8 bytes, no terminator in the file */
#define GMMRRT_PROVENANCE_VERSION 1
#define GMMRRT_PROVENANCE_OVERHEAD 20 /* magic, version, reserved, length, CRC-32 */

/* Largest valid file this build accepts: the largest model, the largest background section and
 * the largest trailer. */
size_t gmmrrt_model_max_file_size(void);

/* As gmmrrt_model_encode, then appends a provenance trailer holding text[0..text_len) (text
 * may be NULL when text_len is 0, which still writes an empty trailer). The text must be valid
 * UTF-8 without NUL bytes and at most GMMRRT_MAX_PROVENANCE_BYTES long (BAD_FIELD / TOO_LARGE
 * otherwise, nothing written). */
gmmrrt_status_t gmmrrt_model_encode_provenance(const gmmrrt_model_t *model, const char *text, size_t text_len,
                                               uint8_t *buf, size_t cap, size_t *out_len, char *err,
                                               size_t errcap);

/* The provenance text of the model file buf[0..len): checks the file's framing as decode does
 * (header, lengths, model CRC-32, the trailer's rules; not the model's numbers: decode the model
 * for those) and copies the text, NUL-terminated, into text[cap]; *text_len gets its length.
 * A file without a trailer gives GMMRRT_OK, *text_len = 0 and *has_trailer = 0 (has_trailer
 * may be NULL). GMMRRT_ERR_BUFFER_TOO_SMALL when cap < text length + 1. */
gmmrrt_status_t gmmrrt_model_provenance(const uint8_t *buf, size_t len, char *text, size_t cap, size_t *text_len,
                                        int *has_trailer, char *err, size_t errcap);

/* Checks the trailer at buf[0..len) (the bytes after the model's CRC-32; `at` is their offset
 * in the file, for messages) and gives the text's offset in buf and its length. Used by decode
 * and gmmrrt_model_provenance; status and message as documented above. */
gmmrrt_status_t gmmrrt_provenance_check(const uint8_t *buf, size_t len, size_t at, size_t *text_off,
                                        size_t *text_len, char *err, size_t errcap);

/* ------------------------------------------------------------------ background section
 *
 * A model file may carry a second mixture, the task model's background: the density of the
 * same features where the demonstrators would have been had they not reacted to the person
 * (for GMMRRT_TASK_COST_BACKGROUND, config.h; docs/planner.md, "The background cost"). It is
 * a complete model encoding (gmmrrt_model_encode, its own header and CRC-32) wrapped in a
 * section between the task model's CRC-32 and the provenance trailer, so the task model's
 * bytes are those of a file without it and gmmrrt_model_t stays one mixture (fixed memory).
 * Layout (docs/model-format.md), E = gmmrrt_model_encoded_size(D, K):
 *   E      8  magic "GMMRRTBG"
 *   E + 8  2  u16 section version (1)
 *   E + 10 2  u16 reserved (0)
 *   E + 12 4  u32 n: the embedded model's length, gmmrrt_model_encoded_size of its D and K
 *   E + 16 n  the background model, as gmmrrt_model_encode writes it (no trailer of its own)
 *   E+16+n 4  u32 CRC-32 of the section bytes E .. E + 16 + n
 * gmmrrt_model_decode checks the section's framing and the embedded model's framing and
 * CRC-32 and ignores it otherwise; gmmrrt_model_background decodes it and checks it against
 * the task model (same kind, task, D and angle mask: it is a density over the same features). */
#define GMMRRT_BACKGROUND_MAGIC "GMMRRTBG" /* 8 bytes, no terminator in the file */
#define GMMRRT_BACKGROUND_VERSION 1
#define GMMRRT_BACKGROUND_OVERHEAD 20 /* magic, version, reserved, length, CRC-32 */

/* Encodes a whole file: model, then a background section holding `background` when it is not
 * NULL, then a provenance trailer holding text[0..text_len) when text is not NULL (an empty
 * text writes an empty trailer). Both models are validated (the statuses of
 * gmmrrt_model_encode, the message naming which model); the background must match the model
 * (kind, task, D, angle mask: GMMRRT_ERR_MODEL_MISMATCH); the text as in
 * gmmrrt_model_encode_provenance. GMMRRT_ERR_BUFFER_TOO_SMALL when cap is short
 * (gmmrrt_model_max_file_size() always suffices). Nothing is trusted in buf unless GMMRRT_OK. */
gmmrrt_status_t gmmrrt_model_encode_file(const gmmrrt_model_t *model, const gmmrrt_model_t *background,
                                         const char *text, size_t text_len, uint8_t *buf, size_t cap,
                                         size_t *out_len, char *err, size_t errcap);

/* The background model of the model file buf[0..len), decoded and validated into *out (decode
 * into a scratch model, as for gmmrrt_model_decode). The file's framing is checked as decode
 * does (not the task model's numbers: decode it for those). A file without a background
 * section gives GMMRRT_OK with *has_background = 0 and *out untouched; with one,
 * *has_background = 1, or the status of the embedded model's decode (the message says
 * "background model") or GMMRRT_ERR_MODEL_MISMATCH when it does not match the task model. */
gmmrrt_status_t gmmrrt_model_background(const uint8_t *buf, size_t len, gmmrrt_model_t *out, int *has_background,
                                        char *err, size_t errcap);

/* CRC-32 (IEEE 802.3 / zlib polynomial, reflected, init and final xor 0xFFFFFFFF), so
 * Python's zlib.crc32 checks files too. */
uint32_t gmmrrt_crc32(const uint8_t *data, size_t len);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_MODEL_H */
