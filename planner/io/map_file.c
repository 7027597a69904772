/*
 * map_file.c - map_server maps (map_file.h): the YAML through libyaml's document loader, PGM
 * by hand (its header is a few tokens), PNG through libpng's simplified API, both decoded into
 * scratch memory and converted with map_server's thresholds before the raster is touched; then
 * the raster's distance field (raster.c). docs/world.md.
 */
#include "gmmrrt/map_file.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>
#include <yaml.h>

#include "error_text.h" /* planner/src, private include */

/* Largest YAML file read: a map description is a few lines. */
#define MAP_YAML_MAX_BYTES (1u << 20)

/* ---------------------------------------------------------------- YAML */

enum { K_IMAGE, K_RESOLUTION, K_ORIGIN, K_NEGATE, K_OCC, K_FREE, K_MODE, K_COUNT };
static const char *const key_names[K_COUNT] = {"image", "resolution", "origin", "negate",
                                               "occupied_thresh", "free_thresh", "mode"};

static int scalar_number(const yaml_node_t *n, double *out)
{
    if (n->type != YAML_SCALAR_NODE || n->data.scalar.length == 0 || n->data.scalar.length > 64)
        return 0;
    char buf[80];
    memcpy(buf, n->data.scalar.value, n->data.scalar.length);
    buf[n->data.scalar.length] = '\0';
    char *end = NULL;
    errno = 0;
    const double v = strtod(buf, &end);
    if (end == buf || *end != '\0' || errno == ERANGE || !isfinite(v))
        return 0;
    *out = v;
    return 1;
}

static int scalar_is(const yaml_node_t *n, const char *s)
{
    return n->type == YAML_SCALAR_NODE && n->data.scalar.length == strlen(s) &&
           strncasecmp((const char *)n->data.scalar.value, s, n->data.scalar.length) == 0;
}

gmmrrt_status_t gmmrrt_map_parse_yaml(const char *text, size_t len, const char *name, gmmrrt_map_info_t *info,
                                      char *err, size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (!text || !info)
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "map YAML or info is NULL");
    if (!name)
        name = "map YAML";
    yaml_parser_t parser;
    yaml_document_t doc;
    if (!yaml_parser_initialize(&parser))
        return gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap, "%s: out of memory for the YAML parser", name);
    yaml_parser_set_input_string(&parser, (const unsigned char *)text, len);
    if (!yaml_parser_load(&parser, &doc)) {
        gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "%s:%lu: YAML error: %s", name,
                         (unsigned long)parser.problem_mark.line + 1, parser.problem ? parser.problem : "unknown");
        yaml_parser_delete(&parser);
        return GMMRRT_ERR_INVALID_ARGUMENT;
    }
    gmmrrt_status_t st = GMMRRT_OK;
    gmmrrt_map_info_t m;
    memset(&m, 0, sizeof m);
    const yaml_node_t *root = yaml_document_get_root_node(&doc);
    const yaml_node_t *val[K_COUNT] = {NULL};
    if (!root || root->type != YAML_MAPPING_NODE) {
        st = gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap,
                              "%s: not a map description (expected a mapping with image, resolution, origin, ...)",
                              name);
        goto done;
    }
    for (yaml_node_pair_t *pair = root->data.mapping.pairs.start; pair < root->data.mapping.pairs.top; ++pair) {
        yaml_node_t *k = yaml_document_get_node(&doc, pair->key), *v = yaml_document_get_node(&doc, pair->value);
        if (!k || !v || k->type != YAML_SCALAR_NODE)
            continue;
        for (int i = 0; i < K_COUNT; ++i) {
            if (!scalar_is(k, key_names[i]) || strlen(key_names[i]) != k->data.scalar.length)
                continue;
            if (val[i]) {
                st = gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "%s:%lu: key '%s' given twice",
                                      name, (unsigned long)k->start_mark.line + 1, key_names[i]);
                goto done;
            }
            val[i] = v;
        }
    }
    for (int i = 0; i < K_COUNT; ++i)
        if (!val[i] && i != K_MODE) {
            st = gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "%s: missing key '%s'", name,
                                  key_names[i]);
            goto done;
        }
#define BAD(i, what)                                                                                              \
    do {                                                                                                          \
        st = gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "%s:%lu: key '%s': %s", name,            \
                              (unsigned long)val[i]->start_mark.line + 1, key_names[i], what);                    \
        goto done;                                                                                                \
    } while (0)
    if (val[K_IMAGE]->type != YAML_SCALAR_NODE || val[K_IMAGE]->data.scalar.length == 0 ||
        val[K_IMAGE]->data.scalar.length >= sizeof m.image ||
        memchr(val[K_IMAGE]->data.scalar.value, '\0', val[K_IMAGE]->data.scalar.length))
        BAD(K_IMAGE, "expected a file name");
    memcpy(m.image, val[K_IMAGE]->data.scalar.value, val[K_IMAGE]->data.scalar.length);
    if (!scalar_number(val[K_RESOLUTION], &m.resolution_m) || !(m.resolution_m > 0.0))
        BAD(K_RESOLUTION, "expected a number > 0 (metres per cell)");
    {
        const yaml_node_t *o = val[K_ORIGIN];
        double xyz[3];
        if (o->type != YAML_SEQUENCE_NODE || o->data.sequence.items.top - o->data.sequence.items.start != 3)
            BAD(K_ORIGIN, "expected [x, y, yaw]");
        for (int i = 0; i < 3; ++i) {
            const yaml_node_t *e = yaml_document_get_node(&doc, o->data.sequence.items.start[i]);
            if (!e || !scalar_number(e, &xyz[i]))
                BAD(K_ORIGIN, "expected [x, y, yaw] of finite numbers");
        }
        m.origin_x = xyz[0];
        m.origin_y = xyz[1];
        m.origin_yaw = xyz[2];
    }
    if (scalar_is(val[K_NEGATE], "0") || scalar_is(val[K_NEGATE], "false") || scalar_is(val[K_NEGATE], "no"))
        m.negate = 0;
    else if (scalar_is(val[K_NEGATE], "1") || scalar_is(val[K_NEGATE], "true") || scalar_is(val[K_NEGATE], "yes"))
        m.negate = 1;
    else
        BAD(K_NEGATE, "expected 0 or 1");
    if (!scalar_number(val[K_OCC], &m.occupied_thresh) || m.occupied_thresh < 0.0 || m.occupied_thresh > 1.0)
        BAD(K_OCC, "expected a number in [0, 1]");
    if (!scalar_number(val[K_FREE], &m.free_thresh) || m.free_thresh < 0.0 || m.free_thresh > 1.0)
        BAD(K_FREE, "expected a number in [0, 1]");
    if (!(m.free_thresh < m.occupied_thresh))
        BAD(K_FREE, "must be below occupied_thresh");
    if (val[K_MODE]) {
        if (scalar_is(val[K_MODE], "trinary"))
            m.scale_mode = 0;
        else if (scalar_is(val[K_MODE], "scale"))
            m.scale_mode = 1;
        else
            BAD(K_MODE, "expected trinary or scale (raw is not supported)");
    }
#undef BAD
    *info = m;
done:
    yaml_document_delete(&doc);
    yaml_parser_delete(&parser);
    return st;
}

/* ---------------------------------------------------------------- images */

/* Grey pixels, top row first, as decoded. */
typedef struct {
    int32_t width, height;
    uint32_t maxval;
    uint16_t *px; /* width x height */
} grey_image_t;

static gmmrrt_status_t check_size(int64_t w, int64_t h, const char *name, const gmmrrt_raster_t *r, char *err,
                                  size_t errcap)
{
    if (w < 1 || h < 1)
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "%s: image of %lld x %lld pixels", name,
                                (long long)w, (long long)h);
    /* w * h is formed only once both sides fit int32_t's range of a side; the message's figures are
     * doubles because a header may claim sides near 2^64 (the product would overflow). */
    if (w > r->max_side || h > r->max_side || w * h > (int64_t)r->max_cells) {
        const double cells = (double)w * (double)h;
        return gmmrrt_set_error(GMMRRT_ERR_BUFFER_TOO_SMALL, err, errcap,
                                "%s: the map is %lld x %lld = %.0f cells (%.0f bytes of raster); the configured raster "
                                "holds %d cells and %d a side",
                                name, (long long)w, (long long)h, cells, gmmrrt_raster_bytes((double)w, (double)h), (int)r->max_cells,
                                (int)r->max_side);
    }
    return GMMRRT_OK;
}

/* PGM header token: skips whitespace and comments, reads an unsigned decimal. */
static int pgm_number(const uint8_t *d, size_t len, size_t *pos, uint64_t *out)
{
    size_t p = *pos;
    for (;;) {
        while (p < len && isspace(d[p]))
            ++p;
        if (p < len && d[p] == '#') {
            while (p < len && d[p] != '\n')
                ++p;
            continue;
        }
        break;
    }
    if (p >= len || !isdigit(d[p]))
        return 0;
    uint64_t v = 0;
    while (p < len && isdigit(d[p])) {
        v = v * 10u + (uint64_t)(d[p] - '0');
        if (v > 0xFFFFFFFFu)
            return 0;
        ++p;
    }
    *pos = p;
    *out = v;
    return 1;
}

static gmmrrt_status_t decode_pgm(const uint8_t *d, size_t len, const char *name, const gmmrrt_raster_t *r,
                                  grey_image_t *img, char *err, size_t errcap)
{
    const int ascii = d[1] == '2';
    size_t pos = 2;
    uint64_t w, h, maxval;
    if (!pgm_number(d, len, &pos, &w) || !pgm_number(d, len, &pos, &h) || !pgm_number(d, len, &pos, &maxval))
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap,
                                "%s: PGM header: expected width, height and maxval", name);
    if (maxval < 1 || maxval > 65535)
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "%s: PGM maxval %llu (1..65535)", name,
                                (unsigned long long)maxval);
    gmmrrt_status_t st = check_size((int64_t)w, (int64_t)h, name, r, err, errcap);
    if (st != GMMRRT_OK)
        return st;
    const size_t n = (size_t)w * (size_t)h;
    img->px = malloc(n * sizeof(uint16_t));
    if (!img->px)
        return gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap, "%s: out of memory for %zu pixels", name, n);
    img->width = (int32_t)w;
    img->height = (int32_t)h;
    img->maxval = (uint32_t)maxval;
    if (ascii) {
        for (size_t i = 0; i < n; ++i) {
            uint64_t v;
            if (!pgm_number(d, len, &pos, &v) || v > maxval)
                return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap,
                                        "%s: pixel %zu of %zu is missing or above maxval %llu", name, i + 1, n,
                                        (unsigned long long)maxval);
            img->px[i] = (uint16_t)v;
        }
        while (pos < len && isspace(d[pos]))
            ++pos;
        if (pos != len)
            return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap,
                                    "%s: more pixels than the header's %llu x %llu", name, (unsigned long long)w,
                                    (unsigned long long)h);
        return GMMRRT_OK;
    }
    if (pos >= len || !isspace(d[pos]))
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "%s: PGM header not ended by whitespace",
                                name);
    ++pos;
    const size_t bpp = maxval > 255 ? 2 : 1;
    if (len - pos != n * bpp)
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap,
                                "%s: pixel data is %zu bytes, the header's %llu x %llu pixels need %zu", name,
                                len - pos, (unsigned long long)w, (unsigned long long)h, n * bpp);
    for (size_t i = 0; i < n; ++i) {
        const uint32_t v = bpp == 1 ? d[pos + i] : (uint32_t)d[pos + 2 * i] << 8 | d[pos + 2 * i + 1];
        if (v > maxval)
            return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "%s: pixel %zu is %u, above maxval %llu",
                                    name, i + 1, (unsigned)v, (unsigned long long)maxval);
        img->px[i] = (uint16_t)v;
    }
    return GMMRRT_OK;
}

static gmmrrt_status_t decode_png(const uint8_t *d, size_t len, const char *name, const gmmrrt_raster_t *r,
                                  grey_image_t *img, char *err, size_t errcap)
{
    png_image p;
    memset(&p, 0, sizeof p);
    p.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&p, d, len))
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "%s: PNG: %s", name, p.message);
    gmmrrt_status_t st = check_size((int64_t)p.width, (int64_t)p.height, name, r, err, errcap);
    if (st != GMMRRT_OK) {
        png_image_free(&p);
        return st;
    }
    p.format = PNG_FORMAT_GRAY;
    const size_t n = (size_t)p.width * (size_t)p.height;
    uint8_t *buf = malloc(PNG_IMAGE_SIZE(p));
    img->px = malloc(n * sizeof(uint16_t));
    if (!buf || !img->px) {
        free(buf);
        png_image_free(&p);
        return gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap, "%s: out of memory for %zu pixels", name, n);
    }
    if (!png_image_finish_read(&p, NULL, buf, 0, NULL)) {
        st = gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "%s: PNG: %s", name, p.message);
        free(buf);
        png_image_free(&p);
        return st;
    }
    for (size_t i = 0; i < n; ++i)
        img->px[i] = buf[i];
    free(buf);
    img->width = (int32_t)p.width;
    img->height = (int32_t)p.height;
    img->maxval = 255;
    return GMMRRT_OK;
}

/* map_server's rule for one pixel. */
static uint8_t cell_of(uint32_t v, uint32_t maxval, const gmmrrt_map_info_t *info)
{
    const double p = info->negate ? (double)v / maxval : (double)(maxval - v) / maxval;
    if (p > info->occupied_thresh)
        return GMMRRT_RASTER_OCCUPIED;
    if (p < info->free_thresh)
        return GMMRRT_RASTER_FREE;
    if (!info->scale_mode)
        return GMMRRT_RASTER_UNKNOWN;
    const double t = (p - info->free_thresh) / (info->occupied_thresh - info->free_thresh);
    const double c = 1.0 + floor(98.0 * t + 0.5);
    return (uint8_t)(c < 1.0 ? 1.0 : (c > 99.0 ? 99.0 : c));
}

gmmrrt_status_t gmmrrt_map_decode_image(const uint8_t *data, size_t len, const char *name,
                                        const gmmrrt_map_info_t *info, int32_t unknown_blocked,
                                        gmmrrt_raster_t *raster, char *err, size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (!data || !info || !raster || (unknown_blocked != 0 && unknown_blocked != 1))
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "map image, info or raster is NULL");
    if (!name)
        name = "map image";
    if (!(isfinite(info->resolution_m) && info->resolution_m > 0.0 && isfinite(info->origin_x) &&
          isfinite(info->origin_y) && isfinite(info->origin_yaw)))
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "%s: bad resolution or origin", name);
    grey_image_t img = {0, 0, 0, NULL};
    gmmrrt_status_t st;
    static const uint8_t png_sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (len >= 8 && memcmp(data, png_sig, 8) == 0)
        st = decode_png(data, len, name, raster, &img, err, errcap);
    else if (len >= 2 && data[0] == 'P' && (data[1] == '5' || data[1] == '2'))
        st = decode_pgm(data, len, name, raster, &img, err, errcap);
    else
        st = gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap,
                              "%s: not a PGM (P5, P2) or PNG image", name);
    if (st == GMMRRT_OK) {
        st = gmmrrt_raster_set_geometry(raster, img.width, img.height, info->resolution_m, info->origin_x,
                                        info->origin_y, info->origin_yaw, unknown_blocked);
        if (st != GMMRRT_OK) {
            gmmrrt_set_error(st, err, errcap, "%s: the raster refused %d x %d cells at %g m", name, (int)img.width,
                             (int)img.height, info->resolution_m);
        } else {
            /* The image's top row is the raster's last. */
            for (int32_t row = 0; row < img.height; ++row) {
                uint8_t *dst = raster->cells + (size_t)(img.height - 1 - row) * (size_t)img.width;
                const uint16_t *src = img.px + (size_t)row * (size_t)img.width;
                for (int32_t i = 0; i < img.width; ++i)
                    dst[i] = cell_of(src[i], img.maxval, info);
            }
            st = gmmrrt_raster_update_distance(raster, 0, 0.0);
        }
    }
    free(img.px);
    return st;
}

/* ---------------------------------------------------------------- files */

/* Reads a regular file whole (at most max_bytes) into a malloc'ed buffer (+1 byte, a NUL). */
static gmmrrt_status_t read_file(const char *path, const char *what, size_t max_bytes, uint8_t **out, size_t *len,
                                 char *err, size_t errcap)
{
    *out = NULL;
    *len = 0;
    const int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap, "%s: cannot open %s: %s", path, what, strerror(errno));
    struct stat sb;
    if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
        close(fd);
        return gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap, "%s: %s is not a regular file", path, what);
    }
    if ((uint64_t)sb.st_size > max_bytes) {
        close(fd);
        return gmmrrt_set_error(GMMRRT_ERR_BUFFER_TOO_SMALL, err, errcap, "%s: %s of %lld bytes, more than %zu", path,
                                what, (long long)sb.st_size, max_bytes);
    }
    uint8_t *buf = malloc((size_t)sb.st_size + 1);
    if (!buf) {
        close(fd);
        return gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap, "%s: out of memory reading %s", path, what);
    }
    size_t got = 0;
    while (got < (size_t)sb.st_size) {
        const ssize_t n = read(fd, buf + got, (size_t)sb.st_size - got);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            const int e = n < 0 ? errno : 0;
            close(fd);
            free(buf);
            return gmmrrt_set_error(GMMRRT_ERR_IO, err, errcap, "%s: cannot read %s: %s", path, what,
                                    e ? strerror(e) : "file shrank while read");
        }
        got += (size_t)n;
    }
    close(fd);
    buf[got] = '\0';
    *out = buf;
    *len = got;
    return GMMRRT_OK;
}

gmmrrt_status_t gmmrrt_map_load_file(const char *yaml_path, int32_t unknown_blocked, gmmrrt_raster_t *raster,
                                     char *err, size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (!yaml_path || !raster)
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "map path or raster is NULL");
    uint8_t *text;
    size_t len;
    gmmrrt_status_t st = read_file(yaml_path, "map YAML", MAP_YAML_MAX_BYTES, &text, &len, err, errcap);
    if (st != GMMRRT_OK)
        return st;
    static gmmrrt_map_info_t info; /* 4 KB of path: not on the stack */
    st = gmmrrt_map_parse_yaml((const char *)text, len, yaml_path, &info, err, errcap);
    free(text);
    if (st != GMMRRT_OK)
        return st;
    /* The image path: relative to the YAML file's folder unless absolute. */
    char path[2 * GMMRRT_MAP_MAX_PATH];
    const char *slash = strrchr(yaml_path, '/');
    if (info.image[0] == '/' || !slash)
        snprintf(path, sizeof path, "%s", info.image);
    else
        snprintf(path, sizeof path, "%.*s/%s", (int)(slash - yaml_path), yaml_path, info.image);
    uint8_t *data;
    /* A PGM of 16-bit pixels with a long header is the largest honest file. */
    const size_t max_bytes = 2u * (size_t)raster->max_cells + (1u << 16);
    st = read_file(path, "map image", max_bytes, &data, &len, err, errcap);
    if (st != GMMRRT_OK)
        return st;
    st = gmmrrt_map_decode_image(data, len, path, &info, unknown_blocked, raster, err, errcap);
    free(data);
    return st;
}
