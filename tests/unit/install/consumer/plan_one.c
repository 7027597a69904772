/*
 * plan_one.c - a program outside the project, built against an installed gmmrrt (pkg-config or
 * find_package): loads the model file argv[1] with gmmrrt_model_load_file and plans one path
 * around a standing person with GMM-RRT* (planner.h). Prints "path N points, length L m".
 * With GMMRRT_CONSUMER_LCMTYPES it also encodes and decodes a waypoints message
 * (gmmrrt::lcmtypes), so the installed message library and LCM link too.
 * Exit: 0 a path was found; 1 any error (printed).
 */
#include <stdio.h>
#include <stdlib.h>

#include "gmmrrt/model_file.h"
#include "gmmrrt/planner.h"
#ifdef GMMRRT_CONSUMER_LCMTYPES
#include "gmmrrt/gmmrrt_waypoints_t.h"
#endif

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s MODEL.gmm\n", argv[0]);
        return 1;
    }
    static gmmrrt_model_t model;
    char err[256];
    gmmrrt_status_t st = gmmrrt_model_load_file(argv[1], &model, err, sizeof err);
    if (st != GMMRRT_OK) {
        fprintf(stderr, "model %s: %s\n", argv[1], err);
        return 1;
    }
    gmmrrt_planner_config_t cfg;
    gmmrrt_planner_config_default(&cfg);
    cfg.max_nodes = 5000;
    const size_t size = gmmrrt_planner_mem_size(&cfg);
    void *mem = malloc(size);
    gmmrrt_planner_t *p = NULL;
    if (!mem || (st = gmmrrt_planner_init(&p, mem, size, &cfg)) != GMMRRT_OK) {
        fprintf(stderr, "planner init: %s\n", mem ? gmmrrt_status_str(st) : "out of memory");
        free(mem);
        return 1;
    }
    static gmmrrt_problem_t pr;
    pr.start_x = 0.0;
    pr.start_y = 0.0;
    pr.goal_x = 6.0;
    pr.goal_y = 0.0;
    pr.goal_tolerance_m = 0.1;
    pr.task = GMMRRT_TASK_AVOID;
    pr.target_person = -1;
    pr.model = &model;
    pr.obstacles.bounds = (gmmrrt_bounds_t){-3.0, -4.0, 9.0, 4.0};
    pr.obstacles.people[0] = (gmmrrt_pose_t){3.0, 0.2, 3.14159};
    pr.obstacles.num_people = 1;
    if ((st = gmmrrt_planner_set_problem(p, &pr)) != GMMRRT_OK) {
        fprintf(stderr, "problem refused: %s\n", gmmrrt_status_str(st));
        free(mem);
        return 1;
    }
    const gmmrrt_budget_t budget = {0.0, 3000, 0.0, 0};
    gmmrrt_plan_stats_t stats;
    gmmrrt_planner_run(p, &budget, &stats);
    static gmmrrt_path_t path;
    st = gmmrrt_planner_best_path(p, &path);
    free(mem);
    if (st != GMMRRT_OK || path.num_points < 2) {
        fprintf(stderr, "no path after %lld iterations: %s\n", (long long)stats.iterations, gmmrrt_status_str(st));
        return 1;
    }
#ifdef GMMRRT_CONSUMER_LCMTYPES
    static gmmrrt_waypoints_t msg, back;
    static char frame[] = "map";
    msg.utime = 1;
    msg.frame = frame;
    msg.num_waypoints = path.num_points;
    static uint8_t buf[1 << 16];
    const int n = gmmrrt_waypoints_t_encode(buf, 0, (int)sizeof buf, &msg);
    if (n <= 0 || gmmrrt_waypoints_t_decode(buf, 0, n, &back) != n || back.num_waypoints != path.num_points) {
        fprintf(stderr, "waypoints message did not round-trip (%d bytes)\n", n);
        return 1;
    }
    gmmrrt_waypoints_t_decode_cleanup(&back);
    printf("lcmtypes: waypoints message round-trips in %d bytes\n", n);
#endif
    printf("path %d points, length %.3f m\n", path.num_points, path.length_m);
    return 0;
}
