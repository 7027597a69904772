/* planner.model: the binary model format (model.h, docs/model-format.md).
 * Round trip; a file assembled byte by byte in this test decodes to the right fields;
 * SQLite-style fault tests: every truncation length, every single bit flip, oversized
 * input; and each validation rule on a hand-made file whose CRC is correct, so that the
 * specific check (not the checksum) must reject it. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "gmmrrt/model.h"
#include "gmmrrt/rng.h"
#include "model_fixture.h"

/* Byte offsets in the fixture features file (D = 2, K = 3). */
enum {
    OFF_KIND = 12, OFF_TASK = 13, OFF_HOMOTOPY = 14, OFF_DIM = 15, OFF_K = 16, OFF_RESERVED = 18,
    OFF_MASK = 20, OFF_DELTA = 24, OFF_W = 32, OFF_MEAN = 32 + 3 * 8, OFF_CHOL = 32 + 3 * 8 + 6 * 8,
    FEATURES_LEN = 32 + 3 * (1 + 2 + 3) * 8 + 4
};

static size_t encode_fixture(uint8_t *buf, size_t cap)
{
    gmmrrt_model_t m;
    fixture_features_model(&m);
    size_t len = 0;
    char err[256];
    const gmmrrt_status_t st = gmmrrt_model_encode(&m, buf, cap, &len, err, sizeof err);
    if (st != GMMRRT_OK)
        fail_msg("encode: %s", err);
    assert_int_equal(len, FEATURES_LEN);
    return len;
}

static void refresh_crc(uint8_t *buf, size_t len)
{
    le_put_u32(buf + len - 4, gmmrrt_crc32(buf, len - 4));
}

/* Decodes buf into a heap copy of exactly len bytes (so a sanitizer sees any overread). */
static gmmrrt_status_t decode_exact(const uint8_t *buf, size_t len, gmmrrt_model_t *out, char *err,
                                    size_t errcap)
{
    uint8_t *copy = malloc(len ? len : 1);
    assert_non_null(copy);
    if (len)
        memcpy(copy, buf, len);
    const gmmrrt_status_t st = gmmrrt_model_decode(copy, len, out, err, errcap);
    free(copy);
    return st;
}

static void expect_status(const uint8_t *buf, size_t len, gmmrrt_status_t want, const char *want_in_msg)
{
    static gmmrrt_model_t scratch;
    char err[256] = "";
    const gmmrrt_status_t st = decode_exact(buf, len, &scratch, err, sizeof err);
    if (st != want)
        fail_msg("decode gave %d (%s: %s), expected %d (%s)", st, gmmrrt_status_str(st), err, want,
                 gmmrrt_status_str(want));
    if (want != GMMRRT_OK && err[0] == '\0')
        fail_msg("status %d without a message", st);
    if (want_in_msg != NULL && strstr(err, want_in_msg) == NULL)
        fail_msg("message \"%s\" does not mention \"%s\"", err, want_in_msg);
}

/* ------------------------------------------------------------------ basics */

static void test_crc32_matches_zlib_check_value(void **state)
{
    (void)state;
    /* The standard check value of CRC-32/ISO-HDLC (zlib.crc32(b"123456789")). */
    assert_int_equal(gmmrrt_crc32((const uint8_t *)"123456789", 9), 0xCBF43926u);
    assert_int_equal(gmmrrt_crc32((const uint8_t *)"", 0), 0u);
    /* zlib.crc32(b"GMMRRTMD") computed with Python. */
    assert_int_equal(gmmrrt_crc32((const uint8_t *)"GMMRRTMD", 8), 0xAC6470B9u);
}

static void test_encoded_size_follows_the_layout(void **state)
{
    (void)state;
    assert_int_equal(gmmrrt_model_encoded_size(2, 3), FEATURES_LEN);
    assert_int_equal(gmmrrt_model_encoded_size(2, 19), 32 + 19 * 6 * 8 + 4);
    assert_int_equal(gmmrrt_model_encoded_size(3, 1), 32 + 10 * 8 + 4);
    assert_int_equal(gmmrrt_model_encoded_size(0, 3), 0);
    assert_int_equal(gmmrrt_model_encoded_size(GMMRRT_MAX_DIM + 1, 3), 0);
    assert_int_equal(gmmrrt_model_encoded_size(2, 0), 0);
    assert_int_equal(gmmrrt_model_encoded_size(2, GMMRRT_MAX_K + 1), 0);
    assert_int_equal(gmmrrt_model_max_encoded_size(),
                     32 + GMMRRT_MAX_K * (1 + GMMRRT_MAX_DIM + GMMRRT_MAX_TRI) * 8 + 4);
}

static void test_round_trip_keeps_every_stored_field(void **state)
{
    (void)state;
    uint8_t buf[FEATURES_LEN];
    const size_t len = encode_fixture(buf, sizeof buf);
    gmmrrt_model_t in, out;
    fixture_features_model(&in);
    char err[256];
    assert_int_equal(gmmrrt_model_decode(buf, len, &out, err, sizeof err), GMMRRT_OK);
    assert_int_equal(out.kind, in.kind);
    assert_int_equal(out.task, in.task);
    assert_int_equal(out.homotopy, in.homotopy);
    assert_int_equal(out.dim, in.dim);
    assert_int_equal(out.k, in.k);
    assert_int_equal(out.angle_mask, in.angle_mask);
    assert_memory_equal(&out.delta, &in.delta, sizeof in.delta);
    assert_memory_equal(out.weight, in.weight, sizeof in.weight);
    assert_memory_equal(out.mean, in.mean, sizeof in.mean);
    assert_memory_equal(out.chol, in.chol, sizeof in.chol);
    /* Re-encoding the decoded model gives the same bytes. */
    uint8_t again[FEATURES_LEN];
    size_t len2 = 0;
    assert_int_equal(gmmrrt_model_encode(&out, again, sizeof again, &len2, err, sizeof err), GMMRRT_OK);
    assert_int_equal(len2, len);
    assert_memory_equal(again, buf, len);
}

static void test_prepare_derives_inverse_log_coef_and_cumulative_weights(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    fixture_generic_d4_model(&m);
    assert_int_equal(gmmrrt_model_prepare(&m, NULL, 0), GMMRRT_OK);
    const int d = m.dim;
    for (int i = 0; i < m.k; ++i) {
        /* L^-1 L == I, both packed lower triangles. */
        for (int r = 0; r < d; ++r)
            for (int c = 0; c < d; ++c) {
                double acc = 0.0;
                for (int s = c; s <= r; ++s)
                    acc += m.inv_chol[i][GMMRRT_TRI(r) + s] * m.chol[i][GMMRRT_TRI(s) + c];
                if (c > r)
                    continue;
                if (fabs(acc - (r == c ? 1.0 : 0.0)) > 1e-12)
                    fail_msg("component %d: (L^-1 L)[%d][%d] = %g", i, r, c, acc);
            }
        double log_det_half = 0.0;
        for (int j = 0; j < d; ++j)
            log_det_half += log(m.chol[i][GMMRRT_TRI(j) + j]);
        const double want = log(m.weight[i]) - 0.5 * d * log(2.0 * M_PI) - log_det_half;
        assert_true(fabs(m.log_coef[i] - want) < 1e-12);
    }
    assert_true(fabs(m.cum_weight[0] - 0.6) < 1e-15);
    assert_true(m.cum_weight[1] == 1.0);
}

/* A D = 1, K = 1 generic model written byte by byte here, not by the encoder. */
static void test_hand_assembled_little_endian_file_decodes(void **state)
{
    (void)state;
    uint8_t buf[32 + 3 * 8 + 4];
    memset(buf, 0, sizeof buf);
    memcpy(buf, "GMMRRTMD", 8);
    buf[8] = 1; buf[9] = 0;          /* version 1 */
    buf[10] = 0xFF; buf[11] = 0xFE;  /* byte-order mark 0xFEFF, little-endian */
    buf[12] = 3; buf[13] = 2; buf[14] = 3; buf[15] = 1; /* generic, approach, frontal, D = 1 */
    buf[16] = 1; buf[17] = 0;        /* K = 1 */
    buf[20] = 1;                     /* angle_mask: dimension 0 */
    le_put_f64(buf + 24, 0.125);     /* delta */
    le_put_f64(buf + 32, 1.0);       /* weight */
    le_put_f64(buf + 40, -2.5);      /* mean */
    le_put_f64(buf + 48, 0.75);      /* L00 */
    refresh_crc(buf, sizeof buf);
    gmmrrt_model_t m;
    char err[256];
    assert_int_equal(gmmrrt_model_decode(buf, sizeof buf, &m, err, sizeof err), GMMRRT_OK);
    assert_int_equal(m.kind, GMMRRT_MODEL_KIND_GENERIC);
    assert_int_equal(m.task, GMMRRT_TASK_APPROACH);
    assert_int_equal(m.homotopy, GMMRRT_HOMOTOPY_FRONTAL);
    assert_int_equal(m.dim, 1);
    assert_int_equal(m.k, 1);
    assert_int_equal(m.angle_mask, 1u);
    assert_true(m.delta == 0.125 && m.weight[0] == 1.0 && m.mean[0][0] == -2.5 && m.chol[0][0] == 0.75);
    assert_true(fabs(m.inv_chol[0][0] - 1.0 / 0.75) < 1e-15);
    /* And the encoder writes exactly these bytes. */
    uint8_t enc[sizeof buf];
    size_t len = 0;
    assert_int_equal(gmmrrt_model_encode(&m, enc, sizeof enc, &len, err, sizeof err), GMMRRT_OK);
    assert_int_equal(len, sizeof buf);
    assert_memory_equal(enc, buf, sizeof buf);
}

static void test_encode_short_buffer_writes_nothing_past_cap(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    fixture_features_model(&m);
    uint8_t buf[FEATURES_LEN];
    memset(buf, 0xA5, sizeof buf);
    size_t len = 99;
    char err[256];
    assert_int_equal(gmmrrt_model_encode(&m, buf, 100, &len, err, sizeof err), GMMRRT_ERR_BUFFER_TOO_SMALL);
    assert_int_equal(len, 0);
    assert_non_null(strstr(err, "180"));
    for (size_t i = 100; i < sizeof buf; ++i)
        assert_int_equal(buf[i], 0xA5);
}

static void test_encode_and_prepare_reject_invalid_models(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    uint8_t buf[FEATURES_LEN];
    size_t len = 0;
    char err[256];
    fixture_features_model(&m);
    m.weight[2] = 0.5; /* sum 1.1 */
    assert_int_equal(gmmrrt_model_encode(&m, buf, sizeof buf, &len, err, sizeof err), GMMRRT_ERR_MODEL_BAD_WEIGHTS);
    assert_int_equal(gmmrrt_model_prepare(&m, err, sizeof err), GMMRRT_ERR_MODEL_BAD_WEIGHTS);
    fixture_features_model(&m);
    m.dim = 0;
    assert_int_equal(gmmrrt_model_prepare(&m, err, sizeof err), GMMRRT_ERR_MODEL_BAD_SIZE);
    fixture_features_model(&m);
    m.k = GMMRRT_MAX_K + 1;
    assert_int_equal(gmmrrt_model_prepare(&m, err, sizeof err), GMMRRT_ERR_MODEL_BAD_SIZE);
    assert_int_equal(gmmrrt_model_prepare(NULL, err, sizeof err), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_int_equal(gmmrrt_model_encode(NULL, buf, sizeof buf, &len, err, sizeof err), GMMRRT_ERR_INVALID_ARGUMENT);
    assert_int_equal(gmmrrt_model_decode(NULL, 10, &m, err, sizeof err), GMMRRT_ERR_INVALID_ARGUMENT);
}

/* ------------------------------------------------------------------ fault tests */

static void test_every_truncation_length_is_rejected_as_truncated(void **state)
{
    (void)state;
    uint8_t buf[FEATURES_LEN];
    const size_t len = encode_fixture(buf, sizeof buf);
    for (size_t n = 0; n < len; ++n) {
        static gmmrrt_model_t scratch;
        char err[256] = "";
        const gmmrrt_status_t st = decode_exact(buf, n, &scratch, err, sizeof err);
        if (st != GMMRRT_ERR_MODEL_TRUNCATED)
            fail_msg("%zu of %zu bytes: status %d (%s)", n, len, st, err);
    }
    expect_status(buf, len, GMMRRT_OK, NULL);
}

static void test_every_single_bit_flip_is_rejected(void **state)
{
    (void)state;
    uint8_t buf[FEATURES_LEN];
    const size_t len = encode_fixture(buf, sizeof buf);
    for (size_t byte = 0; byte < len; ++byte)
        for (int bit = 0; bit < 8; ++bit) {
            static gmmrrt_model_t scratch;
            char err[256] = "";
            buf[byte] ^= (uint8_t)(1u << bit);
            const gmmrrt_status_t st = decode_exact(buf, len, &scratch, err, sizeof err);
            buf[byte] ^= (uint8_t)(1u << bit);
            gmmrrt_status_t allowed[3] = {GMMRRT_ERR_MODEL_BAD_CHECKSUM, GMMRRT_ERR_MODEL_BAD_CHECKSUM,
                                          GMMRRT_ERR_MODEL_BAD_CHECKSUM};
            if (byte < 8) allowed[0] = GMMRRT_ERR_MODEL_BAD_MAGIC;
            else if (byte < 10) allowed[0] = GMMRRT_ERR_MODEL_BAD_VERSION;
            else if (byte < 12) allowed[0] = GMMRRT_ERR_MODEL_BAD_BYTE_ORDER;
            else if (byte == OFF_DIM || byte == OFF_K || byte == OFF_K + 1) {
                allowed[0] = GMMRRT_ERR_MODEL_BAD_SIZE;   /* out of range, or longer than needed */
                allowed[1] = GMMRRT_ERR_MODEL_TRUNCATED;  /* the new D or K needs more bytes */
            } else if (byte == OFF_RESERVED || byte == OFF_RESERVED + 1)
                allowed[0] = GMMRRT_ERR_MODEL_BAD_FIELD;
            if (st != allowed[0] && st != allowed[1] && st != allowed[2])
                fail_msg("bit %d of byte %zu: status %d (%s: %s)", bit, byte, st, gmmrrt_status_str(st), err);
            if (err[0] == '\0')
                fail_msg("bit %d of byte %zu: no message", bit, byte);
        }
    expect_status(buf, len, GMMRRT_OK, NULL);
}

static void test_oversized_input_is_too_large_and_trailing_bytes_bad_size(void **state)
{
    (void)state;
    const size_t max = gmmrrt_model_max_encoded_size();
    /* The largest file: the largest model, the largest background section and the largest
     * provenance trailer. */
    const size_t max_file = gmmrrt_model_max_file_size();
    assert_int_equal(max_file, max + GMMRRT_BACKGROUND_OVERHEAD + max + GMMRRT_PROVENANCE_OVERHEAD +
                                   GMMRRT_MAX_PROVENANCE_BYTES);
    uint8_t *big = calloc(max_file + 4096, 1);
    assert_non_null(big);
    const size_t len = encode_fixture(big, max_file + 4096);
    expect_status(big, max_file + 1, GMMRRT_ERR_MODEL_TOO_LARGE, NULL);
    expect_status(big, max_file + 4096, GMMRRT_ERR_MODEL_TOO_LARGE, NULL);
    /* One trailing byte after a valid model: not a provenance trailer, not a valid model. */
    expect_status(big, len + 1, GMMRRT_ERR_MODEL_BAD_SIZE, "not a provenance trailer");
    expect_status(big, max + 1, GMMRRT_ERR_MODEL_BAD_SIZE, "not a provenance trailer");
    free(big);

    /* The largest valid model decodes. */
    gmmrrt_model_t *m = calloc(1, sizeof *m);
    uint8_t *buf = malloc(max);
    assert_non_null(m);
    assert_non_null(buf);
    m->kind = GMMRRT_MODEL_KIND_GENERIC;
    m->dim = GMMRRT_MAX_DIM;
    m->k = GMMRRT_MAX_K;
    m->delta = 1e-3;
    for (int i = 0; i < m->k; ++i) {
        m->weight[i] = 1.0 / m->k;
        for (int j = 0; j < m->dim; ++j)
            m->chol[i][GMMRRT_TRI(j) + j] = 1.0 + 0.01 * i;
    }
    size_t n = 0;
    char err[256];
    assert_int_equal(gmmrrt_model_encode(m, buf, max, &n, err, sizeof err), GMMRRT_OK);
    assert_int_equal(n, max);
    expect_status(buf, n, GMMRRT_OK, NULL);
    free(buf);
    free(m);
}

/* ------------------------------------------------------------------ each rule, valid CRC */

typedef struct {
    uint8_t b[FEATURES_LEN];
} file_t;

static file_t fresh(void)
{
    file_t f;
    encode_fixture(f.b, sizeof f.b);
    return f;
}

static void check(file_t *f, gmmrrt_status_t want, const char *msg)
{
    refresh_crc(f->b, sizeof f->b);
    expect_status(f->b, sizeof f->b, want, msg);
}

static void test_header_rules_each_give_their_status(void **state)
{
    (void)state;
    file_t f;
    f = fresh(); memcpy(f.b, "GMMRRTMX", 8); check(&f, GMMRRT_ERR_MODEL_BAD_MAGIC, "magic");
    f = fresh(); le_put_u16(f.b + 8, 2); check(&f, GMMRRT_ERR_MODEL_BAD_VERSION, "version 2");
    f = fresh(); le_put_u16(f.b + 8, 0); check(&f, GMMRRT_ERR_MODEL_BAD_VERSION, "version 0");
    f = fresh(); f.b[10] = 0xFE; f.b[11] = 0xFF; check(&f, GMMRRT_ERR_MODEL_BAD_BYTE_ORDER, "big-endian");
    f = fresh(); f.b[10] = 0; f.b[11] = 0; check(&f, GMMRRT_ERR_MODEL_BAD_BYTE_ORDER, "0x0000");
    f = fresh(); f.b[OFF_DIM] = 0; check(&f, GMMRRT_ERR_MODEL_BAD_SIZE, "D = 0");
    f = fresh(); f.b[OFF_DIM] = GMMRRT_MAX_DIM + 1; check(&f, GMMRRT_ERR_MODEL_BAD_SIZE, "dimension");
    f = fresh(); le_put_u16(f.b + OFF_K, 0); check(&f, GMMRRT_ERR_MODEL_BAD_SIZE, "K = 0");
    f = fresh(); le_put_u16(f.b + OFF_K, GMMRRT_MAX_K + 1); check(&f, GMMRRT_ERR_MODEL_BAD_SIZE, "component count");
    f = fresh(); le_put_u16(f.b + OFF_RESERVED, 7); check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "reserved");
    /* K = 2 needs fewer bytes than the file holds: trailing bytes. */
    f = fresh(); le_put_u16(f.b + OFF_K, 2); check(&f, GMMRRT_ERR_MODEL_BAD_SIZE, "need exactly");
    /* K = 4 needs more: truncated. */
    f = fresh(); le_put_u16(f.b + OFF_K, 4); check(&f, GMMRRT_ERR_MODEL_TRUNCATED, "needs");
    /* A correct file with a wrong CRC. */
    f = fresh(); f.b[FEATURES_LEN - 1] ^= 0x10;
    expect_status(f.b, sizeof f.b, GMMRRT_ERR_MODEL_BAD_CHECKSUM, "CRC");
}

static void test_field_rules_each_give_their_status(void **state)
{
    (void)state;
    file_t f;
    f = fresh(); f.b[OFF_KIND] = 0; check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "kind");
    f = fresh(); f.b[OFF_KIND] = 4; check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "kind");
    f = fresh(); f.b[OFF_KIND] = GMMRRT_MODEL_KIND_XY; check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "kind xy");
    f = fresh(); le_put_u32(f.b + OFF_MASK, 0); check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "angle_mask");
    f = fresh(); le_put_u32(f.b + OFF_MASK, 0x3); check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "angle_mask");
    /* Generic kind accepts any mask within D, but not a bit >= D. */
    f = fresh(); f.b[OFF_KIND] = GMMRRT_MODEL_KIND_GENERIC; le_put_u32(f.b + OFF_MASK, 0x3); check(&f, GMMRRT_OK, NULL);
    f = fresh(); f.b[OFF_KIND] = GMMRRT_MODEL_KIND_GENERIC; le_put_u32(f.b + OFF_MASK, 0x4); check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "dimension >= D");
    f = fresh(); f.b[OFF_KIND] = GMMRRT_MODEL_KIND_GENERIC; le_put_u32(f.b + OFF_MASK, 0x80000000u); check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "angle_mask");
    f = fresh(); f.b[OFF_TASK] = 3; check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "task");
    f = fresh(); f.b[OFF_HOMOTOPY] = 4; check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "homotopy");
    f = fresh(); le_put_f64(f.b + OFF_DELTA, 0.0); check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "delta");
    f = fresh(); le_put_f64(f.b + OFF_DELTA, -1e-3); check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "delta");
    f = fresh(); le_put_f64(f.b + OFF_DELTA, NAN); check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "delta");
    f = fresh(); le_put_f64(f.b + OFF_DELTA, INFINITY); check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "delta");
}

static void test_number_rules_each_give_their_status(void **state)
{
    (void)state;
    file_t f;
    /* Finite numbers. */
    f = fresh(); le_put_f64(f.b + OFF_W + 8, NAN); check(&f, GMMRRT_ERR_MODEL_NOT_FINITE, "component 1: weight");
    f = fresh(); le_put_f64(f.b + OFF_MEAN + 2 * 16, INFINITY); check(&f, GMMRRT_ERR_MODEL_NOT_FINITE, "component 2: mean[0]");
    f = fresh(); le_put_f64(f.b + OFF_CHOL + 8, -INFINITY); check(&f, GMMRRT_ERR_MODEL_NOT_FINITE, "component 0: Cholesky");
    f = fresh(); le_put_f64(f.b + OFF_CHOL + 3 * 8 + 8, NAN); check(&f, GMMRRT_ERR_MODEL_NOT_FINITE, "component 1: Cholesky factor entry 1");
    /* Weights. */
    f = fresh(); le_put_f64(f.b + OFF_W, 0.0); le_put_f64(f.b + OFF_W + 16, 0.65);
    check(&f, GMMRRT_ERR_MODEL_BAD_WEIGHTS, "component 0: weight");
    f = fresh(); le_put_f64(f.b + OFF_W, -0.25); check(&f, GMMRRT_ERR_MODEL_BAD_WEIGHTS, "component 0");
    f = fresh(); le_put_f64(f.b + OFF_W + 16, 1.5); check(&f, GMMRRT_ERR_MODEL_BAD_WEIGHTS, "component 2");
    f = fresh(); le_put_f64(f.b + OFF_W + 16, 0.40 + 1e-6); check(&f, GMMRRT_ERR_MODEL_BAD_WEIGHTS, "sum");
    f = fresh(); le_put_f64(f.b + OFF_W + 16, 0.40 + 5e-10); check(&f, GMMRRT_OK, NULL); /* within 1e-9 */
    f = fresh(); le_put_f64(f.b + OFF_W + 16, 0.40 + 2e-9); check(&f, GMMRRT_ERR_MODEL_BAD_WEIGHTS, "sum");
    /* Positive-definite factors: diagonal > 0, diagonal ratio <= 1e8. */
    f = fresh(); le_put_f64(f.b + OFF_CHOL + 3 * 8 + 2 * 8, 0.0); check(&f, GMMRRT_ERR_MODEL_NOT_POSITIVE_DEFINITE, "component 1: Cholesky diagonal L[1][1]");
    f = fresh(); le_put_f64(f.b + OFF_CHOL, -0.3); check(&f, GMMRRT_ERR_MODEL_NOT_POSITIVE_DEFINITE, "component 0: Cholesky diagonal L[0][0]");
    f = fresh(); le_put_f64(f.b + OFF_CHOL + 6 * 8, 0.25e9); check(&f, GMMRRT_ERR_MODEL_NOT_POSITIVE_DEFINITE, "component 2: Cholesky diagonal ratio");
    f = fresh(); le_put_f64(f.b + OFF_CHOL + 6 * 8, 0.25e7); check(&f, GMMRRT_OK, NULL);
    /* Off-diagonals may be anything finite... unless the inverse overflows. */
    f = fresh(); le_put_f64(f.b + OFF_CHOL + 8, -1e3); check(&f, GMMRRT_OK, NULL);
    f = fresh(); le_put_f64(f.b + OFF_CHOL, 1e-300); le_put_f64(f.b + OFF_CHOL + 2 * 8, 1e-300);
    le_put_f64(f.b + OFF_CHOL + 8, 1e10); check(&f, GMMRRT_ERR_MODEL_NOT_POSITIVE_DEFINITE, "inverted");
    /* Angle means in [-pi, pi]; the ends are accepted. */
    f = fresh(); le_put_f64(f.b + OFF_MEAN + 16 + 8, 3.2); check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "component 1: mean[1]");
    f = fresh(); le_put_f64(f.b + OFF_MEAN + 8, -M_PI - 1e-9); check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "angle");
    f = fresh(); le_put_f64(f.b + OFF_MEAN + 16 + 8, M_PI); check(&f, GMMRRT_OK, NULL);
    f = fresh(); le_put_f64(f.b + OFF_MEAN + 16 + 8, -M_PI); check(&f, GMMRRT_OK, NULL);
    /* A non-angle mean may be anything finite. */
    f = fresh(); le_put_f64(f.b + OFF_MEAN, -40.0); check(&f, GMMRRT_OK, NULL);
}

static void test_rules_are_checked_in_the_documented_order(void **state)
{
    (void)state;
    file_t f;
    /* Several faults at once: the earliest rule in the documented order wins. */
    f = fresh(); f.b[OFF_KIND] = 9; le_put_f64(f.b + OFF_W, NAN); check(&f, GMMRRT_ERR_MODEL_BAD_FIELD, "kind");
    f = fresh(); le_put_f64(f.b + OFF_W, NAN); le_put_f64(f.b + OFF_CHOL, -1.0); check(&f, GMMRRT_ERR_MODEL_NOT_FINITE, NULL);
    f = fresh(); le_put_f64(f.b + OFF_W, 2.0); le_put_f64(f.b + OFF_CHOL, -1.0); check(&f, GMMRRT_ERR_MODEL_BAD_WEIGHTS, NULL);
    f = fresh(); le_put_f64(f.b + OFF_CHOL, -1.0); le_put_f64(f.b + OFF_MEAN + 8, 4.0); check(&f, GMMRRT_ERR_MODEL_NOT_POSITIVE_DEFINITE, NULL);
    f = fresh(); le_put_u16(f.b + 8, 9); le_put_u16(f.b + 10, 0xFFFE); check(&f, GMMRRT_ERR_MODEL_BAD_VERSION, NULL);
    /* A bad CRC hides field errors: the checksum is checked before the fields. */
    f = fresh(); f.b[OFF_KIND] = 9; expect_status(f.b, sizeof f.b, GMMRRT_ERR_MODEL_BAD_CHECKSUM, NULL);
}

/* Random multi-field mutations with the CRC recomputed, so they reach the field and number
 * checks behind the checksum: decode must never crash (the sanitizer build watches reads),
 * and whatever it accepts must be a valid, prepared model that re-encodes to the same bytes. */
static void test_random_mutations_with_valid_crc_are_rejected_or_valid(void **state)
{
    (void)state;
    static const double specials[] = {0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 1e-300, 1e300, 4.9e-324,
                                      3.1415926535897931, 3.2, -3.2, 1e9, NAN, INFINITY, -INFINITY};
    const size_t n_specials = sizeof specials / sizeof specials[0];
    gmmrrt_model_t fixtures[2];
    fixture_features_model(&fixtures[0]);
    fixture_generic_d4_model(&fixtures[1]);
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, 8675309);
    long seen[64] = {0};
    for (int iter = 0; iter < 200000; ++iter) {
        uint8_t buf[1024], again[1024];
        size_t len = 0, len2 = 0;
        char err[256];
        assert_int_equal(gmmrrt_model_encode(&fixtures[iter & 1], buf, sizeof buf, &len, err, sizeof err), GMMRRT_OK);
        const int n_mut = 1 + (int)(gmmrrt_rng_next_u64(&rng) % 3);
        for (int k = 0; k < n_mut; ++k) {
            const uint64_t r = gmmrrt_rng_next_u64(&rng);
            if (r % 3 == 0) { /* one header byte (12..23) to a random value */
                buf[12 + (r >> 8) % 12] = (uint8_t)(r >> 40);
            } else { /* one f64 slot (delta or any number) to a special value */
                const size_t slots = (len - 4 - 24) / 8;
                le_put_f64(buf + 24 + 8 * ((r >> 8) % slots), specials[(r >> 40) % n_specials]);
            }
        }
        refresh_crc(buf, len);
        static gmmrrt_model_t m;
        const gmmrrt_status_t st = decode_exact(buf, len, &m, err, sizeof err);
        assert_true(st >= 0 && st < 64);
        ++seen[st];
        if (st != GMMRRT_OK) {
            if (err[0] == '\0')
                fail_msg("status %d without a message", st);
            continue;
        }
        double sum = 0.0;
        for (int i = 0; i < m.k; ++i) {
            sum += m.weight[i];
            assert_true(isfinite(m.log_coef[i]));
            for (int t = 0; t < GMMRRT_TRI(m.dim); ++t)
                assert_true(isfinite(m.inv_chol[i][t]));
        }
        assert_true(fabs(sum - 1.0) <= 1e-9 && m.cum_weight[m.k - 1] == 1.0 && m.delta > 0.0);
        assert_int_equal(gmmrrt_model_encode(&m, again, sizeof again, &len2, err, sizeof err), GMMRRT_OK);
        assert_int_equal(len2, len);
        assert_memory_equal(again, buf, len);
    }
    /* The mutations reached every check behind the CRC. */
    const gmmrrt_status_t deep[] = {GMMRRT_OK, GMMRRT_ERR_MODEL_BAD_SIZE, GMMRRT_ERR_MODEL_BAD_FIELD,
                                    GMMRRT_ERR_MODEL_NOT_FINITE, GMMRRT_ERR_MODEL_BAD_WEIGHTS,
                                    GMMRRT_ERR_MODEL_NOT_POSITIVE_DEFINITE, GMMRRT_ERR_MODEL_TRUNCATED};
    for (size_t i = 0; i < sizeof deep / sizeof deep[0]; ++i)
        if (seen[deep[i]] == 0)
            fail_msg("no mutation gave status %d (%s)", deep[i], gmmrrt_status_str(deep[i]));
}

/* A model learned for one task never serves the other; one without a task serves either. */
static void test_task_fits_its_own_task_or_none(void **state)
{
    (void)state;
    static gmmrrt_model_t m;
    fixture_features_model(&m);
    m.task = GMMRRT_TASK_AVOID;
    assert_int_equal(gmmrrt_model_task_fits(&m, GMMRRT_TASK_AVOID), GMMRRT_OK);
    assert_int_equal(gmmrrt_model_task_fits(&m, GMMRRT_TASK_APPROACH), GMMRRT_ERR_MODEL_MISMATCH);
    m.task = GMMRRT_TASK_APPROACH;
    assert_int_equal(gmmrrt_model_task_fits(&m, GMMRRT_TASK_APPROACH), GMMRRT_OK);
    assert_int_equal(gmmrrt_model_task_fits(&m, GMMRRT_TASK_AVOID), GMMRRT_ERR_MODEL_MISMATCH);
    m.task = GMMRRT_TASK_NONE;
    assert_int_equal(gmmrrt_model_task_fits(&m, GMMRRT_TASK_AVOID), GMMRRT_OK);
    assert_int_equal(gmmrrt_model_task_fits(&m, GMMRRT_TASK_APPROACH), GMMRRT_OK);
    assert_int_equal(gmmrrt_model_task_fits(NULL, GMMRRT_TASK_AVOID), GMMRRT_ERR_INVALID_ARGUMENT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crc32_matches_zlib_check_value),
        cmocka_unit_test(test_encoded_size_follows_the_layout),
        cmocka_unit_test(test_round_trip_keeps_every_stored_field),
        cmocka_unit_test(test_prepare_derives_inverse_log_coef_and_cumulative_weights),
        cmocka_unit_test(test_hand_assembled_little_endian_file_decodes),
        cmocka_unit_test(test_encode_short_buffer_writes_nothing_past_cap),
        cmocka_unit_test(test_encode_and_prepare_reject_invalid_models),
        cmocka_unit_test(test_every_truncation_length_is_rejected_as_truncated),
        cmocka_unit_test(test_every_single_bit_flip_is_rejected),
        cmocka_unit_test(test_oversized_input_is_too_large_and_trailing_bytes_bad_size),
        cmocka_unit_test(test_header_rules_each_give_their_status),
        cmocka_unit_test(test_field_rules_each_give_their_status),
        cmocka_unit_test(test_number_rules_each_give_their_status),
        cmocka_unit_test(test_rules_are_checked_in_the_documented_order),
        cmocka_unit_test(test_random_mutations_with_valid_crc_are_rejected_or_valid),
        cmocka_unit_test(test_task_fits_its_own_task_or_none),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
