/*
 * bench_memory.c - gmmrrt-bench-memory: the planner's memory (planner.h: one caller-owned
 * block, nothing allocated after init; STYLE.md rule 1). Prints one JSON object:
 *   - the block size of the default configuration (gmmrrt_planner_mem_size);
 *   - bytes per node: the growth of that size per extra node of max_nodes (everything a
 *     node costs: pool entry, spatial index, history is not per node);
 *   - allocations (malloc, calloc, realloc, aligned_alloc, posix_memalign, free: this
 *     executable defines them over glibc's __libc_* entry points, as the planner.alloc test
 *     does, so C++ operator new inside FCL counts too) during set_problem, during run and
 *     best_path, for plain RRT* on the disc problem and for GMM-RRT* on an avoid scene with a
 *     hand-built (d, theta) mixture (paper Sect. 3-4).
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gmmrrt/planner.h"

#include "alloc_counter.h" /* defines malloc & co. and the counters `counting`, `alloc_calls` */

/* A (d, theta) avoid mixture: 10 components at 1.2 m around the person's sides. */
static gmmrrt_status_t make_avoid_model(gmmrrt_model_t *m)
{
    memset(m, 0, sizeof *m);
    m->kind = GMMRRT_MODEL_KIND_FEATURES;
    m->task = GMMRRT_TASK_AVOID;
    m->homotopy = GMMRRT_HOMOTOPY_ALL;
    m->dim = 2;
    m->k = 10;
    m->angle_mask = 1u << 1;
    m->delta = GMMRRT_MODEL_DEFAULT_DELTA;
    double sum = 0.0;
    for (int32_t i = 0; i < m->k; ++i) {
        const double side = i < 5 ? 1.0 : -1.0;
        m->weight[i] = i + 1 < m->k ? 0.1 : 1.0 - sum;
        sum += m->weight[i];
        m->mean[i][0] = 1.2;
        m->mean[i][1] = side * (M_PI / 6.0) * (double)(i % 5 + 1);
        m->chol[i][0] = 0.2;
        m->chol[i][2] = 0.25;
    }
    return gmmrrt_model_prepare(m, NULL, 0);
}

typedef struct {
    long set_problem_allocs, run_allocs;
    int64_t iterations;
    gmmrrt_status_t status;
} alloc_result_t;

static gmmrrt_status_t count_allocs(const gmmrrt_planner_config_t *cfg, const gmmrrt_problem_t *pb, double time_ms,
                                    alloc_result_t *out)
{
    const size_t size = gmmrrt_planner_mem_size(cfg);
    if (size == 0)
        return GMMRRT_ERR_INVALID_ARGUMENT;
    void *mem = aligned_alloc(64, (size + 63) / 64 * 64);
    if (!mem)
        return GMMRRT_ERR_BUFFER_TOO_SMALL;
    gmmrrt_planner_t *p = NULL;
    gmmrrt_status_t st = gmmrrt_planner_init(&p, mem, size, cfg);
    if (st == GMMRRT_OK) {
        alloc_calls = 0;
        counting = 1;
        st = gmmrrt_planner_set_problem(p, pb);
        counting = 0;
        out->set_problem_allocs = alloc_calls;
    }
    if (st == GMMRRT_OK) {
        static gmmrrt_path_t path; /* static: 6 kB, not on the stack */
        gmmrrt_budget_t budget = {time_ms, 0, 0.0, 0};
        gmmrrt_plan_stats_t stats;
        alloc_calls = 0;
        counting = 1;
        out->status = gmmrrt_planner_run(p, &budget, &stats);
        (void)gmmrrt_planner_best_path(p, &path);
        counting = 0;
        out->run_allocs = alloc_calls;
        out->iterations = stats.iterations;
    }
    free(mem);
    return st;
}

int main(int argc, char **argv)
{
    double time_ms = 200.0;
    if (argc == 2 && (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0)) {
        printf("usage: gmmrrt-bench-memory [TIME_MS]\nPrints the planner's memory figures as one JSON "
               "object; TIME_MS (default 200) is each counted run's budget.\n");
        return 0;
    }
    if (argc == 2) {
        char *end = NULL;
        time_ms = strtod(argv[1], &end);
        if (end == argv[1] || *end || !(time_ms > 0.0) || time_ms > 600000.0) {
            fprintf(stderr, "gmmrrt-bench-memory: TIME_MS must be a number in (0, 600000], got '%s'\n", argv[1]);
            return 2;
        }
    } else if (argc > 2) {
        fprintf(stderr, "gmmrrt-bench-memory: at most one argument (TIME_MS); see --help\n");
        return 2;
    }

    /* The counter must see an allocation made through the C library's entry points (called
     * through volatile pointers so that the compiler cannot elide the pair). */
    void *(*volatile alloc_fn)(size_t) = malloc;
    void (*volatile free_fn)(void *) = free;
    alloc_calls = 0;
    counting = 1;
    free_fn(alloc_fn(16));
    counting = 0;
    const int counter_works = alloc_calls == 2;

    gmmrrt_planner_config_t cfg;
    gmmrrt_planner_config_default(&cfg);
    const size_t default_bytes = gmmrrt_planner_mem_size(&cfg);
    gmmrrt_planner_config_t big = cfg;
    big.max_nodes = cfg.max_nodes + 100000;
    const size_t big_bytes = gmmrrt_planner_mem_size(&big);
    gmmrrt_planner_config_t small = cfg;
    small.max_nodes = 2;
    const size_t small_bytes = gmmrrt_planner_mem_size(&small);
    if (default_bytes == 0 || big_bytes == 0 || small_bytes == 0) {
        fprintf(stderr, "gmmrrt-bench-memory: gmmrrt_planner_mem_size rejected the default configuration\n");
        return 1;
    }
    const double bytes_per_node = (double)(big_bytes - default_bytes) / 100000.0;

    /* Plain RRT* on the disc problem of the OMPL comparison. */
    gmmrrt_planner_config_t rrt = cfg;
    rrt.planner = GMMRRT_PLANNER_RRT_STAR;
    rrt.w_task = 0.0;
    gmmrrt_problem_t disc;
    memset(&disc, 0, sizeof disc);
    disc.start_x = -5.0, disc.goal_x = 5.0, disc.goal_tolerance_m = 0.1, disc.target_person = -1;
    disc.obstacles.bounds = (gmmrrt_bounds_t){-10.0, -10.0, 10.0, 10.0};
    disc.obstacles.num_circles = 1;
    disc.obstacles.circles[0] = (gmmrrt_circle_t){0.0, 0.0, 2.0};
    alloc_result_t a_rrt = {0, 0, 0, GMMRRT_OK};
    gmmrrt_status_t st = count_allocs(&rrt, &disc, time_ms, &a_rrt);
    if (st != GMMRRT_OK) {
        fprintf(stderr, "gmmrrt-bench-memory: RRT* on the disc problem: %s\n", gmmrrt_status_str(st));
        return 1;
    }

    /* GMM-RRT* (default configuration) on an avoid scene. */
    static gmmrrt_model_t model;
    st = make_avoid_model(&model);
    if (st != GMMRRT_OK) {
        fprintf(stderr, "gmmrrt-bench-memory: avoid model: %s\n", gmmrrt_status_str(st));
        return 1;
    }
    gmmrrt_problem_t avoid;
    memset(&avoid, 0, sizeof avoid);
    avoid.start_x = -4.0, avoid.goal_x = 4.0, avoid.goal_tolerance_m = 0.1, avoid.target_person = -1;
    avoid.task = GMMRRT_TASK_AVOID;
    avoid.model = &model;
    avoid.obstacles.bounds = (gmmrrt_bounds_t){-6.0, -5.0, 6.0, 5.0};
    avoid.obstacles.num_people = 1;
    avoid.obstacles.people[0] = (gmmrrt_pose_t){0.0, 0.0, M_PI};
    alloc_result_t a_gmm = {0, 0, 0, GMMRRT_OK};
    st = count_allocs(&cfg, &avoid, time_ms, &a_gmm);
    if (st != GMMRRT_OK) {
        fprintf(stderr, "gmmrrt-bench-memory: GMM-RRT* on the avoid scene: %s\n", gmmrrt_status_str(st));
        return 1;
    }

    printf("{\"alloc_counter_works\":%s,\"default_max_nodes\":%d,\"default_mem_bytes\":%zu,\"mem_bytes_at_2_nodes\":%zu,"
           "\"bytes_per_node\":%.3f,\"grid_max_cells\":%d,\"history_capacity\":%d,\"time_ms\":%.3f,"
           "\"rrtstar_disc\":{\"set_problem_allocs\":%ld,\"run_allocs\":%ld,\"iterations\":%lld,\"status\":\"%s\"},"
           "\"gmm_rrtstar_avoid\":{\"set_problem_allocs\":%ld,\"run_allocs\":%ld,\"iterations\":%lld,\"status\":\"%s\"}}\n",
           counter_works ? "true" : "false", cfg.max_nodes, default_bytes, small_bytes, bytes_per_node, cfg.grid_max_cells, cfg.history_capacity, time_ms,
           a_rrt.set_problem_allocs, a_rrt.run_allocs, (long long)a_rrt.iterations, gmmrrt_status_str(a_rrt.status),
           a_gmm.set_problem_allocs, a_gmm.run_allocs, (long long)a_gmm.iterations, gmmrrt_status_str(a_gmm.status));
    return 0;
}
