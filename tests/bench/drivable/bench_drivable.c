/*
 * bench_drivable.c - time to a first solution of gmmrrt-bench-social's problems (avoid: person at
 * the origin facing the robot, (-4, 0) -> (4, 0); approach: person facing +x, (-4, 0.5) -> (1.2, 0))
 * plus gmmrrt_planner_drivable_path on that first path, median over seeds. The run is cut into
 * 8-iteration slices and stops at the first solution; wall-clock times (CLOCK_MONOTONIC).
 *
 *   build/bench/bench_drivable MODEL.gmm avoid|approach [SEEDS]
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "gmmrrt/drivable.h"
#include "gmmrrt/model_file.h"
#include "planner_fixtures.h"

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

static int by_value(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    if (argc < 3 || (strcmp(argv[2], "avoid") != 0 && strcmp(argv[2], "approach") != 0)) {
        fprintf(stderr, "usage: bench_drivable MODEL.gmm avoid|approach [SEEDS]\n");
        return 2;
    }
    const int approach = strcmp(argv[2], "approach") == 0;
    const int seeds = argc > 3 ? atoi(argv[3]) : 40;
    if (seeds < 1 || seeds > 1000) {
        fprintf(stderr, "bench_drivable: SEEDS must be in 1..1000\n");
        return 2;
    }
    static gmmrrt_model_t model;
    char err[256];
    if (gmmrrt_model_load_file(argv[1], &model, err, sizeof err) != GMMRRT_OK) {
        fprintf(stderr, "bench_drivable: %s\n", err);
        return 1;
    }
    double *first = calloc((size_t)seeds, sizeof *first), *drive = calloc((size_t)seeds, sizeof *drive);
    double *sum = calloc((size_t)seeds, sizeof *sum);
    if (!first || !drive || !sum)
        return 1;
    static gmmrrt_path_t path;
    for (int s = 0; s < seeds; ++s) {
        gmmrrt_planner_config_t cfg;
        gmmrrt_planner_config_default(&cfg);
        cfg.seed = (uint64_t)s + 1u;
        test_planner_t t;
        if (test_planner_make(&t, &cfg) != GMMRRT_OK)
            return 1;
        gmmrrt_problem_t pb = empty_problem(-4.0, approach ? 0.5 : 0.0, approach ? 1.2 : 4.0, 0.0);
        pb.obstacles.bounds = (gmmrrt_bounds_t){-6.0, -5.0, 6.0, 5.0};
        pb.goal_tolerance_m = 0.1;
        pb.model = &model;
        pb.task = approach ? GMMRRT_TASK_APPROACH : GMMRRT_TASK_AVOID;
        pb.target_person = approach ? 0 : -1;
        pb.obstacles.num_people = 1;
        pb.obstacles.people[0] = (gmmrrt_pose_t){0.0, 0.0, approach ? 0.0 : M_PI};
        gmmrrt_status_t st = gmmrrt_planner_set_problem(t.p, &pb);
        if (st != GMMRRT_OK) {
            fprintf(stderr, "bench_drivable: %s\n", gmmrrt_status_str(st));
            return 1;
        }
        gmmrrt_budget_t slice = {0.0, 8, 0.0, 0};
        gmmrrt_plan_stats_t stats;
        const double t0 = now_ms();
        do
            st = gmmrrt_planner_run(t.p, &slice, &stats);
        while (st == GMMRRT_NO_PATH_YET && stats.iterations < 1000000);
        const double t1 = now_ms();
        gmmrrt_drive_options_t opt;
        gmmrrt_drive_options_default(&opt);
        opt.arrival = approach ? GMMRRT_ARRIVAL_FACE_TARGET : GMMRRT_ARRIVAL_ANY;
        gmmrrt_drive_report_t rep;
        const gmmrrt_status_t ds = gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep);
        const double t2 = now_ms();
        if (st != GMMRRT_OK || (ds != GMMRRT_OK && ds != GMMRRT_TIGHT_TURNS)) {
            fprintf(stderr, "bench_drivable: seed %d: %s / %s\n", s + 1, gmmrrt_status_str(st), gmmrrt_status_str(ds));
            return 1;
        }
        first[s] = t1 - t0;
        drive[s] = t2 - t1;
        sum[s] = t2 - t0;
        test_planner_free(&t);
    }
    qsort(first, (size_t)seeds, sizeof *first, by_value);
    qsort(drive, (size_t)seeds, sizeof *drive, by_value);
    qsort(sum, (size_t)seeds, sizeof *sum, by_value);
    printf("%s, %d seeds, median: first solution %.3f ms, drivable path %.3f ms, both %.3f ms\n", argv[2], seeds,
           first[seeds / 2], drive[seeds / 2], sum[seeds / 2]);
    free(first);
    free(drive);
    free(sum);
    return 0;
}
