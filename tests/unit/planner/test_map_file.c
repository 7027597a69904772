/*
 * test_map_file.c - planner.map_file: map_server maps (planner/io map_file.h) into the raster,
 * and planning in them. The floor plan of logs/maps/ loads from PGM and from PNG to the same
 * cells; bad input is refused with the file, line and key or the sizes named (a missing key, a
 * negative resolution, pixel data shorter or longer than the header, a map larger than the
 * raster's capacity, a directory as the image), the raster unchanged; and plans in the floor
 * plan keep more than the robot's radius from every blocked pixel, checked against the image
 * file read here by its own small PGM reader, not against the planner's raster or grid.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "gmmrrt/map_file.h"
#include "gmmrrt/planner.h"

static char maps_dir[1024];
static char tmp_dir[256];

static int setup(void **state)
{
    (void)state;
    const char *data = getenv("GMMRRT_TEST_DATA_DIR"); /* tests/data: the maps are in logs/maps */
    snprintf(maps_dir, sizeof maps_dir, "%s/../../logs/maps", data ? data : "tests/data");
    const char *tmp = getenv("TMPDIR");
    snprintf(tmp_dir, sizeof tmp_dir, "%s/gmmrrt_map_test_XXXXXX", tmp && tmp[0] ? tmp : P_tmpdir);
    return mkdtemp(tmp_dir) ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    char cmd[512];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp_dir);
    return system(cmd) == 0 ? 0 : -1;
}

typedef struct {
    void *mem;
    gmmrrt_raster_t r;
} raster_block_t;

static void make_raster(raster_block_t *b, int32_t max_cells, int32_t max_side)
{
    const size_t size = gmmrrt_raster_mem_size(max_cells, max_side);
    b->mem = aligned_alloc(8, (size + 7u) & ~(size_t)7u);
    assert_non_null(b->mem);
    assert_int_equal(gmmrrt_raster_init(&b->r, b->mem, size, max_cells, max_side), GMMRRT_OK);
}

static void write_file(const char *name, const void *data, size_t len)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", tmp_dir, name);
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, len, f), len);
    fclose(f);
}

static const char *good_yaml(const char *image)
{
    static char y[512];
    snprintf(y, sizeof y,
             "image: %s\nresolution: 0.1\norigin: [-1.0, -2.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\n"
             "free_thresh: 0.196\n",
             image);
    return y;
}

/* Loads tmp_dir/name into the raster; returns the status, the message in err. */
static gmmrrt_status_t load(raster_block_t *b, const char *name, char *err, size_t errcap)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", tmp_dir, name);
    return gmmrrt_map_load_file(path, 1, &b->r, err, errcap);
}

static void test_floor_plan_loads_from_pgm_and_png_alike(void **state)
{
    (void)state;
    raster_block_t a, p;
    make_raster(&a, 1 << 20, 4096);
    make_raster(&p, 1 << 20, 4096);
    char path[1200], err[512];
    snprintf(path, sizeof path, "%s/floor.yaml", maps_dir);
    assert_int_equal(gmmrrt_map_load_file(path, 1, &a.r, err, sizeof err), GMMRRT_OK);
    snprintf(path, sizeof path, "%s/floor_png.yaml", maps_dir);
    assert_int_equal(gmmrrt_map_load_file(path, 1, &p.r, err, sizeof err), GMMRRT_OK);
    assert_int_equal(a.r.width, 440);
    assert_int_equal(a.r.height, 280);
    assert_true(a.r.resolution_m == 0.05 && a.r.origin_x == -11.0 && a.r.origin_y == -7.0);
    assert_true(gmmrrt_raster_distance_ready(&a.r));
    assert_memory_equal(a.r.cells, p.r.cells, 440 * 280);
    /* Bottom-left pixel is outside the building (unknown), the outer wall at 1.1 m is occupied,
     * the first room inside free: the image's top row is the raster's last. */
    assert_int_equal(a.r.cells[0], GMMRRT_RASTER_UNKNOWN);
    assert_int_equal(a.r.cells[22 * 440 + 100], GMMRRT_RASTER_OCCUPIED);
    assert_int_equal(a.r.cells[40 * 440 + 40], GMMRRT_RASTER_FREE);
    free(a.mem);
    free(p.mem);
}

static void assert_refused(raster_block_t *b, const char *name, gmmrrt_status_t want, const char *must_say,
                           const char *and_say)
{
    char err[512];
    const uint32_t gen = b->r.generation;
    const gmmrrt_status_t st = load(b, name, err, sizeof err);
    if (st != want || !strstr(err, must_say) || (and_say && !strstr(err, and_say)))
        fail_msg("%s: status %d, message '%s' (want %d with '%s')", name, (int)st, err, (int)want, must_say);
    assert_int_equal(b->r.generation, gen); /* the raster is untouched */
}

static void test_bad_maps_are_refused_naming_the_problem(void **state)
{
    (void)state;
    raster_block_t b;
    make_raster(&b, 64 * 64, 64);
    /* A good 4 x 3 map first, so the refusals below have something to keep. */
    const uint8_t pgm[] = "P5\n4 3\n255\n\xfe\xfe\xfe\xfe\xfe\x00\x00\xfe\xfe\xfe\xfe\xcd";
    write_file("ok.pgm", pgm, sizeof pgm - 1);
    write_file("ok.yaml", good_yaml("ok.pgm"), strlen(good_yaml("ok.pgm")));
    char err[512];
    assert_int_equal(load(&b, "ok.yaml", err, sizeof err), GMMRRT_OK);
    assert_int_equal(b.r.cells[1 * 4 + 1], GMMRRT_RASTER_OCCUPIED);
    assert_int_equal(b.r.cells[0 * 4 + 3], GMMRRT_RASTER_UNKNOWN); /* bottom row, last pixel 205 */

    const char *missing = "image: ok.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\n";
    write_file("missing.yaml", missing, strlen(missing));
    assert_refused(&b, "missing.yaml", GMMRRT_ERR_INVALID_ARGUMENT, "missing key 'free_thresh'", "missing.yaml");

    const char *neg = "image: ok.pgm\nresolution: -0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\n"
                      "free_thresh: 0.196\n";
    write_file("neg.yaml", neg, strlen(neg));
    assert_refused(&b, "neg.yaml", GMMRRT_ERR_INVALID_ARGUMENT, "neg.yaml:2: key 'resolution'", NULL);

    const char *origin = "image: ok.pgm\nresolution: 0.05\norigin: [0, 0]\nnegate: 0\noccupied_thresh: 0.65\n"
                         "free_thresh: 0.196\n";
    write_file("origin.yaml", origin, strlen(origin));
    assert_refused(&b, "origin.yaml", GMMRRT_ERR_INVALID_ARGUMENT, "origin.yaml:3: key 'origin'", NULL);

    const char *syntax = "image: [ok.pgm\nresolution: 0.05\n";
    write_file("syntax.yaml", syntax, strlen(syntax));
    assert_refused(&b, "syntax.yaml", GMMRRT_ERR_INVALID_ARGUMENT, "syntax.yaml:", "YAML error");

    write_file("short.pgm", pgm, sizeof pgm - 2); /* one pixel byte missing */
    write_file("short.yaml", good_yaml("short.pgm"), strlen(good_yaml("short.pgm")));
    assert_refused(&b, "short.yaml", GMMRRT_ERR_INVALID_ARGUMENT, "short.pgm: pixel data is 11 bytes",
                   "4 x 3 pixels need 12");

    const uint8_t longer[] = "P5\n4 3\n255\n\xfe\xfe\xfe\xfe\xfe\x00\x00\xfe\xfe\xfe\xfe\xcd\xfe";
    write_file("long.pgm", longer, sizeof longer - 1);
    write_file("long.yaml", good_yaml("long.pgm"), strlen(good_yaml("long.pgm")));
    assert_refused(&b, "long.yaml", GMMRRT_ERR_INVALID_ARGUMENT, "pixel data is 13 bytes", NULL);

    const char big[] = "P5\n100 50\n255\n";
    char *bigbuf = malloc(sizeof big - 1 + 5000);
    memcpy(bigbuf, big, sizeof big - 1);
    memset(bigbuf + sizeof big - 1, 254, 5000);
    write_file("big.pgm", bigbuf, sizeof big - 1 + 5000);
    free(bigbuf);
    write_file("big.yaml", good_yaml("big.pgm"), strlen(good_yaml("big.pgm")));
    assert_refused(&b, "big.yaml", GMMRRT_ERR_BUFFER_TOO_SMALL, "100 x 50 = 5000 cells", "holds 4096 cells");

    write_file("text.pgm", "hello", 5);
    write_file("text.yaml", good_yaml("text.pgm"), strlen(good_yaml("text.pgm")));
    assert_refused(&b, "text.yaml", GMMRRT_ERR_INVALID_ARGUMENT, "not a PGM", NULL);

    char dir[512];
    snprintf(dir, sizeof dir, "%s/adir", tmp_dir);
    assert_int_equal(mkdir(dir, 0700), 0);
    write_file("dir.yaml", good_yaml("adir"), strlen(good_yaml("adir")));
    assert_refused(&b, "dir.yaml", GMMRRT_ERR_IO, "adir: map image is not a regular file", NULL);
    assert_refused(&b, "nothere.yaml", GMMRRT_ERR_IO, "cannot open map YAML", NULL);

    const char *raw = "image: ok.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\n"
                      "free_thresh: 0.196\nmode: raw\n";
    write_file("raw.yaml", raw, strlen(raw));
    assert_refused(&b, "raw.yaml", GMMRRT_ERR_INVALID_ARGUMENT, "raw.yaml:7: key 'mode'", NULL);
    free(b.mem);
}

/* The image read here, independently of planner/io: 1 where a pixel blocks (p > 0.65, or
 * unknown: neither free nor occupied), rows top first. */
typedef struct {
    int w, h;
    uint8_t *blocked;
} image_t;

static image_t read_floor_image(void)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/floor.pgm", maps_dir);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    char magic[3] = {0};
    int maxval = 0;
    image_t im = {0, 0, NULL};
    assert_int_equal(fscanf(f, "%2s", magic), 1);
    assert_string_equal(magic, "P5");
    int c;
    while ((c = fgetc(f)) != EOF && c != '\n') /* rest of the magic line */
        ;
    while ((c = fgetc(f)) == '#')
        while ((c = fgetc(f)) != EOF && c != '\n')
            ;
    ungetc(c, f);
    assert_int_equal(fscanf(f, "%d %d %d", &im.w, &im.h, &maxval), 3);
    fgetc(f);
    im.blocked = malloc((size_t)im.w * (size_t)im.h);
    for (int k = 0; k < im.w * im.h; ++k) {
        const int v = fgetc(f);
        assert_true(v >= 0);
        const double p = (255.0 - v) / 255.0;
        im.blocked[k] = p > 0.65 || !(p < 0.196);
    }
    fclose(f);
    return im;
}

/* Distance (m) from world (x, y) to the nearest blocked pixel square of the floor image
 * (origin (-11, -7), 5 cm, no rotation; outside the image counts as blocked). */
static double image_clearance(const image_t *im, double x, double y)
{
    const double u = (x + 11.0) / 0.05, v = (y + 7.0) / 0.05; /* cells, y up */
    if (u < 0 || v < 0 || u > im->w || v > im->h)
        return 0.0;
    double best = INFINITY;
    const int r = 12; /* cells: 0.6 m, more than the robot radius plus a margin */
    for (int j = (int)v - r; j <= (int)v + r; ++j)
        for (int i = (int)u - r; i <= (int)u + r; ++i) {
            const int outside = i < 0 || j < 0 || i >= im->w || j >= im->h;
            if (!outside && !im->blocked[(im->h - 1 - j) * im->w + i])
                continue;
            const double ex = u < i ? i - u : (u > i + 1 ? u - i - 1 : 0.0);
            const double ey = v < j ? j - v : (v > j + 1 ? v - j - 1 : 0.0);
            best = fmin(best, hypot(ex, ey) * 0.05);
        }
    return best;
}

static void test_plans_in_the_floor_plan_keep_the_robot_radius_from_every_wall(void **state)
{
    (void)state;
    raster_block_t b;
    make_raster(&b, 1 << 20, 4096);
    char path[1200], err[512];
    snprintf(path, sizeof path, "%s/floor.yaml", maps_dir);
    assert_int_equal(gmmrrt_map_load_file(path, 1, &b.r, err, sizeof err), GMMRRT_OK);
    const image_t im = read_floor_image();
    gmmrrt_planner_config_t cfg;
    gmmrrt_planner_config_default(&cfg);
    cfg.planner = GMMRRT_PLANNER_RRT_STAR;
    cfg.robot_radius_m = 0.3;
    cfg.max_nodes = 6000;
    const size_t size = gmmrrt_planner_mem_size(&cfg);
    void *mem = aligned_alloc(8, (size + 7u) & ~(size_t)7u);
    gmmrrt_planner_t *p;
    assert_int_equal(gmmrrt_planner_init(&p, mem, size, &cfg), GMMRRT_OK);
    /* From the first room below the corridor to the far room above it, through two doorways. */
    const double ends[][4] = {{-9.0, -2.0, 8.0, 4.0}, {-2.0, -4.0, 5.0, -3.0}, {8.5, -4.5, -8.5, 4.5}};
    for (int e = 0; e < 3; ++e) {
        gmmrrt_problem_t pr;
        memset(&pr, 0, sizeof pr);
        pr.start_x = ends[e][0];
        pr.start_y = ends[e][1];
        pr.goal_x = ends[e][2];
        pr.goal_y = ends[e][3];
        pr.goal_tolerance_m = 0.1;
        pr.task = GMMRRT_TASK_NONE;
        pr.target_person = -1;
        pr.obstacles.bounds = (gmmrrt_bounds_t){-10.0, -6.0, 10.0, 6.0};
        pr.obstacles.raster = &b.r;
        assert_int_equal(gmmrrt_planner_set_problem(p, &pr), GMMRRT_OK);
        gmmrrt_budget_t budget = {0.0, 20000, 0.0, 0};
        gmmrrt_plan_stats_t st;
        assert_int_equal(gmmrrt_planner_run(p, &budget, &st), GMMRRT_OK);
        /* Every tree edge (the path is made of them), sampled every 5 mm. */
        double worst = INFINITY;
        for (int32_t i = 1; i < st.nodes; ++i) {
            double x, y, px, py, c;
            int32_t parent, pp;
            assert_int_equal(gmmrrt_planner_node(p, i, &x, &y, &parent, &c), GMMRRT_OK);
            assert_int_equal(gmmrrt_planner_node(p, parent, &px, &py, &pp, &c), GMMRRT_OK);
            const int n = 1 + (int)(hypot(x - px, y - py) / 0.005);
            for (int k = 0; k <= n; ++k)
                worst = fmin(worst, image_clearance(&im, px + (x - px) * k / n, py + (y - py) * k / n));
        }
        if (!(worst > cfg.robot_radius_m))
            fail_msg("problem %d: a tree edge comes %.6f m from a blocked pixel (robot radius %.2f)", e, worst,
                     cfg.robot_radius_m);
        gmmrrt_path_t out;
        assert_int_equal(gmmrrt_planner_best_path(p, &out), GMMRRT_OK);
        for (int32_t k = 0; k < out.num_points; ++k)
            assert_true(image_clearance(&im, out.x[k], out.y[k]) > cfg.robot_radius_m);
    }
    free(im.blocked);
    free(mem);
    free(b.mem);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_floor_plan_loads_from_pgm_and_png_alike),
        cmocka_unit_test(test_bad_maps_are_refused_naming_the_problem),
        cmocka_unit_test(test_plans_in_the_floor_plan_keep_the_robot_radius_from_every_wall),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
