/*
 * map_file.h - static maps in the map_server format that 2-D SLAM tools write (a YAML file
 * naming an image, PGM or PNG), read into an occupancy raster (raster.h). docs/world.md.
 *
 * YAML keys (libyaml): image (path, relative to the YAML file's folder unless absolute),
 * resolution (m per cell, > 0), origin ([x, y, yaw]: world pose of the image's lower-left
 * corner), negate (0/1 or true/false), occupied_thresh and free_thresh (0 <= free < occupied
 * <= 1) are required; mode (trinary, the default, or scale) is optional; other keys are ignored.
 * A pixel of value v (maxval m) has occupancy p = (m - v) / m (v / m with negate): p >
 * occupied_thresh is occupied, p < free_thresh free, and in between unknown (trinary) or a
 * value 1..99 that does not block (scale). Colour PNGs are read as grey by libpng.
 */
#ifndef GMMRRT_MAP_FILE_H
#define GMMRRT_MAP_FILE_H

#include <stddef.h>
#include <stdint.h>

#include "gmmrrt/raster.h"
#include "gmmrrt/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define GMMRRT_MAP_MAX_PATH 4096

typedef struct {
    char image[GMMRRT_MAP_MAX_PATH]; /* as written in the YAML */
    double resolution_m;
    double origin_x, origin_y, origin_yaw;
    int32_t negate;
    double occupied_thresh, free_thresh;
    int32_t scale_mode;              /* 0 trinary, 1 scale */
} gmmrrt_map_info_t;

/* Parses the YAML text[len] (name: the file name used in messages). GMMRRT_OK, or
 * GMMRRT_ERR_INVALID_ARGUMENT with err naming the file, the line and the key (a missing key,
 * a value of the wrong type or out of range, a YAML syntax error). *info is written only on
 * success. */
gmmrrt_status_t gmmrrt_map_parse_yaml(const char *text, size_t len, const char *name, gmmrrt_map_info_t *info,
                                      char *err, size_t errcap);

/* Decodes a PGM (P5 8 or 16 bit, P2) or PNG image data[len] (name: for messages) with info's
 * thresholds into raster (geometry from info and the image's size, unknown cells blocking when
 * unknown_blocked is 1) and computes its distance field. GMMRRT_ERR_INVALID_ARGUMENT: not a PGM
 * or PNG, a bad header, pixel data shorter or longer than the header says;
 * GMMRRT_ERR_BUFFER_TOO_SMALL: more cells or a longer side than the raster's capacity (err gives
 * both). On any error the raster is left as it was (the image is decoded into scratch memory
 * first). Allocates the scratch (this is io/, not the planning core). */
gmmrrt_status_t gmmrrt_map_decode_image(const uint8_t *data, size_t len, const char *name,
                                        const gmmrrt_map_info_t *info, int32_t unknown_blocked,
                                        gmmrrt_raster_t *raster, char *err, size_t errcap);

/* Reads the YAML file at yaml_path and its image, as the two functions above. Files must be
 * regular files (opened without blocking, checked with fstat). GMMRRT_ERR_IO when a file cannot
 * be opened or read, or is not a regular file; otherwise as above. err starts with the file's
 * path. The raster is changed only on success. */
gmmrrt_status_t gmmrrt_map_load_file(const char *yaml_path, int32_t unknown_blocked, gmmrrt_raster_t *raster,
                                     char *err, size_t errcap);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_MAP_FILE_H */
