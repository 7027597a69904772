/*
 * fuzz_map.c - libFuzzer target for the map reader (planner/io map_file.h): the YAML parser
 * gmmrrt_map_parse_yaml and the image decoder gmmrrt_map_decode_image (PGM by hand, PNG by
 * libpng), into a raster of fixed capacity (256 x 256 cells).
 *
 * Input: the YAML text, a NUL byte, then the image bytes (no NUL: the whole input is YAML and
 * the image is decoded with a fixed valid description). Properties checked (abort = finding):
 *   - neither reads outside its input (ASan) nor hits undefined behaviour (UBSan);
 *   - a refusal always comes with a message, and leaves the raster as it was (generation);
 *   - an accepted YAML has a resolution > 0, finite origin and 0 <= free < occupied <= 1;
 *   - an accepted image fits the capacity, every cell is FREE, OCCUPIED, UNKNOWN or 1..99,
 *     and the distance field is ready and zero exactly at the corners of blocked cells (and on
 *     the border while the outside blocks).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gmmrrt/map_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define CAP_SIDE 256
/* Cells and marks (5 bytes a cell), the field (a float a corner), the transform's scratch. */
static uint64_t g_mem[(CAP_SIDE * CAP_SIDE * 5 + (CAP_SIDE + 1) * (CAP_SIDE + 1) * 4 + 8 * 4 * (CAP_SIDE + 3)) / 8 + 64];
static gmmrrt_raster_t g_raster;
static int g_ready;
static char g_text[1 << 16];

static void check(int ok, const char *what)
{
    if (!ok) {
        fprintf(stderr, "fuzz_map: %s\n", what);
        abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!g_ready) {
        check(gmmrrt_raster_mem_size(CAP_SIDE * CAP_SIDE, CAP_SIDE) <= sizeof g_mem, "raster block too small");
        check(gmmrrt_raster_init(&g_raster, g_mem, sizeof g_mem, CAP_SIDE * CAP_SIDE, CAP_SIDE) == GMMRRT_OK,
              "raster init");
        g_ready = 1;
    }
    const uint8_t *nul = memchr(data, 0, size);
    const size_t ylen = nul ? (size_t)(nul - data) : size;
    if (ylen >= sizeof g_text)
        return 0;
    memcpy(g_text, data, ylen);
    g_text[ylen] = '\0';
    char err[512] = {0};
    gmmrrt_map_info_t info;
    gmmrrt_status_t st = gmmrrt_map_parse_yaml(g_text, ylen, "fuzz.yaml", &info, err, sizeof err);
    if (st != GMMRRT_OK) {
        check(err[0] != '\0', "YAML refused without a message");
        if (!nul)
            return 0;
        /* Decode the image anyway, with a valid description. */
        memset(&info, 0, sizeof info);
        info.resolution_m = 0.05;
        info.occupied_thresh = 0.65;
        info.free_thresh = 0.196;
        info.scale_mode = (int32_t)(ylen & 1);
    } else {
        check(info.resolution_m > 0.0 && isfinite(info.origin_x) && isfinite(info.origin_y) &&
                  isfinite(info.origin_yaw) && info.free_thresh >= 0.0 && info.free_thresh < info.occupied_thresh &&
                  info.occupied_thresh <= 1.0 && info.image[0] != '\0',
              "accepted YAML out of range");
    }
    if (!nul)
        return 0;
    const uint32_t gen = g_raster.generation;
    err[0] = '\0';
    st = gmmrrt_map_decode_image(nul + 1, size - ylen - 1, "fuzz.img", &info, (int32_t)(size & 1), &g_raster, err,
                                 sizeof err);
    if (st != GMMRRT_OK) {
        check(err[0] != '\0', "image refused without a message");
        check(g_raster.generation == gen, "a refused image changed the raster");
        return 0;
    }
    const gmmrrt_raster_t *r = &g_raster;
    check(r->width >= 1 && r->height >= 1 && r->width <= CAP_SIDE && r->height <= CAP_SIDE, "size beyond capacity");
    check(gmmrrt_raster_distance_ready(r), "field not ready");
    for (int32_t c = 0; c < r->width * r->height; ++c) {
        const uint8_t v = r->cells[c];
        check(v == GMMRRT_RASTER_FREE || v == GMMRRT_RASTER_OCCUPIED || v == GMMRRT_RASTER_UNKNOWN || (v >= 1 && v <= 99),
              "cell value out of range");
    }
    for (int32_t j = 0; j <= r->height; ++j)
        for (int32_t i = 0; i <= r->width; ++i) {
            int blocked = r->unknown_blocked && (i == 0 || j == 0 || i == r->width || j == r->height);
            for (int32_t b = j - 1; b <= j; ++b)
                for (int32_t a = i - 1; a <= i; ++a)
                    if (a >= 0 && b >= 0 && a < r->width && b < r->height) {
                        const uint8_t v = r->cells[b * r->width + a];
                        blocked |= v == GMMRRT_RASTER_OCCUPIED || (v == GMMRRT_RASTER_UNKNOWN && r->unknown_blocked);
                    }
            check(blocked == (r->dist[j * (r->width + 1) + i] == 0.0f),
                  "field is not zero exactly at the blocked cells' corners");
        }
    return 0;
}
