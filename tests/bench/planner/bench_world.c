/*
 * bench_world.c - bench_world: what the collision world's set-up costs (prints, asserts
 * nothing; tools/run bench and docs/benchmarks.md).
 *
 *  1. The worst legal OBSTACLES content: 64 huge circles far away and 64 long diagonal boxes
 *     across the planning area, changed every cycle: set_problem's time (the set-up before the
 *     first iteration) and the tiles a 50 ms search then computes, per cycle.
 *  2. Map load + distance transform for 1000 x 1000 and 4000 x 4000 cells (a PGM written to
 *     the temporary folder, read by gmmrrt_map_load_file: YAML, image, thresholds, field), and
 *     the field alone.
 *  3. One 1081-beam scan into a 1000 x 1000 raster, and the field after it.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "gmmrrt/map_file.h"
#include "gmmrrt/planner.h"

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static int cmp(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void worst_obstacles(void)
{
    gmmrrt_planner_config_t cfg;
    gmmrrt_planner_config_default(&cfg);
    cfg.planner = GMMRRT_PLANNER_RRT_STAR;
    const size_t size = gmmrrt_planner_mem_size(&cfg);
    void *mem = aligned_alloc(8, (size + 7u) & ~(size_t)7u);
    gmmrrt_planner_t *p;
    if (!mem || gmmrrt_planner_init(&p, mem, size, &cfg) != GMMRRT_OK) {
        fprintf(stderr, "bench_world: planner init failed\n");
        exit(1);
    }
    enum { CYCLES = 40 };
    double setup[CYCLES], lazy[CYCLES];
    for (int c = 0; c < CYCLES; ++c) {
        gmmrrt_problem_t pr;
        memset(&pr, 0, sizeof pr);
        pr.start_x = -20.0;
        pr.start_y = -20.0;
        pr.goal_x = 20.0;
        pr.goal_y = 20.0;
        pr.goal_tolerance_m = 0.1;
        pr.task = GMMRRT_TASK_NONE;
        pr.target_person = -1;
        pr.obstacles.bounds = (gmmrrt_bounds_t){-25.0, -25.0, 25.0, 25.0}; /* 1M cells at 5 cm */
        const double jitter = 0.001 * c; /* a new world every cycle */
        pr.obstacles.num_circles = GMMRRT_MAX_CIRCLES;
        for (int k = 0; k < GMMRRT_MAX_CIRCLES; ++k) {
            const double a = 2.0 * M_PI * k / GMMRRT_MAX_CIRCLES;
            pr.obstacles.circles[k] = (gmmrrt_circle_t){5000.0 * cos(a) + jitter, 5000.0 * sin(a), 4000.0};
        }
        pr.obstacles.num_boxes = GMMRRT_MAX_BOXES;
        for (int k = 0; k < GMMRRT_MAX_BOXES; ++k) {
            /* Long thin diagonal walls across the area, with gaps between them. */
            const double off = -24.0 + 48.0 * k / GMMRRT_MAX_BOXES + jitter;
            pr.obstacles.boxes[k] = (gmmrrt_box_t){off, -off, 60.0, 0.05, M_PI / 4.0 + 1e-6 * k};
        }
        /* Along the corridor between the walls x - y = 0 and x - y = -1.5. */
        pr.start_x = -5.0;
        pr.start_y = -4.25;
        pr.goal_x = 4.25;
        pr.goal_y = 5.0;
        const double t0 = now_ms();
        const gmmrrt_status_t st = gmmrrt_planner_set_problem(p, &pr);
        setup[c] = now_ms() - t0;
        if (st != GMMRRT_OK) {
            fprintf(stderr, "bench_world: set_problem %s\n", gmmrrt_status_str(st));
            exit(1);
        }
        gmmrrt_budget_t b = {50.0, 0, 0.0, 0};
        gmmrrt_plan_stats_t s;
        (void)gmmrrt_planner_run(p, &b, &s);
        lazy[c] = (double)gmmrrt_world_lazy_cells(gmmrrt_planner_world(p));
    }
    qsort(setup, CYCLES, sizeof setup[0], cmp);
    qsort(lazy, CYCLES, sizeof lazy[0], cmp);
    printf("worst OBSTACLES (64 circles r=4 km far away + 64 diagonal 60 m walls, changed every cycle, 1M-cell grid):\n"
           "  set_problem ms p50 %.4f max %.4f over %d cycles; cells computed by a 50 ms search p50 %.0f max %.0f\n",
           setup[CYCLES / 2], setup[CYCLES - 1], CYCLES, lazy[CYCLES / 2], lazy[CYCLES - 1]);
    free(mem);
}

static void write_map(const char *dir, int side, char *yaml, size_t cap)
{
    char pgm[512];
    snprintf(pgm, sizeof pgm, "%s/bench_map_%d.pgm", dir, side);
    snprintf(yaml, cap, "%s/bench_map_%d.yaml", dir, side);
    FILE *f = fopen(pgm, "wb");
    fprintf(f, "P5\n%d %d\n255\n", side, side);
    unsigned char *row = malloc((size_t)side);
    for (int j = 0; j < side; ++j) {
        for (int i = 0; i < side; ++i) /* walls every 100 cells with doors, and unknown outside a margin */
            row[i] = (i % 100 == 0 && j % 100 > 20) || (j % 100 == 0 && i % 100 > 20) ? 0
                     : (i < 5 || j < 5)                                              ? 205
                                                                                     : 254;
        fwrite(row, 1, (size_t)side, f);
    }
    free(row);
    fclose(f);
    f = fopen(yaml, "w");
    fprintf(f, "image: bench_map_%d.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\n"
               "free_thresh: 0.196\n", side);
    fclose(f);
}

static void maps(void)
{
    const char *tmp = getenv("TMPDIR");
    const char *dir = tmp && tmp[0] ? tmp : P_tmpdir;
    const int32_t max_side = 4000, max_cells = 4000 * 4000;
    const size_t size = gmmrrt_raster_mem_size(max_cells, max_side);
    void *mem = aligned_alloc(8, (size + 7u) & ~(size_t)7u);
    gmmrrt_raster_t r;
    if (!mem || gmmrrt_raster_init(&r, mem, size, max_cells, max_side) != GMMRRT_OK) {
        fprintf(stderr, "bench_world: raster init failed\n");
        exit(1);
    }
    const int sides[] = {1000, 4000};
    for (int s = 0; s < 2; ++s) {
        char yaml[512], err[512];
        write_map(dir, sides[s], yaml, sizeof yaml);
        double load = INFINITY, field = INFINITY;
        for (int rep = 0; rep < 3; ++rep) {
            const double t0 = now_ms();
            if (gmmrrt_map_load_file(yaml, 1, &r, err, sizeof err) != GMMRRT_OK) {
                fprintf(stderr, "bench_world: %s\n", err);
                exit(1);
            }
            const double t1 = now_ms();
            gmmrrt_raster_update_distance(&r, 0, 0.0);
            const double t2 = now_ms();
            load = fmin(load, t1 - t0);
            field = fmin(field, t2 - t1);
        }
        printf("map %d x %d cells: load (YAML + PGM + thresholds + field) %.1f ms, field alone %.1f ms (best of 3)\n",
               sides[s], sides[s], load, field);
        remove(yaml);
        yaml[strlen(yaml) - 4] = '\0';
        strcat(yaml, "pgm");
        remove(yaml);
    }
    /* A 1081-beam scan (270 deg at 0.25 deg) into the 1000 x 1000 map. */
    char yaml[512], err[512];
    write_map(dir, 1000, yaml, sizeof yaml);
    gmmrrt_map_load_file(yaml, 1, &r, err, sizeof err);
    static float ranges[1081];
    for (int k = 0; k < 1081; ++k)
        ranges[k] = (float)(4.0 + 3.0 * sin(0.05 * k));
    gmmrrt_scan_t scan = {-0.75 * M_PI, 1.5 * M_PI / 1080.0, 0.05, 30.0, 1081, ranges};
    double apply = INFINITY, field = INFINITY;
    for (int rep = 0; rep < 5; ++rep) {
        const double t0 = now_ms();
        gmmrrt_raster_apply_scan(&r, &scan, 25.0, 25.0, 0.1 * rep, 1000000 + rep * 100000, NULL, NULL);
        const double t1 = now_ms();
        gmmrrt_raster_update_distance(&r, 1000000 + rep * 100000, 500.0);
        const double t2 = now_ms();
        apply = fmin(apply, t1 - t0);
        field = fmin(field, t2 - t1);
    }
    double window = INFINITY;
    for (int rep = 0; rep < 5; ++rep) {
        gmmrrt_raster_apply_scan(&r, &scan, 25.0, 25.0, 0.1 * rep, 2000000 + rep * 100000, NULL, NULL);
        const double t0 = now_ms();
        gmmrrt_raster_update_distance_window(&r, 2000000 + rep * 100000, 500.0, 15.0, 15.0, 35.0, 35.0, 1.0);
        window = fmin(window, now_ms() - t0);
    }
    printf("1081-beam scan into 1000 x 1000 cells: ray casting %.3f ms, field after it %.1f ms, field over a\n"
           "  20 x 20 m window (reach 1 m) %.2f ms (best of 5)\n", apply, field, window);
    remove(yaml);
    yaml[strlen(yaml) - 4] = '\0';
    strcat(yaml, "pgm");
    remove(yaml);
    free(mem);
}

int main(void)
{
    worst_obstacles();
    maps();
    return 0;
}
