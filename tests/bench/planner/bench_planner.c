/*
 * bench_planner.c - micro-benchmarks of the planner core; prints,
 * asserts nothing (docs/planner.md quotes its output with this command):
 *   1. collision queries: FCL per query (what the loop would do without the grid) against
 *      the clearance grid, and the cost of building the grid (set_problem);
 *   2. the whole planner on the disc problem (start (-5, 0), goal (5, 0), disc r = 2, point
 *      robot, optimum 10.811): iterations per second, time to the first solution and to
 *      within 1 % of the optimum, for rrt-star; and iterations per second of gmm-rrt-star
 *      with a 10-component (d, theta) model around a person.
 * Usage: bench_planner [seeds (default 5)]
 */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "fcl_adapter.h"
#include "planner_fixtures.h"

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof v[0], cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static gmmrrt_obstacle_set_t clutter(void)
{
    gmmrrt_obstacle_set_t o;
    memset(&o, 0, sizeof o);
    o.bounds = (gmmrrt_bounds_t){-7.0, -5.0, 7.0, 5.0};
    for (int i = 0; i < 10; ++i)
        o.circles[o.num_circles++] = (gmmrrt_circle_t){-6.0 + 1.3 * i, 3.0 * sin(i), 0.3 + 0.05 * i};
    for (int i = 0; i < 5; ++i)
        o.boxes[o.num_boxes++] = (gmmrrt_box_t){-5.0 + 2.5 * i, -3.5 + 0.5 * i, 1.0, 0.4, 0.3 * i};
    for (int i = 0; i < 3; ++i)
        o.people[o.num_people++] = (gmmrrt_pose_t){-2.0 + 2.0 * i, 1.5, 0.5 * i};
    return o;
}

/* What the loop would call without a grid: FCL distance to every obstacle. */
static int fcl_point_free(const gmmrrt_obstacle_set_t *o, double r, double pr, double x, double y)
{
    for (int32_t k = 0; k < o->num_circles; ++k)
        if (gmmrrt_fcl_disc_distance(x, y, r, o->circles[k].x, o->circles[k].y, o->circles[k].radius_m) <= 0.0)
            return 0;
    for (int32_t k = 0; k < o->num_people; ++k)
        if (gmmrrt_fcl_disc_distance(x, y, r, o->people[k].x, o->people[k].y, pr) <= 0.0)
            return 0;
    for (int32_t k = 0; k < o->num_boxes; ++k) {
        const gmmrrt_box_t *b = &o->boxes[k];
        if (gmmrrt_fcl_box_distance(x, y, r, b->x, b->y, b->width_m, b->height_m, b->yaw) <= 0.0)
            return 0;
    }
    return 1;
}

static void bench_collision(void)
{
    const gmmrrt_obstacle_set_t o = clutter();
    const int32_t cells = 1 << 20;
    const size_t size = gmmrrt_world_mem_size(cells);
    void *mem = aligned_alloc(8, size);
    gmmrrt_world_t *w;
    const int builds = 20;
    double t0 = now_ms();
    for (int i = 0; i < builds; ++i)
        gmmrrt_world_build(&w, mem, size, cells, 0.05, 0.3, 0.25, &o);
    const double build_ms = (now_ms() - t0) / builds;
    /* What the daemon's cycles pay since the grid is kept (gmmrrt_world_update): people moved
     * only, and a robot step of 10 cm that moves the bounds (cells shifted, a strip computed). */
    gmmrrt_obstacle_set_t moving = o;
    const int updates = 200;
    double kept_ms = 0.0, shifted_ms = 0.0;
    for (int i = 0; i < updates; ++i) {
        moving.people[i % moving.num_people].x += 0.01;
        t0 = now_ms();
        gmmrrt_world_update(&w, mem, size, cells, 0.05, 0.3, 0.25, &moving);
        kept_ms += now_ms() - t0;
        const double step = (i % 40 < 20) ? 0.1 : -0.1;
        moving.bounds.xmin += step;
        moving.bounds.xmax += step;
        t0 = now_ms();
        gmmrrt_world_update(&w, mem, size, cells, 0.05, 0.3, 0.25, &moving);
        shifted_ms += now_ms() - t0;
    }
    gmmrrt_world_build(&w, mem, size, cells, 0.05, 0.3, 0.25, &o);

    enum { Q = 400000 };
    static double qx[Q], qy[Q];
    gmmrrt_rng_t rng;
    gmmrrt_rng_seed(&rng, 1);
    for (int i = 0; i < Q; ++i) {
        qx[i] = -7.0 + 14.0 * gmmrrt_rng_uniform(&rng);
        qy[i] = -5.0 + 10.0 * gmmrrt_rng_uniform(&rng);
    }
    int free_grid = 0, free_fcl = 0, disagree = 0;
    t0 = now_ms();
    for (int i = 0; i < Q; ++i)
        free_grid += gmmrrt_world_point_free(w, qx[i], qy[i]);
    const double grid_ns = (now_ms() - t0) * 1e6 / Q;
    t0 = now_ms();
    for (int i = 0; i < Q; ++i)
        free_fcl += fcl_point_free(&o, 0.3, 0.25, qx[i], qy[i]);
    const double fcl_ns = (now_ms() - t0) * 1e6 / Q;
    for (int i = 0; i < Q; ++i)
        disagree += gmmrrt_world_point_free(w, qx[i], qy[i]) != fcl_point_free(&o, 0.3, 0.25, qx[i], qy[i]);
    printf("collision, 14 x 10 m, 10 circles + 5 boxes + 3 people, robot r = 0.3 m, grid 5 cm:\n");
    printf("  grid build (set_problem)   %8.2f ms\n", build_ms);
    printf("  grid kept, people moved    %8.3f ms   (gmmrrt_world_update)\n", kept_ms / updates);
    printf("  grid shifted, 10 cm step   %8.3f ms   (gmmrrt_world_update)\n", shifted_ms / updates);
    printf("  point query, grid          %8.1f ns   (%d of %d free)\n", grid_ns, free_grid, Q);
    printf("  point query, FCL per query %8.1f ns   (%d free)   ratio FCL/grid %.1f\n", fcl_ns, free_fcl,
           fcl_ns / grid_ns);
    printf("  grid calls blocked what FCL calls free: %d of %d (%.2f %%, within a cell of an obstacle)\n",
           disagree, Q, 100.0 * disagree / Q);
    free(mem);
}

static void bench_disc(int seeds)
{
    const double optimum = disc_detour_length(5.0, 2.0);
    double ips[64], first_ms[64], within_ms[64], within_it[64];
    int reached = 0;
    for (int s = 0; s < seeds; ++s) {
        gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
        cfg.seed = (uint64_t)s + 1;
        cfg.max_nodes = 200000;
        test_planner_t t;
        test_planner_make(&t, &cfg);
        gmmrrt_problem_t pr = disc_problem();
        gmmrrt_planner_set_problem(t.p, &pr);
        gmmrrt_plan_stats_t st;
        within_ms[s] = within_it[s] = INFINITY;
        for (int chunk = 0; chunk < 400; ++chunk) {
            gmmrrt_budget_t b = {0.0, 500, 0.0, 0};
            if (gmmrrt_planner_run(t.p, &b, &st) == GMMRRT_POOL_FULL)
                break;
            if (st.best_cost <= optimum * 1.01) {
                within_ms[s] = st.time_ms;
                within_it[s] = (double)st.iterations;
                ++reached;
                break;
            }
        }
        first_ms[s] = st.first_solution_ms;
        /* iterations per second over a fixed 20000-iteration run */
        gmmrrt_planner_set_problem(t.p, &pr);
        gmmrrt_budget_t b = {0.0, 20000, 0.0, 0};
        gmmrrt_planner_run(t.p, &b, &st);
        ips[s] = (double)st.iterations / (st.time_ms * 1e-3);
        test_planner_free(&t);
    }
    printf("rrt-star on the disc problem (optimum %.4f m), median of %d seeds:\n", optimum, seeds);
    printf("  iterations per second      %10.0f (first 20000 iterations)\n", median(ips, seeds));
    printf("  time to first solution     %10.2f ms\n", median(first_ms, seeds));
    printf("  time to within 1 %%         %10.2f ms, %.0f iterations (%d of %d seeds got there)\n",
           median(within_ms, seeds), median(within_it, seeds), reached, seeds);
}

static void bench_social(int seeds)
{
    gmmrrt_model_t m;
    double theta[10];
    for (int i = 0; i < 5; ++i) {
        theta[i] = M_PI * (i + 1) / 6.0;
        theta[i + 5] = -theta[i];
    }
    make_features_model(&m, theta, 10, 1.2, 0.2, 0.25);
    double ips[64], first_ms[64];
    for (int s = 0; s < seeds; ++s) {
        gmmrrt_planner_config_t cfg;
        gmmrrt_planner_config_default(&cfg);
        cfg.seed = (uint64_t)s + 1;
        test_planner_t t;
        test_planner_make(&t, &cfg);
        gmmrrt_problem_t pr = empty_problem(-4.0, 0.0, 4.0, 0.0);
        pr.goal_tolerance_m = 0.1;
        pr.task = GMMRRT_TASK_AVOID;
        pr.model = &m;
        pr.obstacles.num_people = 1;
        pr.obstacles.people[0] = (gmmrrt_pose_t){0.0, 0.0, M_PI};
        gmmrrt_planner_set_problem(t.p, &pr);
        gmmrrt_budget_t b = {0.0, 20000, 0.0, 0};
        gmmrrt_plan_stats_t st;
        gmmrrt_planner_run(t.p, &b, &st);
        ips[s] = (double)st.iterations / (st.time_ms * 1e-3);
        first_ms[s] = st.first_solution_ms;
        test_planner_free(&t);
    }
    printf("gmm-rrt-star, avoid one person, 10-component (d, theta) model, defaults, median of %d seeds:\n", seeds);
    printf("  iterations per second      %10.0f (first 20000 iterations)\n", median(ips, seeds));
    printf("  time to first solution     %10.2f ms\n", median(first_ms, seeds));
}

int main(int argc, char **argv)
{
    int seeds = argc > 1 ? atoi(argv[1]) : 5;
    if (seeds < 1 || seeds > 64)
        seeds = 5;
    bench_collision();
    bench_disc(seeds);
    bench_social(seeds);
    return 0;
}
