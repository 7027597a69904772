/* planner.model_provenance: the provenance trailer after a model (model.h, model_file.h,
 * docs/model-format.md). Round trip in memory and through a file; a file without a trailer
 * still decodes and has no provenance; every truncation and every single bit flip of the
 * trailer is refused with a message naming the trailer; each trailer rule on a hand-made
 * trailer whose CRC is correct; the writer refuses text it could not read back. */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

#include "gmmrrt/model.h"
#include "gmmrrt/model_file.h"
#include "model_fixture.h"

#define FEATURES_LEN (32 + 3 * (1 + 2 + 3) * 8 + 4) /* the fixture model, D = 2, K = 3 */

static const char kText[] = "{\"learner\":\"gmmrrt-learn test\",\"seed\":7,\"note\":\"caf\xc3\xa9 \xe2\x9c\x93\"}";

/* Encodes the fixture with kText; returns the length. */
static size_t encode_with_text(uint8_t *buf, size_t cap)
{
    gmmrrt_model_t m;
    fixture_features_model(&m);
    size_t len = 0;
    char err[256];
    if (gmmrrt_model_encode_provenance(&m, kText, strlen(kText), buf, cap, &len, err, sizeof err) != GMMRRT_OK)
        fail_msg("encode_provenance: %s", err);
    assert_int_equal(len, FEATURES_LEN + GMMRRT_PROVENANCE_OVERHEAD + strlen(kText));
    return len;
}

/* Decodes an exact heap copy (a sanitizer sees any overread); checks status and message. */
static void expect_status(const uint8_t *buf, size_t len, gmmrrt_status_t want, const char *want_in_msg)
{
    static gmmrrt_model_t scratch;
    uint8_t *copy = malloc(len ? len : 1);
    assert_non_null(copy);
    memcpy(copy, buf, len);
    char err[320] = "";
    const gmmrrt_status_t st = gmmrrt_model_decode(copy, len, &scratch, err, sizeof err);
    /* The provenance reader applies the same framing rules. */
    char text[GMMRRT_MAX_PROVENANCE_BYTES + 1];
    size_t n = 0;
    char err2[320] = "";
    const gmmrrt_status_t st2 = gmmrrt_model_provenance(copy, len, text, sizeof text, &n, NULL, err2, sizeof err2);
    free(copy);
    if (st != want)
        fail_msg("decode gave %d (%s: %s), expected %d (%s)", st, gmmrrt_status_str(st), err, want,
                 gmmrrt_status_str(want));
    if (st2 != want)
        fail_msg("provenance gave %d (%s: %s), expected %d", st2, gmmrrt_status_str(st2), err2, want);
    if (want != GMMRRT_OK && err[0] == '\0')
        fail_msg("status %d without a message", st);
    if (want_in_msg != NULL && (strstr(err, want_in_msg) == NULL || strstr(err2, want_in_msg) == NULL))
        fail_msg("messages \"%s\" / \"%s\" do not mention \"%s\"", err, err2, want_in_msg);
}

static void refresh_trailer_crc(uint8_t *buf, size_t len)
{
    le_put_u32(buf + len - 4, gmmrrt_crc32(buf + FEATURES_LEN, len - 4 - FEATURES_LEN));
}

static void test_round_trip_keeps_model_bytes_and_text(void **state)
{
    (void)state;
    uint8_t with[FEATURES_LEN + GMMRRT_PROVENANCE_OVERHEAD + 256], plain[FEATURES_LEN];
    const size_t len = encode_with_text(with, sizeof with);
    gmmrrt_model_t m, a, b;
    fixture_features_model(&m);
    size_t plain_len = 0;
    assert_int_equal(gmmrrt_model_encode(&m, plain, sizeof plain, &plain_len, NULL, 0), GMMRRT_OK);
    /* The model's bytes are those of a file without provenance. */
    assert_memory_equal(with, plain, FEATURES_LEN);
    assert_memory_equal(with + FEATURES_LEN, GMMRRT_PROVENANCE_MAGIC, 8);
    char err[256];
    assert_int_equal(gmmrrt_model_decode(with, len, &a, err, sizeof err), GMMRRT_OK);
    assert_int_equal(gmmrrt_model_decode(plain, plain_len, &b, err, sizeof err), GMMRRT_OK);
    assert_memory_equal(&a, &b, sizeof a);
    char text[GMMRRT_MAX_PROVENANCE_BYTES + 1];
    size_t n = 0;
    int has = -1;
    assert_int_equal(gmmrrt_model_provenance(with, len, text, sizeof text, &n, &has, err, sizeof err), GMMRRT_OK);
    assert_int_equal(has, 1);
    assert_int_equal(n, strlen(kText));
    assert_string_equal(text, kText);
    /* Too small a buffer for the text and its terminator. */
    assert_int_equal(gmmrrt_model_provenance(with, len, text, strlen(kText), &n, &has, err, sizeof err),
                     GMMRRT_ERR_BUFFER_TOO_SMALL);
    /* An empty text is a valid (empty) trailer. */
    size_t elen = 0;
    assert_int_equal(gmmrrt_model_encode_provenance(&m, NULL, 0, with, sizeof with, &elen, err, sizeof err),
                     GMMRRT_OK);
    assert_int_equal(elen, FEATURES_LEN + GMMRRT_PROVENANCE_OVERHEAD);
    assert_int_equal(gmmrrt_model_provenance(with, elen, text, sizeof text, &n, &has, err, sizeof err), GMMRRT_OK);
    assert_int_equal(has, 1);
    assert_int_equal(n, 0);
}

static void test_file_without_trailer_has_no_provenance(void **state)
{
    (void)state;
    uint8_t plain[FEATURES_LEN];
    gmmrrt_model_t m;
    fixture_features_model(&m);
    size_t len = 0;
    assert_int_equal(gmmrrt_model_encode(&m, plain, sizeof plain, &len, NULL, 0), GMMRRT_OK);
    expect_status(plain, len, GMMRRT_OK, NULL);
    char text[8] = "x";
    size_t n = 99;
    int has = -1;
    assert_int_equal(gmmrrt_model_provenance(plain, len, text, sizeof text, &n, &has, NULL, 0), GMMRRT_OK);
    assert_int_equal(has, 0);
    assert_int_equal(n, 0);
    assert_string_equal(text, "");
}

static void test_every_truncation_of_the_trailer_is_truncated(void **state)
{
    (void)state;
    uint8_t buf[FEATURES_LEN + GMMRRT_PROVENANCE_OVERHEAD + 256];
    const size_t len = encode_with_text(buf, sizeof buf);
    for (size_t cut = FEATURES_LEN + 1; cut < len; ++cut)
        expect_status(buf, cut, GMMRRT_ERR_MODEL_TRUNCATED, "provenance trailer");
    expect_status(buf, len, GMMRRT_OK, NULL);
}

static void test_every_bit_flip_of_the_trailer_is_refused(void **state)
{
    (void)state;
    uint8_t buf[FEATURES_LEN + GMMRRT_PROVENANCE_OVERHEAD + 256];
    const size_t len = encode_with_text(buf, sizeof buf);
    for (size_t byte = FEATURES_LEN; byte < len; ++byte)
        for (int bit = 0; bit < 8; ++bit) {
            buf[byte] ^= (uint8_t)(1u << bit);
            gmmrrt_model_t m;
            char err[320] = "";
            const gmmrrt_status_t st = gmmrrt_model_decode(buf, len, &m, err, sizeof err);
            buf[byte] ^= (uint8_t)(1u << bit);
            if (st == GMMRRT_OK)
                fail_msg("bit %d of byte %zu: a damaged trailer was accepted", bit, byte);
            if (strstr(err, "provenance") == NULL)
                fail_msg("bit %d of byte %zu: message \"%s\" does not name the provenance trailer", bit, byte, err);
            /* Text and CRC bytes: only the trailer's checksum can tell. */
            if (byte >= FEATURES_LEN + 16 && st != GMMRRT_ERR_MODEL_BAD_CHECKSUM)
                fail_msg("bit %d of byte %zu: status %d, expected the trailer's checksum", bit, byte, st);
        }
    expect_status(buf, len, GMMRRT_OK, NULL);
}

static void test_each_trailer_rule_with_a_correct_crc(void **state)
{
    (void)state;
    uint8_t good[FEATURES_LEN + GMMRRT_PROVENANCE_OVERHEAD + 256], b[sizeof good + 1];
    const size_t len = encode_with_text(good, sizeof good);
    const size_t t = FEATURES_LEN; /* trailer offset */

    memcpy(b, good, len); b[t + 7] = 'X';
    expect_status(b, len, GMMRRT_ERR_MODEL_BAD_SIZE, "not a provenance trailer");
    memcpy(b, good, len); le_put_u16(b + t + 8, 2); refresh_trailer_crc(b, len);
    expect_status(b, len, GMMRRT_ERR_MODEL_BAD_VERSION, "version 2");
    memcpy(b, good, len); le_put_u16(b + t + 10, 1); refresh_trailer_crc(b, len);
    expect_status(b, len, GMMRRT_ERR_MODEL_BAD_FIELD, "reserved");
    memcpy(b, good, len); le_put_u32(b + t + 12, GMMRRT_MAX_PROVENANCE_BYTES + 1); refresh_trailer_crc(b, len);
    expect_status(b, len, GMMRRT_ERR_MODEL_TOO_LARGE, "exceeds");
    /* A length one short leaves a trailing byte; one long runs past the end. */
    memcpy(b, good, len); le_put_u32(b + t + 12, (uint32_t)strlen(kText) - 1);
    expect_status(b, len, GMMRRT_ERR_MODEL_BAD_SIZE, "trailing");
    memcpy(b, good, len); le_put_u32(b + t + 12, (uint32_t)strlen(kText) + 1);
    expect_status(b, len, GMMRRT_ERR_MODEL_TRUNCATED, "truncated");
    /* One byte after a complete trailer. */
    memcpy(b, good, len); b[len] = 0;
    expect_status(b, len + 1, GMMRRT_ERR_MODEL_BAD_SIZE, "trailing");
    /* Text that is not UTF-8, or holds a NUL, with a correct CRC. */
    memcpy(b, good, len); b[t + 16 + 3] = 0xFF; refresh_trailer_crc(b, len);
    expect_status(b, len, GMMRRT_ERR_MODEL_BAD_FIELD, "UTF-8");
    memcpy(b, good, len); b[t + 16 + 3] = 0x00; refresh_trailer_crc(b, len);
    expect_status(b, len, GMMRRT_ERR_MODEL_BAD_FIELD, "NUL");
    /* A damaged model before a good trailer is still the model's checksum error. */
    memcpy(b, good, len); b[40] ^= 1;
    expect_status(b, len, GMMRRT_ERR_MODEL_BAD_CHECKSUM, "the file is corrupt");
}

static void test_writer_refuses_text_it_could_not_read_back(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    fixture_features_model(&m);
    static uint8_t buf[FEATURES_LEN + GMMRRT_PROVENANCE_OVERHEAD + GMMRRT_MAX_PROVENANCE_BYTES + 8];
    static char big[GMMRRT_MAX_PROVENANCE_BYTES + 2];
    memset(big, 'a', sizeof big - 1);
    size_t len = 99;
    char err[256];
    assert_int_equal(gmmrrt_model_encode_provenance(&m, big, GMMRRT_MAX_PROVENANCE_BYTES + 1, buf, sizeof buf, &len,
                                                    err, sizeof err),
                     GMMRRT_ERR_MODEL_TOO_LARGE);
    assert_int_equal(len, 0);
    assert_int_equal(gmmrrt_model_encode_provenance(&m, "a\0b", 3, buf, sizeof buf, &len, err, sizeof err),
                     GMMRRT_ERR_MODEL_BAD_FIELD);
    assert_int_equal(gmmrrt_model_encode_provenance(&m, "\xc0\xaf", 2, buf, sizeof buf, &len, err, sizeof err),
                     GMMRRT_ERR_MODEL_BAD_FIELD); /* overlong '/' */
    assert_int_equal(gmmrrt_model_encode_provenance(&m, "\xed\xa0\x80", 3, buf, sizeof buf, &len, err, sizeof err),
                     GMMRRT_ERR_MODEL_BAD_FIELD); /* a surrogate */
    assert_int_equal(gmmrrt_model_encode_provenance(&m, kText, strlen(kText), buf, FEATURES_LEN + 10, &len, err,
                                                    sizeof err),
                     GMMRRT_ERR_BUFFER_TOO_SMALL);
    /* The longest text fits and reads back. */
    assert_int_equal(gmmrrt_model_encode_provenance(&m, big, GMMRRT_MAX_PROVENANCE_BYTES, buf, sizeof buf, &len,
                                                    err, sizeof err),
                     GMMRRT_OK);
    expect_status(buf, len, GMMRRT_OK, NULL);
}

static void test_largest_model_with_largest_trailer_decodes(void **state)
{
    (void)state;
    const size_t max = gmmrrt_model_max_file_size();
    gmmrrt_model_t *m = calloc(1, sizeof *m);
    uint8_t *buf = malloc(max + 1);
    char *text = malloc(GMMRRT_MAX_PROVENANCE_BYTES);
    assert_non_null(m);
    assert_non_null(buf);
    assert_non_null(text);
    memset(text, 'z', GMMRRT_MAX_PROVENANCE_BYTES);
    m->kind = GMMRRT_MODEL_KIND_GENERIC;
    m->dim = GMMRRT_MAX_DIM;
    m->k = GMMRRT_MAX_K;
    m->delta = 1e-3;
    for (int i = 0; i < m->k; ++i) {
        m->weight[i] = 1.0 / m->k;
        for (int j = 0; j < m->dim; ++j)
            m->chol[i][GMMRRT_TRI(j) + j] = 1.0;
    }
    size_t n = 0;
    char err[256];
    /* The largest file also carries the largest background section (model.h): the same model. */
    assert_int_equal(gmmrrt_model_encode_file(m, m, text, GMMRRT_MAX_PROVENANCE_BYTES, buf, max + 1, &n, err,
                                              sizeof err),
                     GMMRRT_OK);
    assert_int_equal(n, max);
    expect_status(buf, n, GMMRRT_OK, NULL);
    buf[n] = 0;
    expect_status(buf, n + 1, GMMRRT_ERR_MODEL_TOO_LARGE, NULL);
    free(text);
    free(buf);
    free(m);
}

static void test_files_round_trip_and_a_corrupt_trailer_keeps_the_model(void **state)
{
    (void)state;
    char dir[256], path[300];
    snprintf(dir, sizeof dir, "%s/gmmrrt-provenance-XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/m.gmm", dir);
    gmmrrt_model_t m, got;
    fixture_features_model(&m);
    char err[512];
    assert_int_equal(gmmrrt_model_save_file_provenance(path, &m, kText, strlen(kText), err, sizeof err), GMMRRT_OK);
    char text[GMMRRT_MAX_PROVENANCE_BYTES + 1];
    size_t n = 0;
    assert_int_equal(gmmrrt_model_load_file_provenance(path, &got, text, sizeof text, &n, err, sizeof err),
                     GMMRRT_OK);
    assert_string_equal(text, kText);
    assert_int_equal(n, strlen(kText));
    /* The plain loader reads the same model. */
    gmmrrt_model_t plain;
    assert_int_equal(gmmrrt_model_load_file(path, &plain, err, sizeof err), GMMRRT_OK);
    assert_memory_equal(&plain, &got, sizeof got);

    /* Flip one text byte on disk: refused, the path and the trailer named, the model kept. */
    FILE *f = fopen(path, "r+b");
    assert_non_null(f);
    assert_int_equal(fseek(f, FEATURES_LEN + 20, SEEK_SET), 0);
    const int c = fgetc(f);
    assert_int_equal(fseek(f, FEATURES_LEN + 20, SEEK_SET), 0);
    fputc(c ^ 0x01, f);
    fclose(f);
    const gmmrrt_model_t before = got;
    assert_int_equal(gmmrrt_model_load_file_provenance(path, &got, text, sizeof text, &n, err, sizeof err),
                     GMMRRT_ERR_MODEL_BAD_CHECKSUM);
    assert_non_null(strstr(err, path));
    assert_non_null(strstr(err, "provenance"));
    assert_memory_equal(&got, &before, sizeof got);
    assert_int_equal(gmmrrt_model_load_file(path, &got, err, sizeof err), GMMRRT_ERR_MODEL_BAD_CHECKSUM);

    /* Invalid text is refused by the writer and leaves the previous file alone. */
    assert_int_equal(gmmrrt_model_save_file_provenance(path, &m, "a\0b", 3, err, sizeof err),
                     GMMRRT_ERR_MODEL_BAD_FIELD);
    assert_int_equal(gmmrrt_model_load_file(path, &got, err, sizeof err), GMMRRT_ERR_MODEL_BAD_CHECKSUM);
    assert_int_equal(unlink(path), 0);
    assert_int_equal(rmdir(dir), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip_keeps_model_bytes_and_text),
        cmocka_unit_test(test_file_without_trailer_has_no_provenance),
        cmocka_unit_test(test_every_truncation_of_the_trailer_is_truncated),
        cmocka_unit_test(test_every_bit_flip_of_the_trailer_is_refused),
        cmocka_unit_test(test_each_trailer_rule_with_a_correct_crc),
        cmocka_unit_test(test_writer_refuses_text_it_could_not_read_back),
        cmocka_unit_test(test_largest_model_with_largest_trailer_decodes),
        cmocka_unit_test(test_files_round_trip_and_a_corrupt_trailer_keeps_the_model),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
