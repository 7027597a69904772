/*
 * fuzz_model.c - libFuzzer target for the model file decoder gmmrrt_model_decode
 * (planner/src/model.c; format in docs/model-format.md, the mixture of paper eq. 1).
 *
 * Each input is decoded twice: as given (exercises magic, version, sizes, CRC), and with
 * its last four bytes replaced by the CRC-32 of the rest, so mutations reach the field
 * validation behind the checksum. Properties checked (abort = finding):
 *   - decode never reads outside the input (ASan) and never hits undefined behaviour (UBSan);
 *   - a rejected input always comes with a non-empty message;
 *   - an accepted model encodes again, and the encoding decodes to the same stored fields;
 *   - an accepted file's provenance text (if any) reads back (the same framing rules) and
 *     re-encodes with the model to a file that gives the same text;
 *   - an accepted file's background section (if any) either decodes or is refused with a
 *     message, and a decoded background re-encodes with the model to a file whose background
 *     has the same stored fields.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gmmrrt/model.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static gmmrrt_model_t g_model, g_again, g_bg, g_bg_again;
static uint8_t g_fixed[1 << 16];
static uint8_t g_encoded[1 << 16];
static char g_text[GMMRRT_MAX_PROVENANCE_BYTES + 1], g_text_again[GMMRRT_MAX_PROVENANCE_BYTES + 1];

static void check_one(const uint8_t *buf, size_t len)
{
    char err[256] = {0};
    const gmmrrt_status_t st = gmmrrt_model_decode(buf, len, &g_model, err, sizeof err);
    if (st != GMMRRT_OK) {
        if (err[0] == '\0') {
            fprintf(stderr, "fuzz_model: status %d without a message\n", (int)st);
            abort();
        }
        return;
    }
    size_t n = 0, text_len = 0, again_len = 0;
    int has = 0;
    if (gmmrrt_model_provenance(buf, len, g_text, sizeof g_text, &text_len, &has, err, sizeof err) != GMMRRT_OK) {
        fprintf(stderr, "fuzz_model: a decoded file's provenance does not read: %s\n", err);
        abort();
    }
    if (has) {
        if (gmmrrt_model_encode_provenance(&g_model, g_text, text_len, g_encoded, sizeof g_encoded, &n, err,
                                           sizeof err) != GMMRRT_OK ||
            gmmrrt_model_provenance(g_encoded, n, g_text_again, sizeof g_text_again, &again_len, NULL, err,
                                    sizeof err) != GMMRRT_OK ||
            again_len != text_len || memcmp(g_text, g_text_again, text_len) != 0) {
            fprintf(stderr, "fuzz_model: the provenance text does not survive a round trip: %s\n", err);
            abort();
        }
    }
    int has_bg = 0;
    const gmmrrt_status_t bst = gmmrrt_model_background(buf, len, &g_bg, &has_bg, err, sizeof err);
    if (bst != GMMRRT_OK && err[0] == '\0') {
        fprintf(stderr, "fuzz_model: background status %d without a message\n", (int)bst);
        abort();
    }
    if (bst == GMMRRT_OK && has_bg) {
        int again_has = 0;
        if (gmmrrt_model_encode_file(&g_model, &g_bg, NULL, 0, g_encoded, sizeof g_encoded, &n, err, sizeof err) !=
                GMMRRT_OK ||
            gmmrrt_model_background(g_encoded, n, &g_bg_again, &again_has, err, sizeof err) != GMMRRT_OK ||
            !again_has || g_bg_again.k != g_bg.k ||
            memcmp(g_bg_again.weight, g_bg.weight, sizeof g_bg.weight) != 0 ||
            memcmp(g_bg_again.mean, g_bg.mean, sizeof g_bg.mean) != 0 ||
            memcmp(g_bg_again.chol, g_bg.chol, sizeof g_bg.chol) != 0) {
            fprintf(stderr, "fuzz_model: the background does not survive a round trip: %s\n", err);
            abort();
        }
    }
    if (gmmrrt_model_encode(&g_model, g_encoded, sizeof g_encoded, &n, err, sizeof err) != GMMRRT_OK) {
        fprintf(stderr, "fuzz_model: an accepted model does not encode: %s\n", err);
        abort();
    }
    if (gmmrrt_model_decode(g_encoded, n, &g_again, err, sizeof err) != GMMRRT_OK) {
        fprintf(stderr, "fuzz_model: the re-encoded model does not decode: %s\n", err);
        abort();
    }
    if (g_again.kind != g_model.kind || g_again.task != g_model.task || g_again.dim != g_model.dim ||
        g_again.k != g_model.k || g_again.angle_mask != g_model.angle_mask ||
        memcmp(g_again.weight, g_model.weight, sizeof g_model.weight) != 0 ||
        memcmp(g_again.mean, g_model.mean, sizeof g_model.mean) != 0 ||
        memcmp(g_again.chol, g_model.chol, sizeof g_model.chol) != 0) {
        fprintf(stderr, "fuzz_model: encode/decode round trip changed the model\n");
        abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    check_one(data, size);
    if (size >= 4 && size <= sizeof g_fixed) {
        memcpy(g_fixed, data, size);
        const uint32_t crc = gmmrrt_crc32(g_fixed, size - 4);
        for (int i = 0; i < 4; ++i) /* little-endian, docs/model-format.md */
            g_fixed[size - 4 + (size_t)i] = (uint8_t)(crc >> (8 * i));
        check_one(g_fixed, size);
    }
    return 0;
}
