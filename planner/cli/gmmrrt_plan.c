/*
 * gmmrrt_plan.c - gmmrrt-plan: plans one path with the gmmrrt core (planner.h) from the
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
#include <time.h>

#include "gmmrrt/config_keys.h"
#include "gmmrrt/drivable.h"
#include "gmmrrt/map_file.h"
#include "gmmrrt/model_file.h"
#include "gmmrrt/model_set.h"
#include "gmmrrt/problem_bounds.h"
#include "gmmrrt/planner.h"

#define EXIT_BAD_INPUT 1
#define EXIT_NO_PATH 3

static const char *prog = "gmmrrt-plan";

/* Cost-history capacity of the CLI's planner (the library default is 1024): 4096 entries x 16 B.
 * When it fills, the planner keeps the latest improvement in the last slot and --json says
 * "cost_history_complete": false. */
#define GMMRRT_CLI_MAX_HISTORY 4096

/* Raster capacity of --map: 4096 x 4096 cells (205 x 205 m at 5 cm), 16384 a side; 9 bytes a
 * cell (raster.h), allocated once, touched only as far as the map reaches. */
#define GMMRRT_CLI_MAP_MAX_CELLS (1 << 24)
#define GMMRRT_CLI_MAP_MAX_SIDE 16384

static double mono_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static void usage(FILE *out)
{
    fprintf(out,
            "usage: %s [--model FILE] --start x,y --goal x,y[,yaw] [--person x,y,yaw[,vx,vy] ...]\n"
            "       [--obstacle circle:x,y,r | box:cx,cy,w,h,yaw ...]\n"
            "       [--budget-ms N] [--iterations N] [--bounds xmin,ymin,xmax,ymax] [--bounds-margin M]\n"
            "       [--task avoid|approach] [--target-person I] [--goal-tolerance M] [--json]\n"
            "       [--goal-yaw-tolerance DEG] [--min-turn-radius M] [--nominal-speed M_S] [--raw-path]\n"
            "       [--face-target[=0|1]] [--approach-models DIR] [--map FILE.yaml]\n"
            "       [--side left|right|either] [--background-model FILE] [PLANNER SETTING ...]\n"
            "\n"
            "Plans a path with GMM-RRT* (the paper's planner), plain RRT* or the GMM-RRT baseline\n"
            "and prints it as x,y CSV (header line first), or with --json one object:\n"
            "  {\"status\": ..., \"path\": [[x, y], ...], \"stats\": {\"iterations\": ..., \"nodes\": ...,\n"
            "   \"first_solution_ms\": ..., \"best_cost\": ..., \"length_m\": ..., \"time_ms\": ...,\n"
            "   \"setup_ms\": ..., \"cost_history\": [[iteration, best cost], ...], \"cost_history_complete\": true,\n"
            "   \"max_nodes\": ..., \"pruned\": ..., \"pool_full\": false}, \"bounds\": [xmin, ymin, xmax, ymax]}\n"
            "setup_ms is the time from the problem to the first iteration (planner init and set-up);\n"
            "first_solution_ms and time_ms count from the first iteration.\n"
            "A full node pool is pruned (nodes that cannot lie on a cheaper path are recycled; pruned\n"
            "counts them) and the search goes on; pool_full is true when the pool filled and nothing\n"
            "could be pruned (no path yet), which ends the run before its budget (a note on stderr\n"
            "says so too); --max-nodes raises the pool.\n"
            "cost_history lists every improvement of the best cost (iteration = samples drawn so far,\n"
            "1-based); the best cost after N iterations is the last entry with iteration <= N.\n"
            "\n",
            prog);
    fprintf(out,
            "  --map FILE.yaml     static map (map_server YAML + PGM/PNG, docs/world.md); unknown cells\n"
            "                      block; read inside the bounds\n"
            "  --model FILE        mixture model (gmmrrt-learn); features kind for gmm-rrt-star,\n"
            "                      xy kind for gmm-rrt; optional for rrt-star\n"
            "  --start x,y         start position [m]\n"
            "  --goal x,y[,yaw]    goal position [m] and the heading to arrive with [rad]; approach\n"
            "                      arrives facing the target person unless a yaw is given\n"
            "  --face-target[=0|1] approach arrives facing the target person (default 1; 0: any heading\n"
            "                      unless --goal gives one)\n"
            "  --person x,y,yaw[,vx,vy]  a person [m, m, rad facing, m/s]; repeat for several;\n"
            "                      below 0.2 m/s standing, above 3 m/s (or NaN) refused\n"
            "  --goal-yaw-tolerance DEG  arrival heading tolerance, > 0 (default 15)\n"
            "  --min-turn-radius M smallest turning radius of the output path [m] (default 0.3;\n"
            "                      0: turning in place allowed)\n"
            "  --nominal-speed M_S robot speed that times the path against walking people (default 0.5)\n"
            "  --raw-path          print the tree's path (no shortcuts, arcs or arrival leg)\n"
            "  --approach-models DIR  approach with the set DIR/1-front.gmm ... DIR/8-45_left.gmm (the 8\n"
            "                      directions of the UPO lab's models): the one of the start's bearing\n"
            "                      in the target's frame plans (\"approach_model\" in --json)\n"
            "  --obstacle SPEC     circle:x,y,r or box:cx,cy,w,h,yaw [m, rad]; repeat\n"
            "  --budget-ms N       wall-clock budget [ms] (default 1000 unless --iterations)\n"
            "  --iterations N      iteration cap (samples drawn); with no --budget-ms, no time limit\n"
            "  --bounds ...        planning area [m] (default: the box around start and goal grown by\n"
            "                      --bounds-margin, the rule gmmrrtd plans with; docs/planner.md)\n"
            "  --bounds-margin M   margin of that box [m] (default 3)\n"
            "  --task NAME         avoid or approach (default: the model's task, else avoid); a model\n"
            "                      learned for the other task is refused, as gmmrrtd does\n"
            "  --target-person I   person index (0-based) for approach (default 0)\n"
            "  --goal-tolerance M  goal region radius [m] (default 0.1)\n"
            "  --side S            left: the path goes counterclockwise round the person (the person\n"
            "                      stays on the robot's left), right: clockwise; either: plan both and\n"
            "                      print the cheaper, with each side's path and cost under \"sides\".\n"
            "                      Default: one plan, whichever side is cheapest. No path on the side\n"
            "                      within the budget: status \"no path on the preferred side\", exit 3\n"
            "  --side-person I     person index (0-based) the side is about (default: the person\n"
            "                      nearest the segment start-goal)\n"
            "  --background-model FILE  background model other than the --model file's (for\n"
            "                      --task-cost background; default: the --model file's own)\n"
            "  --json              print one JSON object instead of CSV\n"
            "  -h, --help          this text\n"
            "\n"
            "Planner settings (the same names as gmmrrtd's [planner] keys and flags, docs/settings.md);\n"
            "--planner defaults to gmm-rrt-star with --model and rrt-star without, --grid-max-cells to\n"
            "what the bounds need:\n");
    gmmrrt_planner_config_t defaults;
    gmmrrt_planner_config_default(&defaults);
    for (int32_t i = 0; i < gmmrrt_config_key_count(); ++i) {
        const gmmrrt_config_key_t *k = gmmrrt_config_key_at(i);
        char left[48], range[128], def[48];
        snprintf(left, sizeof left, "--%s V", k->flag);
        fprintf(out, "  %-19s %s; %s; default %s\n", left, k->help, gmmrrt_config_key_range(k, range, sizeof range),
                gmmrrt_config_key_format(&defaults, k, def, sizeof def));
    }
    fprintf(out,
            "\n"
            "The path printed is drivable (docs/planner.md): shortcut, corners rounded to the turning\n"
            "radius, yaw = tangent (--json adds \"yaw\" and \"drive\"). A start inside a person's disc\n"
            "or an obstacle escapes first (status_code 43, exit 0); a corner tighter than the radius\n"
            "(no free arc there) gives status_code 45, exit 0.\n"
            "Exit: 0 path found, 1 bad input or refused problem (or frozen: no way out), 3 no path\n"
            "within the budget.\n");
}

/* set_problem accepted the problem: as asked (OK) or starting with an escape (ESCAPE). */
static int problem_set(gmmrrt_status_t st) { return st == GMMRRT_OK || st == GMMRRT_ESCAPE; }

static const char *task_name(int32_t task)
{
    return task == GMMRRT_TASK_AVOID ? "avoid" : task == GMMRRT_TASK_APPROACH ? "approach" : "none";
}

static int fail(const char *fmt, const char *a, const char *b)
{
    fprintf(stderr, "%s: error: ", prog);
    fprintf(stderr, fmt, a, b);
    fputc('\n', stderr);
    return EXIT_BAD_INPUT;
}

/* Old spellings of planner settings, refused with the name that replaced them. */
static const char *const k_renamed[][2] = {{"bias", "gmm-bias"}, {"cost", "task-cost"}};
#define N_RENAMED ((int)(sizeof k_renamed / sizeof k_renamed[0]))

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

/* Parses between lo and hi comma-separated numbers (NaN parses, the caller decides); returns the
 * count or 0. */
static int parse_some(const char *s, double *out, int lo, int hi)
{
    for (int n = hi; n >= lo; --n) {
        const char *p = s;
        int ok = 1;
        for (int i = 0; i < n && ok; ++i) {
            char *end;
            errno = 0;
            out[i] = strtod(p, &end);
            ok = end != p && errno != ERANGE && !isinf(out[i]) && (*end == (i < n - 1 ? ',' : '\0'));
            p = end + 1;
        }
        if (ok)
            return n;
    }
    return 0;
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

int main(int argc, char **argv)
{
    enum { OPT_MODEL = 256, OPT_START, OPT_GOAL, OPT_PERSON, OPT_OBSTACLE, OPT_BUDGET, OPT_ITER, OPT_BOUNDS,
           OPT_TASK, OPT_TARGET, OPT_TOL, OPT_JSON, OPT_YAW_TOL, OPT_TURN_RADIUS, OPT_SPEED, OPT_RAW, OPT_SET,
           OPT_MAP, OPT_SIDE, OPT_SIDE_PERSON, OPT_BG, OPT_FACE, OPT_MARGIN, OPT_RENAMED = 1000,
           OPT_SETTING = 2000 };
    static const struct option own_opts[] = {
        {"model", required_argument, NULL, OPT_MODEL},       {"start", required_argument, NULL, OPT_START},
        {"goal", required_argument, NULL, OPT_GOAL},         {"person", required_argument, NULL, OPT_PERSON},
        {"obstacle", required_argument, NULL, OPT_OBSTACLE}, {"budget-ms", required_argument, NULL, OPT_BUDGET},
        {"iterations", required_argument, NULL, OPT_ITER},   {"bounds", required_argument, NULL, OPT_BOUNDS},
        {"task", required_argument, NULL, OPT_TASK},         {"target-person", required_argument, NULL, OPT_TARGET},
        {"goal-tolerance", required_argument, NULL, OPT_TOL}, {"json", no_argument, NULL, OPT_JSON},
        {"goal-yaw-tolerance", required_argument, NULL, OPT_YAW_TOL},
        {"min-turn-radius", required_argument, NULL, OPT_TURN_RADIUS},
        {"nominal-speed", required_argument, NULL, OPT_SPEED},  {"raw-path", no_argument, NULL, OPT_RAW},
        {"approach-models", required_argument, NULL, OPT_SET},
        {"map", required_argument, NULL, OPT_MAP},
        {"side", required_argument, NULL, OPT_SIDE},         {"side-person", required_argument, NULL, OPT_SIDE_PERSON},
        {"background-model", required_argument, NULL, OPT_BG}, {"face-target", optional_argument, NULL, OPT_FACE},
        {"bounds-margin", required_argument, NULL, OPT_MARGIN},
        {"help", no_argument, NULL, 'h'}};
    /* This program's own options, then every planner setting of the core's table, then the old
     * spellings (refused with their new name). */
    enum { N_OWN = (int)(sizeof own_opts / sizeof own_opts[0]) };
    struct option opts[N_OWN + GMMRRT_CONFIG_MAX_KEYS + N_RENAMED + 1];
    int n_opts = 0;
    for (int i = 0; i < N_OWN; ++i)
        opts[n_opts++] = own_opts[i];
    for (int32_t i = 0; i < gmmrrt_config_key_count(); ++i)
        opts[n_opts++] = (struct option){gmmrrt_config_key_at(i)->flag, required_argument, NULL, OPT_SETTING + i};
    for (int i = 0; i < N_RENAMED; ++i)
        opts[n_opts++] = (struct option){k_renamed[i][0], required_argument, NULL, OPT_RENAMED + i};
    opts[n_opts] = (struct option){NULL, 0, NULL, 0};

    static gmmrrt_problem_t pr; /* large (obstacle arrays): static, zeroed */
    gmmrrt_planner_config_t cfg;
    gmmrrt_planner_config_default(&cfg);
    const char *model_path = NULL, *set_dir = NULL, *map_path = NULL, *bg_path = NULL;
    int have_start = 0, have_goal = 0, have_bounds = 0, json = 0, planner = 0, task = 0, raw = 0, have_yaw = 0;
    int face_target = 1, have_grid_cells = 0;
    double bounds_margin_m = GMMRRT_DEFAULT_BOUNDS_MARGIN_M;
    gmmrrt_drive_options_t drive;
    gmmrrt_drive_options_default(&drive);
    double budget_ms = -1.0;
    long long iterations = 0, target = 0, side_person = -1;
    int side = -1; /* -1: no --side (one plan); GMMRRT_SIDE_EITHER: both sides */
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
            have_yaw = parse_some(optarg, v, 2, 3) == 3;
            if (!parse_some(optarg, v, 2, 3) || isnan(v[0]) || isnan(v[1]) || (have_yaw && isnan(v[2])))
                return fail("--goal '%s': expected x,y or x,y,yaw (finite numbers, metres and radians)%s", optarg, "");
            pr.goal_x = v[0];
            pr.goal_y = v[1];
            drive.goal_yaw = have_yaw ? v[2] : 0.0;
            have_goal = 1;
            break;
        case OPT_PERSON: {
            const int np = parse_some(optarg, v, 3, 5);
            if (np != 3 && np != 5)
                return fail("--person '%s': expected x,y,yaw or x,y,yaw,vx,vy (metres, radians, m/s)%s", optarg, "");
            if (isnan(v[0]) || isnan(v[1]) || isnan(v[2]))
                return fail("--person '%s': position and yaw must be finite numbers%s", optarg, "");
            if (np == 5 && !(hypot(v[3], v[4]) <= GMMRRT_MAX_PERSON_SPEED_M_S))
                return fail("--person '%s': velocity must be finite and at most 3 m/s (a running person)%s", optarg,
                            "");
            if (pr.obstacles.num_people >= GMMRRT_MAX_PEOPLE)
                return fail("--person '%s': more people than this build allows%s", optarg, "");
            pr.person_vx[pr.obstacles.num_people] = np == 5 ? v[3] : 0.0;
            pr.person_vy[pr.obstacles.num_people] = np == 5 ? v[4] : 0.0;
            pr.obstacles.people[pr.obstacles.num_people++] = (gmmrrt_pose_t){v[0], v[1], v[2]};
            break;
        }
        case OPT_YAW_TOL:
            if (!parse_numbers(optarg, v, 1) || !(v[0] > 0.0 && v[0] <= 180.0))
                return fail("--goal-yaw-tolerance '%s': expected degrees in (0, 180]%s", optarg, "");
            drive.goal_yaw_tolerance_rad = v[0] * M_PI / 180.0;
            break;
        case OPT_TURN_RADIUS:
            if (!parse_numbers(optarg, v, 1) || !(v[0] >= 0.0 && v[0] <= 100.0))
                return fail("--min-turn-radius '%s': expected metres in [0, 100] (0: turn in place)%s", optarg, "");
            drive.min_turn_radius_m = v[0];
            break;
        case OPT_SPEED:
            if (!parse_numbers(optarg, v, 1) || !(v[0] > 0.0 && v[0] <= 10.0))
                return fail("--nominal-speed '%s': expected m/s in (0, 10]%s", optarg, "");
            pr.nominal_speed_m_s = v[0];
            break;
        case OPT_RAW:
            raw = 1;
            break;
        case OPT_SET:
            set_dir = optarg;
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
        case OPT_MAP:
            map_path = optarg;
            break;
        case OPT_SIDE:
            if (strcmp(optarg, "left") == 0)
                side = GMMRRT_SIDE_LEFT;
            else if (strcmp(optarg, "right") == 0)
                side = GMMRRT_SIDE_RIGHT;
            else if (strcmp(optarg, "either") == 0)
                side = GMMRRT_SIDE_EITHER;
            else
                return fail("--side '%s': expected left, right or either%s", optarg, "");
            break;
        case OPT_SIDE_PERSON:
            if (!parse_int64(optarg, &n) || n < 0)
                return fail("--side-person '%s': expected an index >= 0%s", optarg, "");
            side_person = n;
            break;
        case OPT_BG:
            bg_path = optarg;
            break;
        case OPT_MARGIN: {
            gmmrrt_bounds_t scratch; /* the core's range of the margin: a box round (0, 0) */
            if (!parse_numbers(optarg, v, 1) || gmmrrt_problem_bounds(0.0, 0.0, 0.0, 0.0, v[0], &scratch) != GMMRRT_OK) {
                char range[64];
                snprintf(range, sizeof range, "%g..%g", GMMRRT_MIN_BOUNDS_MARGIN_M, GMMRRT_MAX_BOUNDS_MARGIN_M);
                return fail("--bounds-margin '%s': expected metres in %s", optarg, range);
            }
            bounds_margin_m = v[0];
            break;
        }
        case OPT_FACE:
            if (optarg == NULL || strcmp(optarg, "1") == 0)
                face_target = 1;
            else if (strcmp(optarg, "0") == 0)
                face_target = 0;
            else
                return fail("--face-target='%s': expected 0 or 1%s", optarg, "");
            break;
        case ':':
            return fail("option '%s' needs a value (see --help)%s", argv[optind - 1], "");
        default:
            if (c >= OPT_SETTING && c < OPT_SETTING + GMMRRT_CONFIG_MAX_KEYS) {
                /* A planner setting: its syntax and range are the core table's (config_keys.h). */
                const gmmrrt_config_key_t *k = gmmrrt_config_key_at(c - OPT_SETTING);
                char why[256];
                if (gmmrrt_config_key_set(&cfg, k, optarg, why, sizeof why) != GMMRRT_OK) {
                    fprintf(stderr, "%s: error: --%s '%s': %s\n", prog, k->flag, optarg, why);
                    return EXIT_BAD_INPUT;
                }
                if (strcmp(k->name, "planner") == 0)
                    planner = cfg.planner;
                if (strcmp(k->name, "grid_max_cells") == 0)
                    have_grid_cells = 1;
                break;
            }
            if (c >= OPT_RENAMED && c < OPT_RENAMED + N_RENAMED)
                return fail("--%s was renamed --%s (see --help)", k_renamed[c - OPT_RENAMED][0],
                            k_renamed[c - OPT_RENAMED][1]);
            return fail("unknown option '%s' (see --help)%s", argv[optind - 1], "");
        }
    }
    if (optind < argc)
        return fail("unexpected argument '%s' (see --help)%s", argv[optind], "");
    if (!have_start || !have_goal)
        return fail("--start and --goal are required (see --help)%s%s", "", "");

    static gmmrrt_model_t model;
    static gmmrrt_model_t background; /* the model file's own background, or --background-model */
    int model_has_background = 0;
    char err[512];
    if (model_path) {
        const gmmrrt_status_t ms = gmmrrt_model_load_file_background(model_path, &model, &background,
                                                                     &model_has_background, NULL, 0, NULL, err,
                                                                     sizeof err);
        if (ms != GMMRRT_OK)
            return fail("cannot use --model: %s%s", err, "");
    }
    static gmmrrt_raster_t map;
    static void *map_mem; /* static: reachable until exit on every path */
    if (map_path) {
        const size_t map_size = gmmrrt_raster_mem_size(GMMRRT_CLI_MAP_MAX_CELLS, GMMRRT_CLI_MAP_MAX_SIDE);
        map_mem = malloc(map_size);
        if (!map_mem || gmmrrt_raster_init(&map, map_mem, map_size, GMMRRT_CLI_MAP_MAX_CELLS,
                                           GMMRRT_CLI_MAP_MAX_SIDE) != GMMRRT_OK)
            return fail("out of memory for the map%s%s", "", "");
        const gmmrrt_status_t ms = gmmrrt_map_load_file(map_path, 1, &map, err, sizeof err);
        if (ms != GMMRRT_OK)
            return fail("cannot use --map: %s%s", err, "");
        pr.obstacles.raster = &map;
    }
    /* An approach model set: every direction must load; the start's direction plans. */
    static gmmrrt_model_t set_models[GMMRRT_APPROACH_DIRECTIONS];
    int32_t set_direction = -1;
    if (set_dir) {
        if (model_path)
            return fail("--approach-models and --model exclude each other%s%s", "", "");
        if (target >= pr.obstacles.num_people)
            return fail("--approach-models needs a --person to approach (--target-person is out of range)%s%s", "",
                        "");
        gmmrrt_model_set_t set;
        for (int32_t k = 0; k < GMMRRT_APPROACH_DIRECTIONS; ++k) {
            static char file[4096];
            snprintf(file, sizeof file, "%s/%s.gmm", set_dir, gmmrrt_approach_direction_name(k));
            if (gmmrrt_model_load_file(file, &set_models[k], err, sizeof err) != GMMRRT_OK)
                return fail("cannot use --approach-models: %s%s", err, "");
            set.model[k] = &set_models[k];
        }
        if (gmmrrt_model_set_validate(&set, err, sizeof err) != GMMRRT_OK)
            return fail("cannot use --approach-models %s: %s", set_dir, err);
        model = *gmmrrt_model_set_select(&set, &pr.obstacles.people[target], pr.start_x, pr.start_y, &set_direction);
        model_path = set_dir;
        task = GMMRRT_TASK_APPROACH;
    }
    if (bg_path) { /* overrides the model file's own background */
        const gmmrrt_status_t ms = gmmrrt_model_load_file(bg_path, &background, err, sizeof err);
        if (ms != GMMRRT_OK)
            return fail("cannot use --background-model: %s%s", err, "");
        pr.background_model = &background;
    } else if (model_has_background && !set_dir) {
        pr.background_model = &background;
    }
    if (planner == 0)
        planner = model_path ? GMMRRT_PLANNER_GMM_RRT_STAR : GMMRRT_PLANNER_RRT_STAR;
    if (planner != GMMRRT_PLANNER_RRT_STAR && !model_path)
        return fail("--planner %s needs --model%s", planner == GMMRRT_PLANNER_GMM_RRT ? "gmm-rrt" : "gmm-rrt-star", "");
    cfg.planner = planner;
    /* Only a planner that carries the task cost reads the background (the core's rule). */
    if (gmmrrt_planner_needs_background(&cfg) && !pr.background_model)
        return fail("--task-cost background needs a background model: the --model file has none (fit it with "
                    "gmmrrt-learn fit --background straight) and no --background-model FILE was given%s%s", "", "");
    if (planner != GMMRRT_PLANNER_RRT_STAR) {
        pr.model = &model;
        if (task == 0)
            task = model.task == GMMRRT_TASK_APPROACH ? GMMRRT_TASK_APPROACH : GMMRRT_TASK_AVOID;
        /* The core's rule, as gmmrrtd applies it: a model learned for one task never plans the
         * other; a model without a task (generic, xy) serves either. */
        if (gmmrrt_model_task_fits(&model, task) != GMMRRT_OK) {
            fprintf(stderr, "%s: error: --task %s, but --model %s was learned for task %s; give a model of task %s or "
                    "--task %s\n", prog, task_name(task), model_path, task_name(model.task), task_name(task),
                    task_name(model.task));
            return EXIT_BAD_INPUT;
        }
        pr.task = task;
        if (task == GMMRRT_TASK_APPROACH) {
            if (target >= pr.obstacles.num_people)
                return fail("approach needs a --person to approach (--target-person is out of range)%s%s", "", "");
            pr.target_person = (int32_t)target;
        }
    } else {
        pr.task = GMMRRT_TASK_NONE;
    }
    if (side_person >= pr.obstacles.num_people)
        return fail("--side-person is out of range (fewer --person given)%s%s", "", "");
    pr.side_person = (int32_t)side_person;
    pr.side = side > 0 ? side : GMMRRT_SIDE_EITHER;
    /* Without --bounds, the core's rule (problem_bounds.h), as gmmrrtd plans: the box around
     * start and goal grown by --bounds-margin. */
    if (!have_bounds)
        (void)gmmrrt_problem_bounds(pr.start_x, pr.start_y, pr.goal_x, pr.goal_y, bounds_margin_m,
                                    &pr.obstacles.bounds); /* inputs checked finite, margin > 0 */
    /* The clearance grid must cover the bounds: size it from them (at most the config's ceiling). */
    const double cells = ceil((pr.obstacles.bounds.xmax - pr.obstacles.bounds.xmin) / cfg.grid_resolution_m) *
                         ceil((pr.obstacles.bounds.ymax - pr.obstacles.bounds.ymin) / cfg.grid_resolution_m);
    if (cells > (double)(1 << 26))
        return fail("--bounds: area too large for a %s m clearance grid%s", "0.05", "");
    if (!have_grid_cells)
        cfg.grid_max_cells = (int32_t)cells < 1 ? 1 : (int32_t)cells;

    cfg.history_capacity = GMMRRT_CLI_MAX_HISTORY;
    if (gmmrrt_planner_config_validate(&cfg, err, sizeof err) != GMMRRT_OK)
        return fail("%s%s", err, "");
    const size_t size = gmmrrt_planner_mem_size(&cfg);
    void *mem = malloc(size);
    gmmrrt_planner_t *p;
    if (!mem)
        return fail("out of memory for the planner block%s%s", "", "");
    /* setup_ms: from the problem to the first iteration (init and set_problem; the memory
     * block's allocation and the map's loading are before). */
    const double setup_t0 = mono_ms();
    gmmrrt_status_t st = gmmrrt_planner_init(&p, mem, size, &cfg);
    if (st == GMMRRT_OK)
        st = gmmrrt_planner_set_problem(p, &pr);
    const double setup_ms = mono_ms() - setup_t0;
    if (st == GMMRRT_ERR_FROZEN) {
        static char why[256];
        snprintf(why, sizeof why, "%s", gmmrrt_planner_escape_reason(p));
        free(mem);
        return fail("planning problem refused: frozen: %s%s", why, "");
    }
    if (st != GMMRRT_OK && st != GMMRRT_ESCAPE) {
        free(mem);
        return fail("planning problem refused: %s%s", gmmrrt_status_str(st),
                    st == GMMRRT_ERR_MODEL_MISMATCH ? " (gmm-rrt-star needs a features model, gmm-rrt an xy model)"
                                                    : "");
    }
    drive.arrival = have_yaw ? GMMRRT_ARRIVAL_YAW
                             : (pr.task == GMMRRT_TASK_APPROACH && face_target ? GMMRRT_ARRIVAL_FACE_TARGET
                                                                               : GMMRRT_ARRIVAL_ANY);
    gmmrrt_budget_t budget = {0.0, iterations, 0.0, 0};
    budget.time_ms = budget_ms > 0.0 ? budget_ms : (iterations > 0 ? 0.0 : 1000.0);
    /* --side either: one plan per side (same seed and budget each); the cheaper is the answer. */
    static gmmrrt_path_t side_path[2];
    gmmrrt_status_t side_st[2] = {GMMRRT_NO_PATH_YET, GMMRRT_NO_PATH_YET};
    if (side == GMMRRT_SIDE_EITHER) {
        for (int k = 0; k < 2 && problem_set(st); ++k) {
            pr.side = k == 0 ? GMMRRT_SIDE_LEFT : GMMRRT_SIDE_RIGHT;
            st = gmmrrt_planner_set_problem(p, &pr);
            side_st[k] = problem_set(st) ? gmmrrt_planner_run(p, &budget, NULL) : st;
            if (gmmrrt_planner_best_path(p, &side_path[k]) != GMMRRT_OK)
                side_path[k].num_points = 0;
        }
        const int pick = side_path[1].num_points > 0 &&
                         (side_path[0].num_points == 0 || side_path[1].cost < side_path[0].cost);
        pr.side = pick ? GMMRRT_SIDE_RIGHT : GMMRRT_SIDE_LEFT;
        st = gmmrrt_planner_set_problem(p, &pr); /* the chosen side again, for its statistics and history */
    }
    gmmrrt_plan_stats_t stats;
    memset(&stats, 0, sizeof stats);
    stats.first_solution_ms = -1.0;
    stats.best_cost = INFINITY;
    st = problem_set(st) ? gmmrrt_planner_run(p, &budget, &stats) : st;
    static gmmrrt_path_t path;
    gmmrrt_drive_report_t rep = {0};
    rep.status = GMMRRT_OK;
    gmmrrt_status_t ps =
        raw ? gmmrrt_planner_best_path(p, &path) : gmmrrt_planner_drivable_path(p, &drive, &path, &rep);
    if (ps == GMMRRT_ESCAPE || ps == GMMRRT_TIGHT_TURNS)
        ps = GMMRRT_OK; /* a path; the escape or the tight corner shows in the status */
    else if (raw && ps == GMMRRT_OK && gmmrrt_planner_escape_reason(p)[0]) /* the tree path starts at the exit */
        rep.status = GMMRRT_ESCAPE;
    /* The history lives in the planner block: copy it out before the block is freed. */
    static int64_t hist_iter[GMMRRT_CLI_MAX_HISTORY];
    static double hist_cost[GMMRRT_CLI_MAX_HISTORY];
    const int32_t num_hist = gmmrrt_planner_cost_history(p, hist_iter, hist_cost, GMMRRT_CLI_MAX_HISTORY);
    static char escape_reason[256];
    snprintf(escape_reason, sizeof escape_reason, "%s", gmmrrt_planner_escape_reason(p));
    free(mem);
    const int found = ps == GMMRRT_OK;
    /* The pool filling ends the run before its budget: say so, with the way out. */
    const int pool_full = st == GMMRRT_POOL_FULL;
    if (pool_full)
        fprintf(stderr,
                "%s: note: the node pool (%d nodes) filled after %lld iterations and %.1f ms, before the budget "
                "ran out; --max-nodes raises it\n",
                prog, (int)cfg.max_nodes, (long long)stats.iterations, stats.time_ms);
    if (json) {
        printf("{\"status\": \"%s\", \"status_code\": %d, \"path\": [",
               found ? gmmrrt_status_str(rep.status) : gmmrrt_status_str(st), found ? (int)rep.status : (int)st);
        for (int32_t i = 0; found && i < path.num_points; ++i)
            printf("%s[%.6f, %.6f]", i ? ", " : "", path.x[i], path.y[i]);
        printf("], \"yaw\": [");
        for (int32_t i = 0; found && i < path.num_points; ++i)
            printf("%s%.6f", i ? ", " : "", path.yaw[i]);
        printf("], \"drive\": {\"raw\": %s, \"arrival_error_deg\": ", raw ? "true" : "false");
        json_number(found && !raw ? rep.arrival_error_rad * 180.0 / M_PI : NAN);
        printf(", \"arrival_met\": %s, \"max_curvature\": ", rep.arrival_met || raw ? "true" : "false");
        json_number(found && !raw ? rep.max_curvature : NAN);
        printf(", \"tight_turns\": %d, \"turns_in_place\": %d, \"min_walker_clearance_m\": ", rep.tight_turns,
               rep.turns_in_place);
        json_number(rep.min_walker_clearance_m);
        printf(", \"walker_conflict\": %s, \"side_kept\": %s, \"escape\": \"%s\"}, \"approach_model\": ",
               rep.walker_conflict ? "true" : "false", found && !raw ? (rep.side_kept ? "true" : "false") : "null",
               escape_reason);
        if (set_direction >= 0)
            printf("\"%s\", \"stats\": {", gmmrrt_approach_direction_name(set_direction));
        else
            printf("null, \"stats\": {");
        printf("\"iterations\": %lld, \"nodes\": %d, \"first_solution_ms\": ", (long long)stats.iterations,
               stats.nodes);
        json_number(stats.first_solution_ms >= 0.0 ? stats.first_solution_ms : NAN);
        printf(", \"best_cost\": ");
        json_number(stats.best_cost);
        printf(", \"length_m\": ");
        json_number(found ? path.length_m : NAN);
        printf(", \"time_ms\": ");
        json_number(stats.time_ms);
        printf(", \"setup_ms\": ");
        json_number(setup_ms);
        printf(", \"cost_history\": [");
        for (int32_t i = 0; i < num_hist; ++i) {
            printf("%s[%lld, ", i ? ", " : "", (long long)hist_iter[i]);
            json_number(hist_cost[i]);
            printf("]");
        }
        printf("], \"cost_history_complete\": %s, \"max_nodes\": %d, \"pruned\": %lld, \"pool_full\": %s}",
               num_hist < GMMRRT_CLI_MAX_HISTORY ? "true" : "false", (int)cfg.max_nodes, (long long)stats.pruned,
               pool_full ? "true" : "false");
        printf(", \"bounds\": [%.17g, %.17g, %.17g, %.17g]", pr.obstacles.bounds.xmin, pr.obstacles.bounds.ymin,
               pr.obstacles.bounds.xmax, pr.obstacles.bounds.ymax);
        if (pr.side != GMMRRT_SIDE_EITHER)
            printf(", \"side\": \"%s\"", pr.side == GMMRRT_SIDE_LEFT ? "left" : "right");
        if (side == GMMRRT_SIDE_EITHER) {
            printf(", \"sides\": {");
            for (int k = 0; k < 2; ++k) {
                const int ok = side_path[k].num_points > 0;
                printf("%s\"%s\": {\"status\": \"%s\", \"cost\": ", k ? ", " : "", k ? "right" : "left",
                       ok ? "ok" : gmmrrt_status_str(side_st[k]));
                json_number(ok ? side_path[k].cost : NAN);
                printf(", \"length_m\": ");
                json_number(ok ? side_path[k].length_m : NAN);
                printf(", \"path\": [");
                for (int32_t i = 0; i < side_path[k].num_points; ++i)
                    printf("%s[%.6f, %.6f]", i ? ", " : "", side_path[k].x[i], side_path[k].y[i]);
                printf("]}");
            }
            printf("}");
        }
        printf("}\n");
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
