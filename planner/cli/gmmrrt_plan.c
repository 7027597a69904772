/*
 * gmmrrt_plan.c - gmmrrt-plan: plans one path with the gmmrrt core (rrtstar.h) from the
 * command line and prints it as x,y CSV or, with --json, one JSON object
 * (docs/planner.md). The model is read with gmmrrt_model_load_file.
 *
 * Exit status: 0 a path was found; 1 bad arguments, unreadable model or a problem the
 * planner refuses (start/goal in collision, model mismatch, ...); 3 no path within the
 * budget (the JSON object or an error line says so).
 */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gmmrrt/model_file.h"
#include "gmmrrt/rrtstar.h"

#define EXIT_BAD_INPUT 1
#define EXIT_NO_PATH 3

static const char *prog = "gmmrrt-plan";

/* Cost-history capacity of the CLI's planner (the library default is 1024): 4096 entries x 16 B.
 * When it fills, the planner keeps the latest improvement in the last slot and --json says
 * "cost_history_complete": false. */
#define GMMRRT_CLI_MAX_HISTORY 4096

static void usage(FILE *out)
{
    fprintf(out,
            "usage: %s [--model FILE] --start x,y --goal x,y [--person x,y,yaw ...]\n"
            "       [--obstacle circle:x,y,r | box:cx,cy,w,h,yaw ...]\n"
            "       [--planner gmm-rrt-star|rrt-star|gmm-rrt] [--bias B] [--budget-ms N]\n"
            "       [--iterations N] [--seed S] [--robot-radius R] [--bounds xmin,ymin,xmax,ymax]\n"
            "       [--task avoid|approach] [--target-person I] [--goal-tolerance M]\n"
            "       [--delta D] [--w-task W] [--rewire-k F] [--informed 0|1] [--json]\n"
            "\n"
            "Plans a path with GMM-RRT* (the paper's planner), plain RRT* or the GMM-RRT baseline\n"
            "and prints it as x,y CSV (header line first), or with --json one object:\n"
            "  {\"status\": ..., \"path\": [[x, y], ...], \"stats\": {\"iterations\": ..., \"nodes\": ...,\n"
            "   \"first_solution_ms\": ..., \"best_cost\": ..., \"length_m\": ..., \"time_ms\": ...,\n"
            "   \"cost_history\": [[iteration, best cost], ...], \"cost_history_complete\": true}}\n"
            "cost_history lists every improvement of the best cost (iteration = samples drawn so far,\n"
            "1-based); the best cost after N iterations is the last entry with iteration <= N.\n"
            "\n"
            "  --model FILE        mixture model (gmmrrt-learn); features kind for gmm-rrt-star,\n"
            "                      xy kind for gmm-rrt; optional for rrt-star\n"
            "  --start x,y         start position [m]\n"
            "  --goal x,y          goal position [m]\n"
            "  --person x,y,yaw    a standing person [m, m, rad facing]; repeat for several\n"
            "  --obstacle SPEC     circle:x,y,r or box:cx,cy,w,h,yaw [m, rad]; repeat\n"
            "  --planner NAME      default gmm-rrt-star with --model, rrt-star without\n"
            "  --bias B            probability of a mixture sample, [0, 1] (default 0.95)\n"
            "  --budget-ms N       wall-clock budget [ms] (default 1000 unless --iterations)\n"
            "  --iterations N      iteration cap (samples drawn); with no --budget-ms, no time limit\n"
            "  --seed S            random seed (default 1); same seed, same path\n"
            "  --robot-radius R    robot disc radius [m] (default 0.3; 0 = point robot)\n"
            "  --bounds ...        planning area [m] (default: everything given, padded 3 m)\n"
            "  --task NAME         avoid or approach (default: the model's task, else avoid)\n"
            "  --target-person I   person index (0-based) for approach (default 0)\n"
            "  --goal-tolerance M  goal region radius [m] (default 0.1)\n"
            "  --delta D           task-cost floor delta > 0 of c = delta / max(p, delta) (default: the\n"
            "                      model file's delta)\n"
            "  --w-task W          weight >= 0 of the task cost in the edge cost (default 2)\n"
            "  --rewire-k F        near set: at least the F ln(n+1) nearest nodes (default 4.485,\n"
            "                      OMPL's k_rrg); 0: the radius 15 sqrt(ln n / n)\n"
            "  --informed 0|1      informed sampling once a path exists (default 1)\n"
            "  --json              print one JSON object instead of CSV\n"
            "  -h, --help          this text\n"
            "\n"
            "Exit: 0 path found, 1 bad input or refused problem, 3 no path within the budget.\n",
            prog);
}

static int fail(const char *fmt, const char *a, const char *b)
{
    fprintf(stderr, "%s: error: ", prog);
    fprintf(stderr, fmt, a, b);
    fputc('\n', stderr);
    return EXIT_BAD_INPUT;
}

/* The ranges of the planner's settings live in config.c (gmmrrt_planner_config_validate), not
 * here: a flag that sets a field of cfg is parsed here for its syntax, stored, and the whole
 * configuration validated at once. The configuration was valid before the flag, so a failure is
 * this flag's, and the message names it and the rule that config.c states. */
static int check_config_flag(const gmmrrt_planner_config_t *cfg, const char *flag, const char *value)
{
    char reason[256];
    if (gmmrrt_planner_config_validate(cfg, reason, sizeof reason) == GMMRRT_OK)
        return 0;
    fprintf(stderr, "%s: error: %s '%s': %s\n", prog, flag, value, reason);
    return EXIT_BAD_INPUT;
}

/* Parses exactly n comma-separated finite numbers. */
static int parse_numbers(const char *s, double *out, int n)
{
    const char *p = s;
    for (int i = 0; i < n; ++i) {
        char *end;
        errno = 0;
        out[i] = strtod(p, &end);
        if (end == p || errno == ERANGE || !isfinite(out[i]))
            return 0;
        if (i < n - 1) {
            if (*end != ',')
                return 0;
            p = end + 1;
        } else if (*end != '\0') {
            return 0;
        }
    }
    return 1;
}

static int parse_int64(const char *s, long long *out)
{
    char *end;
    errno = 0;
    const long long v = strtoll(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE)
        return 0;
    *out = v;
    return 1;
}

static void json_number(double v)
{
    if (isfinite(v))
        printf("%.17g", v);
    else
        printf("null");
}

static void grow(gmmrrt_bounds_t *b, double x, double y, double r)
{
    if (x - r < b->xmin)
        b->xmin = x - r;
    if (y - r < b->ymin)
        b->ymin = y - r;
    if (x + r > b->xmax)
        b->xmax = x + r;
    if (y + r > b->ymax)
        b->ymax = y + r;
}

int main(int argc, char **argv)
{
    enum { OPT_MODEL = 256, OPT_START, OPT_GOAL, OPT_PERSON, OPT_OBSTACLE, OPT_PLANNER, OPT_BIAS, OPT_BUDGET,
           OPT_ITER, OPT_SEED, OPT_RADIUS, OPT_BOUNDS, OPT_TASK, OPT_TARGET, OPT_TOL, OPT_JSON, OPT_DELTA,
           OPT_WTASK, OPT_REWIRE_K, OPT_INFORMED };
    static const struct option opts[] = {
        {"model", required_argument, NULL, OPT_MODEL},       {"start", required_argument, NULL, OPT_START},
        {"goal", required_argument, NULL, OPT_GOAL},         {"person", required_argument, NULL, OPT_PERSON},
        {"obstacle", required_argument, NULL, OPT_OBSTACLE}, {"planner", required_argument, NULL, OPT_PLANNER},
        {"bias", required_argument, NULL, OPT_BIAS},         {"budget-ms", required_argument, NULL, OPT_BUDGET},
        {"iterations", required_argument, NULL, OPT_ITER},   {"seed", required_argument, NULL, OPT_SEED},
        {"robot-radius", required_argument, NULL, OPT_RADIUS}, {"bounds", required_argument, NULL, OPT_BOUNDS},
        {"task", required_argument, NULL, OPT_TASK},         {"target-person", required_argument, NULL, OPT_TARGET},
        {"goal-tolerance", required_argument, NULL, OPT_TOL}, {"json", no_argument, NULL, OPT_JSON},
        {"delta", required_argument, NULL, OPT_DELTA},       {"w-task", required_argument, NULL, OPT_WTASK},
        {"rewire-k", required_argument, NULL, OPT_REWIRE_K}, {"informed", required_argument, NULL, OPT_INFORMED},
        {"help", no_argument, NULL, 'h'},                    {NULL, 0, NULL, 0}};

    static gmmrrt_problem_t pr; /* large (obstacle arrays): static, zeroed */
    gmmrrt_planner_config_t cfg;
    gmmrrt_planner_config_default(&cfg);
    int rc;
    const char *model_path = NULL;
    int have_start = 0, have_goal = 0, have_bounds = 0, json = 0, planner = 0, task = 0;
    double budget_ms = -1.0;
    long long iterations = 0, target = 0;
    pr.goal_tolerance_m = 0.1;
    pr.target_person = -1;

    int c;
    opterr = 0;
    while ((c = getopt_long(argc, argv, ":h", opts, NULL)) != -1) {
        double v[5];
        long long n;
        switch (c) {
        case 'h':
            usage(stdout);
            return 0;
        case OPT_MODEL:
            model_path = optarg;
            break;
        case OPT_START:
            if (!parse_numbers(optarg, v, 2))
                return fail("--start '%s': expected x,y (finite numbers, metres)%s", optarg, "");
            pr.start_x = v[0];
            pr.start_y = v[1];
            have_start = 1;
            break;
        case OPT_GOAL:
            if (!parse_numbers(optarg, v, 2))
                return fail("--goal '%s': expected x,y (finite numbers, metres)%s", optarg, "");
            pr.goal_x = v[0];
            pr.goal_y = v[1];
            have_goal = 1;
            break;
        case OPT_PERSON:
            if (!parse_numbers(optarg, v, 3))
                return fail("--person '%s': expected x,y,yaw (finite numbers, metres and radians)%s", optarg, "");
            if (pr.obstacles.num_people >= GMMRRT_MAX_PEOPLE)
                return fail("--person '%s': more people than this build allows%s", optarg, "");
            pr.obstacles.people[pr.obstacles.num_people++] = (gmmrrt_pose_t){v[0], v[1], v[2]};
            break;
        case OPT_OBSTACLE:
            if (strncmp(optarg, "circle:", 7) == 0) {
                if (!parse_numbers(optarg + 7, v, 3) || v[2] <= 0.0)
                    return fail("--obstacle '%s': expected circle:x,y,r with r > 0%s", optarg, "");
                if (pr.obstacles.num_circles >= GMMRRT_MAX_CIRCLES)
                    return fail("--obstacle '%s': more circles than this build allows%s", optarg, "");
                pr.obstacles.circles[pr.obstacles.num_circles++] = (gmmrrt_circle_t){v[0], v[1], v[2]};
            } else if (strncmp(optarg, "box:", 4) == 0) {
                if (!parse_numbers(optarg + 4, v, 5) || v[2] <= 0.0 || v[3] <= 0.0)
                    return fail("--obstacle '%s': expected box:cx,cy,w,h,yaw with w, h > 0%s", optarg, "");
                if (pr.obstacles.num_boxes >= GMMRRT_MAX_BOXES)
                    return fail("--obstacle '%s': more boxes than this build allows%s", optarg, "");
                pr.obstacles.boxes[pr.obstacles.num_boxes++] = (gmmrrt_box_t){v[0], v[1], v[2], v[3], v[4]};
            } else {
                return fail("--obstacle '%s': expected circle:x,y,r or box:cx,cy,w,h,yaw%s", optarg, "");
            }
            break;
        case OPT_PLANNER:
            if (strcmp(optarg, "gmm-rrt-star") == 0)
                planner = GMMRRT_PLANNER_GMM_RRT_STAR;
            else if (strcmp(optarg, "rrt-star") == 0)
                planner = GMMRRT_PLANNER_RRT_STAR;
            else if (strcmp(optarg, "gmm-rrt") == 0)
                planner = GMMRRT_PLANNER_GMM_RRT;
            else
                return fail("--planner '%s': unknown planner (gmm-rrt-star, rrt-star or gmm-rrt)%s", optarg, "");
            break;
        case OPT_BIAS:
            if (!parse_numbers(optarg, v, 1))
                return fail("--bias '%s': expected a number%s", optarg, "");
            cfg.gmm_bias = v[0];
            if ((rc = check_config_flag(&cfg, "--bias", optarg)) != 0)
                return rc;
            break;
        case OPT_BUDGET:
            if (!parse_numbers(optarg, v, 1) || v[0] <= 0.0)
                return fail("--budget-ms '%s': expected a number of milliseconds > 0%s", optarg, "");
            budget_ms = v[0];
            break;
        case OPT_ITER:
            if (!parse_int64(optarg, &n) || n <= 0)
                return fail("--iterations '%s': expected an integer > 0%s", optarg, "");
            iterations = n;
            break;
        case OPT_SEED:
            if (!parse_int64(optarg, &n) || n < 0) /* syntax: config.seed is any uint64 */
                return fail("--seed '%s': expected an integer >= 0%s", optarg, "");
            cfg.seed = (uint64_t)n;
            break;
        case OPT_RADIUS:
            if (!parse_numbers(optarg, v, 1))
                return fail("--robot-radius '%s': expected a number of metres%s", optarg, "");
            cfg.robot_radius_m = v[0];
            if ((rc = check_config_flag(&cfg, "--robot-radius", optarg)) != 0)
                return rc;
            break;
        case OPT_BOUNDS:
            if (!parse_numbers(optarg, v, 4) || v[0] >= v[2] || v[1] >= v[3])
                return fail("--bounds '%s': expected xmin,ymin,xmax,ymax with xmin < xmax, ymin < ymax%s", optarg,
                            "");
            pr.obstacles.bounds = (gmmrrt_bounds_t){v[0], v[1], v[2], v[3]};
            have_bounds = 1;
            break;
        case OPT_TASK:
            if (strcmp(optarg, "avoid") == 0)
                task = GMMRRT_TASK_AVOID;
            else if (strcmp(optarg, "approach") == 0)
                task = GMMRRT_TASK_APPROACH;
            else
                return fail("--task '%s': expected avoid or approach%s", optarg, "");
            break;
        case OPT_TARGET:
            if (!parse_int64(optarg, &n) || n < 0)
                return fail("--target-person '%s': expected an index >= 0%s", optarg, "");
            target = n;
            break;
        case OPT_TOL:
            if (!parse_numbers(optarg, v, 1) || v[0] <= 0.0)
                return fail("--goal-tolerance '%s': expected metres > 0%s", optarg, "");
            pr.goal_tolerance_m = v[0];
            break;
        case OPT_JSON:
            json = 1;
            break;
        case OPT_DELTA:
            if (!parse_numbers(optarg, v, 1))
                return fail("--delta '%s': expected a number%s", optarg, "");
            cfg.delta = v[0];
            if ((rc = check_config_flag(&cfg, "--delta", optarg)) != 0)
                return rc;
            break;
        case OPT_WTASK:
            if (!parse_numbers(optarg, v, 1))
                return fail("--w-task '%s': expected a number%s", optarg, "");
            cfg.w_task = v[0];
            if ((rc = check_config_flag(&cfg, "--w-task", optarg)) != 0)
                return rc;
            break;
        case OPT_REWIRE_K:
            if (!parse_numbers(optarg, v, 1))
                return fail("--rewire-k '%s': expected a number%s", optarg, "");
            cfg.rewire_k_factor = v[0];
            if ((rc = check_config_flag(&cfg, "--rewire-k", optarg)) != 0)
                return rc;
            break;
        case OPT_INFORMED:
            if (!parse_int64(optarg, &n) || n < INT32_MIN || n > INT32_MAX)
                return fail("--informed '%s': expected an integer%s", optarg, "");
            cfg.informed_sampling = (int32_t)n;
            if ((rc = check_config_flag(&cfg, "--informed", optarg)) != 0)
                return rc;
            break;
        case ':':
            return fail("option '%s' needs a value (see --help)%s", argv[optind - 1], "");
        default:
            return fail("unknown option '%s' (see --help)%s", argv[optind - 1], "");
        }
    }
    if (optind < argc)
        return fail("unexpected argument '%s' (see --help)%s", argv[optind], "");
    if (!have_start || !have_goal)
        return fail("--start and --goal are required (see --help)%s%s", "", "");

    static gmmrrt_model_t model;
    char err[512];
    if (model_path) {
        const gmmrrt_status_t ms = gmmrrt_model_load_file(model_path, &model, err, sizeof err);
        if (ms != GMMRRT_OK)
            return fail("cannot use --model: %s%s", err, "");
    }
    if (planner == 0)
        planner = model_path ? GMMRRT_PLANNER_GMM_RRT_STAR : GMMRRT_PLANNER_RRT_STAR;
    if (planner != GMMRRT_PLANNER_RRT_STAR && !model_path)
        return fail("--planner %s needs --model%s", planner == GMMRRT_PLANNER_GMM_RRT ? "gmm-rrt" : "gmm-rrt-star", "");
    cfg.planner = planner;
    if (planner != GMMRRT_PLANNER_RRT_STAR) {
        pr.model = &model;
        if (task == 0)
            task = model.task == GMMRRT_TASK_APPROACH ? GMMRRT_TASK_APPROACH : GMMRRT_TASK_AVOID;
        pr.task = task;
        if (task == GMMRRT_TASK_APPROACH) {
            if (target >= pr.obstacles.num_people)
                return fail("approach needs a --person to approach (--target-person is out of range)%s%s", "", "");
            pr.target_person = (int32_t)target;
        }
    } else {
        pr.task = GMMRRT_TASK_NONE;
    }
    if (!have_bounds) {
        gmmrrt_bounds_t *b = &pr.obstacles.bounds;
        *b = (gmmrrt_bounds_t){pr.start_x, pr.start_y, pr.start_x, pr.start_y};
        grow(b, pr.goal_x, pr.goal_y, 0.0);
        for (int32_t i = 0; i < pr.obstacles.num_people; ++i)
            grow(b, pr.obstacles.people[i].x, pr.obstacles.people[i].y, 0.0);
        for (int32_t i = 0; i < pr.obstacles.num_circles; ++i)
            grow(b, pr.obstacles.circles[i].x, pr.obstacles.circles[i].y, pr.obstacles.circles[i].radius_m);
        for (int32_t i = 0; i < pr.obstacles.num_boxes; ++i) {
            const gmmrrt_box_t *bx = &pr.obstacles.boxes[i];
            grow(b, bx->x, bx->y, 0.5 * hypot(bx->width_m, bx->height_m));
        }
        b->xmin -= 3.0;
        b->ymin -= 3.0;
        b->xmax += 3.0;
        b->ymax += 3.0;
    }
    /* The clearance grid must cover the bounds: size it from them (at most the config's ceiling). */
    const double cells = ceil((pr.obstacles.bounds.xmax - pr.obstacles.bounds.xmin) / cfg.grid_resolution_m) *
                         ceil((pr.obstacles.bounds.ymax - pr.obstacles.bounds.ymin) / cfg.grid_resolution_m);
    if (cells > (double)(1 << 26))
        return fail("--bounds: area too large for a %s m clearance grid%s", "0.05", "");
    cfg.grid_max_cells = (int32_t)cells < 1 ? 1 : (int32_t)cells;

    cfg.history_capacity = GMMRRT_CLI_MAX_HISTORY;
    if (gmmrrt_planner_config_validate(&cfg, err, sizeof err) != GMMRRT_OK)
        return fail("%s%s", err, "");
    const size_t size = gmmrrt_planner_mem_size(&cfg);
    void *mem = malloc(size);
    gmmrrt_planner_t *p;
    if (!mem)
        return fail("out of memory for the planner block%s%s", "", "");
    gmmrrt_status_t st = gmmrrt_planner_init(&p, mem, size, &cfg);
    if (st == GMMRRT_OK)
        st = gmmrrt_planner_set_problem(p, &pr);
    if (st != GMMRRT_OK) {
        free(mem);
        return fail("planning problem refused: %s%s", gmmrrt_status_str(st),
                    st == GMMRRT_ERR_MODEL_MISMATCH ? " (gmm-rrt-star needs a features model, gmm-rrt an xy model)"
                                                    : "");
    }
    gmmrrt_budget_t budget = {0.0, iterations, 0.0, 0};
    budget.time_ms = budget_ms > 0.0 ? budget_ms : (iterations > 0 ? 0.0 : 1000.0);
    gmmrrt_plan_stats_t stats;
    st = gmmrrt_planner_run(p, &budget, &stats);
    static gmmrrt_path_t path;
    const gmmrrt_status_t ps = gmmrrt_planner_best_path(p, &path);
    /* The history lives in the planner block: copy it out before the block is freed. */
    static int64_t hist_iter[GMMRRT_CLI_MAX_HISTORY];
    static double hist_cost[GMMRRT_CLI_MAX_HISTORY];
    const int32_t num_hist = gmmrrt_planner_cost_history(p, hist_iter, hist_cost, GMMRRT_CLI_MAX_HISTORY);
    free(mem);
    const int found = ps == GMMRRT_OK;
    if (json) {
        printf("{\"status\": \"%s\", \"status_code\": %d, \"path\": [", found ? "ok" : gmmrrt_status_str(st),
               found ? 0 : (int)st);
        for (int32_t i = 0; found && i < path.num_points; ++i)
            printf("%s[%.6f, %.6f]", i ? ", " : "", path.x[i], path.y[i]);
        printf("], \"stats\": {\"iterations\": %lld, \"nodes\": %d, \"first_solution_ms\": ",
               (long long)stats.iterations, stats.nodes);
        json_number(stats.first_solution_ms >= 0.0 ? stats.first_solution_ms : NAN);
        printf(", \"best_cost\": ");
        json_number(stats.best_cost);
        printf(", \"length_m\": ");
        json_number(found ? path.length_m : NAN);
        printf(", \"time_ms\": ");
        json_number(stats.time_ms);
        printf(", \"cost_history\": [");
        for (int32_t i = 0; i < num_hist; ++i) {
            printf("%s[%lld, ", i ? ", " : "", (long long)hist_iter[i]);
            json_number(hist_cost[i]);
            printf("]");
        }
        printf("], \"cost_history_complete\": %s}}\n", num_hist < GMMRRT_CLI_MAX_HISTORY ? "true" : "false");
    } else if (found) {
        printf("x,y\n");
        for (int32_t i = 0; i < path.num_points; ++i)
            printf("%.6f,%.6f\n", path.x[i], path.y[i]);
    }
    if (!found) {
        fprintf(stderr, "%s: no path found within the budget (%s; %lld iterations, %d nodes)\n", prog,
                gmmrrt_status_str(st), (long long)stats.iterations, stats.nodes);
        return EXIT_NO_PATH;
    }
    return 0;
}
