/* planner.model_background: the background section of a model file (model.h, model_file.h,
 * docs/model-format.md). Round trip in memory (with and without a provenance trailer after it)
 * and through a file; a file without a section has none and still reads as before; every
 * truncation and every single bit flip of the section is refused with a message naming the
 * background; hand-made sections with a correct CRC for the version, reserved and length
 * rules; a background that does not match the task model is refused on writing and reading. */
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
#define BG_K 2
#define BG_LEN (32 + BG_K * (1 + 2 + 3) * 8 + 4)

static const char kText[] = "{\"learner\":\"test\"}";

/* A background for the fixture: same kind, task, D and angles, other numbers. */
static void background_model(gmmrrt_model_t *m)
{
    fixture_features_model(m);
    m->homotopy = GMMRRT_HOMOTOPY_ALL;
    m->k = BG_K;
    m->weight[0] = 0.7;
    m->weight[1] = 0.3;
    m->mean[0][0] = 2.2;
    m->mean[0][1] = 0.1;
    m->mean[1][0] = 3.1;
    m->mean[1][1] = -2.0;
}

static size_t encode(uint8_t *buf, size_t cap, const char *text)
{
    gmmrrt_model_t m, bg;
    fixture_features_model(&m);
    background_model(&bg);
    size_t len = 0;
    char err[256];
    if (gmmrrt_model_encode_file(&m, &bg, text, text ? strlen(text) : 0, buf, cap, &len, err, sizeof err) !=
        GMMRRT_OK)
        fail_msg("encode_file: %s", err);
    assert_int_equal(len, FEATURES_LEN + GMMRRT_BACKGROUND_OVERHEAD + BG_LEN +
                              (text ? GMMRRT_PROVENANCE_OVERHEAD + strlen(text) : 0));
    return len;
}

static void put_u32(uint8_t *p, uint32_t v)
{
    for (int b = 0; b < 4; ++b)
        p[b] = (uint8_t)((v >> (8 * b)) & 0xFFu);
}

/* Decodes (task model) and reads the background of an exact heap copy; both must give want. */
static void expect_status(const uint8_t *buf, size_t len, gmmrrt_status_t want, const char *want_in_msg)
{
    static gmmrrt_model_t scratch, bg;
    uint8_t *copy = malloc(len ? len : 1);
    assert_non_null(copy);
    memcpy(copy, buf, len);
    char err[320] = "", err2[320] = "";
    const gmmrrt_status_t st = gmmrrt_model_decode(copy, len, &scratch, err, sizeof err);
    int has = -1;
    const gmmrrt_status_t st2 = gmmrrt_model_background(copy, len, &bg, &has, err2, sizeof err2);
    free(copy);
    if (st != want || st2 != want)
        fail_msg("decode gave %d (%s), background %d (%s), expected %d (%s)", st, err, st2, err2, want,
                 gmmrrt_status_str(want));
    if (want != GMMRRT_OK && (strstr(err, want_in_msg) == NULL || strstr(err2, want_in_msg) == NULL))
        fail_msg("messages \"%s\" / \"%s\" do not mention \"%s\"", err, err2, want_in_msg);
}

static void assert_same_stored(const gmmrrt_model_t *a, const gmmrrt_model_t *b)
{
    assert_int_equal(a->kind, b->kind);
    assert_int_equal(a->task, b->task);
    assert_int_equal(a->homotopy, b->homotopy);
    assert_int_equal(a->dim, b->dim);
    assert_int_equal(a->k, b->k);
    for (int i = 0; i < a->k; ++i) {
        assert_memory_equal(&a->weight[i], &b->weight[i], sizeof(double));
        assert_memory_equal(a->mean[i], b->mean[i], sizeof(double) * (size_t)a->dim);
        assert_memory_equal(a->chol[i], b->chol[i], sizeof(double) * GMMRRT_TRI(a->dim));
    }
}

static void test_background_round_trips_with_and_without_provenance(void **state)
{
    (void)state;
    static uint8_t buf[8192];
    gmmrrt_model_t want_m, want_bg;
    fixture_features_model(&want_m);
    background_model(&want_bg);
    for (int with_text = 0; with_text < 2; ++with_text) {
        const size_t len = encode(buf, sizeof buf, with_text ? kText : NULL);
        static gmmrrt_model_t m, bg;
        char err[256];
        assert_int_equal(gmmrrt_model_decode(buf, len, &m, err, sizeof err), GMMRRT_OK);
        assert_same_stored(&m, &want_m);
        int has = 0;
        assert_int_equal(gmmrrt_model_background(buf, len, &bg, &has, err, sizeof err), GMMRRT_OK);
        assert_int_equal(has, 1);
        assert_same_stored(&bg, &want_bg);
        /* The task model's bytes are those of a file without the section. */
        uint8_t plain[FEATURES_LEN];
        size_t plain_len = 0;
        assert_int_equal(gmmrrt_model_encode(&want_m, plain, sizeof plain, &plain_len, err, sizeof err), GMMRRT_OK);
        assert_memory_equal(buf, plain, FEATURES_LEN);
        char text[64];
        size_t n = 99;
        int has_text = -1;
        assert_int_equal(gmmrrt_model_provenance(buf, len, text, sizeof text, &n, &has_text, err, sizeof err),
                         GMMRRT_OK);
        assert_int_equal(has_text, with_text);
        if (with_text)
            assert_string_equal(text, kText);
        else
            assert_int_equal(n, 0);
    }
}

static void test_file_without_background_has_none(void **state)
{
    (void)state;
    gmmrrt_model_t m;
    fixture_features_model(&m);
    uint8_t buf[FEATURES_LEN];
    size_t len = 0;
    char err[256];
    assert_int_equal(gmmrrt_model_encode(&m, buf, sizeof buf, &len, err, sizeof err), GMMRRT_OK);
    static gmmrrt_model_t bg;
    bg.k = 77; /* untouched without a section */
    int has = -1;
    assert_int_equal(gmmrrt_model_background(buf, len, &bg, &has, err, sizeof err), GMMRRT_OK);
    assert_int_equal(has, 0);
    assert_int_equal(bg.k, 77);
}

static void test_every_truncation_and_bit_flip_of_the_section_is_refused(void **state)
{
    (void)state;
    static uint8_t buf[8192];
    const size_t len = encode(buf, sizeof buf, NULL);
    for (size_t cut = FEATURES_LEN + 1; cut < len; ++cut) {
        static gmmrrt_model_t scratch;
        char err[320] = "";
        const gmmrrt_status_t st = gmmrrt_model_decode(buf, cut, &scratch, err, sizeof err);
        if (st == GMMRRT_OK)
            fail_msg("a file cut to %zu of %zu bytes was accepted", cut, len);
        /* Fewer than 7 bytes ("GMMRRT" + 'B') cannot tell a section from a trailer: either way
         * the file is truncated. */
        if (cut < FEATURES_LEN + 7) {
            assert_int_equal(st, GMMRRT_ERR_MODEL_TRUNCATED);
            continue;
        }
        if (strstr(err, "background") == NULL)
            fail_msg("cut %zu: message \"%s\" does not name the background", cut, err);
    }
    for (size_t byte = FEATURES_LEN; byte < len; ++byte)
        for (int bit = 0; bit < 8; ++bit) {
            buf[byte] ^= (uint8_t)(1u << bit);
            static gmmrrt_model_t scratch;
            char err[320] = "";
            const gmmrrt_status_t st = gmmrrt_model_decode(buf, len, &scratch, err, sizeof err);
            buf[byte] ^= (uint8_t)(1u << bit);
            if (st == GMMRRT_OK)
                fail_msg("bit %d of byte %zu flipped was accepted", bit, byte);
            /* A flip in the magic makes the bytes no section at all (BAD_SIZE, "not a provenance
             * trailer"); every other flip is the background's. */
            if (byte >= FEATURES_LEN + 8 && strstr(err, "background") == NULL)
                fail_msg("byte %zu bit %d: message \"%s\" does not name the background", byte, bit, err);
        }
}

/* Rewrites the section's CRC after a hand edit, so the rule under test is the one that fails. */
static void reseal(uint8_t *section, size_t body_len)
{
    put_u32(section + 16 + body_len, gmmrrt_crc32(section, 16 + body_len));
}

static void test_section_rules_with_a_correct_crc(void **state)
{
    (void)state;
    static uint8_t buf[8192];
    const size_t len = encode(buf, sizeof buf, NULL);
    uint8_t *sec = buf + FEATURES_LEN;
    sec[8] = 2; /* version */
    reseal(sec, BG_LEN);
    expect_status(buf, len, GMMRRT_ERR_MODEL_BAD_VERSION, "background section");
    sec[8] = 1;
    sec[10] = 1; /* reserved */
    reseal(sec, BG_LEN);
    expect_status(buf, len, GMMRRT_ERR_MODEL_BAD_FIELD, "reserved");
    sec[10] = 0;
    reseal(sec, BG_LEN);
    expect_status(buf, len, GMMRRT_OK, NULL);
    /* A length that is not the embedded model's own. */
    static uint8_t big[8192];
    memcpy(big, buf, len);
    uint8_t *s2 = big + FEATURES_LEN;
    put_u32(s2 + 12, BG_LEN + 8);
    memset(s2 + 16 + BG_LEN, 0, 8);
    reseal(s2, BG_LEN + 8);
    expect_status(big, len + 8, GMMRRT_ERR_MODEL_BAD_SIZE, "embedded model");
    /* A length beyond any model. */
    put_u32(sec + 12, 0x7FFFFFFFu);
    expect_status(buf, len, GMMRRT_ERR_MODEL_BAD_SIZE, "model length");
}

static void test_a_background_of_other_features_is_refused(void **state)
{
    (void)state;
    gmmrrt_model_t m, other;
    fixture_features_model(&m);
    fixture_generic_d4_model(&other);
    static uint8_t buf[8192];
    size_t len = 7;
    char err[320];
    assert_int_equal(gmmrrt_model_encode_file(&m, &other, NULL, 0, buf, sizeof buf, &len, err, sizeof err),
                     GMMRRT_ERR_MODEL_MISMATCH);
    assert_int_equal(len, 0);
    assert_non_null(strstr(err, "does not match"));
    /* Hand-made: the section holds a valid approach model behind an avoid model. */
    gmmrrt_model_t bg;
    background_model(&bg);
    bg.task = GMMRRT_TASK_APPROACH;
    size_t n = 0;
    assert_int_equal(gmmrrt_model_encode(&m, buf, sizeof buf, &n, err, sizeof err), GMMRRT_OK);
    uint8_t *sec = buf + n;
    memcpy(sec, GMMRRT_BACKGROUND_MAGIC, 8);
    sec[8] = 1;
    sec[9] = sec[10] = sec[11] = 0;
    put_u32(sec + 12, BG_LEN);
    size_t bl = 0;
    assert_int_equal(gmmrrt_model_encode(&bg, sec + 16, BG_LEN, &bl, err, sizeof err), GMMRRT_OK);
    reseal(sec, BG_LEN);
    const size_t total = n + GMMRRT_BACKGROUND_OVERHEAD + BG_LEN;
    static gmmrrt_model_t out;
    int has = -1;
    assert_int_equal(gmmrrt_model_background(buf, total, &out, &has, err, sizeof err), GMMRRT_ERR_MODEL_MISMATCH);
    assert_int_equal(has, 0);
    /* The task model alone still decodes: decode checks the section's framing only. */
    assert_int_equal(gmmrrt_model_decode(buf, total, &out, err, sizeof err), GMMRRT_OK);
}

static void test_files_round_trip_and_a_failed_load_leaves_the_caller_alone(void **state)
{
    (void)state;
    char dir[256]; /* scratch, removed below */
    snprintf(dir, sizeof dir, "%s/gmmrrt-bg-XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    assert_non_null(mkdtemp(dir));
    char path[300];
    snprintf(path, sizeof path, "%s/m.gmm", dir);
    gmmrrt_model_t m, bg;
    fixture_features_model(&m);
    background_model(&bg);
    char err[512];
    assert_int_equal(gmmrrt_model_save_file_background(path, &m, &bg, kText, strlen(kText), err, sizeof err),
                     GMMRRT_OK);
    static gmmrrt_model_t got, got_bg;
    int has = 0;
    char text[64];
    size_t n = 0;
    assert_int_equal(gmmrrt_model_load_file_background(path, &got, &got_bg, &has, text, sizeof text, &n, err,
                                                       sizeof err),
                     GMMRRT_OK);
    assert_int_equal(has, 1);
    assert_same_stored(&got, &m);
    assert_same_stored(&got_bg, &bg);
    assert_string_equal(text, kText);
    /* Plain loading ignores the section. */
    assert_int_equal(gmmrrt_model_load_file(path, &got, err, sizeof err), GMMRRT_OK);
    /* Corrupt the background's last number: the whole load fails, the caller's models stay. */
    FILE *f = fopen(path, "r+b");
    assert_non_null(f);
    assert_int_equal(fseek(f, (long)(FEATURES_LEN + 16 + BG_LEN - 5), SEEK_SET), 0);
    assert_int_equal(fputc(0x55, f), 0x55);
    assert_int_equal(fclose(f), 0);
    got.k = 11;
    got_bg.k = 12;
    has = 5;
    assert_int_equal(gmmrrt_model_load_file_background(path, &got, &got_bg, &has, NULL, 0, NULL, err, sizeof err),
                     GMMRRT_ERR_MODEL_BAD_CHECKSUM);
    assert_non_null(strstr(err, "background"));
    assert_int_equal(got.k, 11);
    assert_int_equal(got_bg.k, 12);
    assert_int_equal(has, 5);
    assert_int_equal(unlink(path), 0);
    assert_int_equal(rmdir(dir), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_background_round_trips_with_and_without_provenance),
        cmocka_unit_test(test_file_without_background_has_none),
        cmocka_unit_test(test_every_truncation_and_bit_flip_of_the_section_is_refused),
        cmocka_unit_test(test_section_rules_with_a_correct_crc),
        cmocka_unit_test(test_a_background_of_other_features_is_refused),
        cmocka_unit_test(test_files_round_trip_and_a_failed_load_leaves_the_caller_alone),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
