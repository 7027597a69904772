/*
 * bench_social_main.cpp - gmmrrt-bench-social: GMM-RRT* (paper Sect. 4: mixture sampling bias and
 * task cost) with the default configuration (gmm_bias 0.95) on one social task, timed with the
 * best cost over time (sliced_run.hpp); one JSON object per trial. tools/bench.py derives the
 * time to first solution (paper Sect. 5: 1.5 s; target <= 1 ms) and to within 1 % of the
 * converged cost.
 *
 * Scenes (person at the origin, people are discs of the default person radius):
 *   avoid:    person faces the robot (yaw pi); start (-4, 0), goal (4, 0) behind the person.
 *   approach: person faces +x (yaw 0), the robot starts behind them at (-4, 0.5) and must reach
 *             (1.2, 0), 1.2 m in front of them (target_person 0).
 * Bounds [-6, 6] x [-5, 5], goal tolerance 0.1 m.
 */
#include <getopt.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "gmmrrt/model_file.h"
#include "gmmrrt/planner.h"
#include "sliced_run.hpp"
#include "trial.hpp"

using namespace gmmrrt_bench;

static void usage(FILE *f)
{
    std::fprintf(f,
                 "usage: gmmrrt-bench-social --task avoid|approach --model FILE [options]\n"
                 "GMM-RRT* (default configuration, mixture bias 0.95) on one social task; one JSON\n"
                 "object per trial with the best cost over time.\n\n"
                 "  -T, --task avoid|approach  the scene and task\n"
                 "  -m, --model FILE           FEATURES (d, theta) model for the task\n"
                 "  -n, --trials N             trials (default 20)\n"
                 "  -t, --time-ms MS           planning time per trial (default 1000)\n"
                 "  -s, --seed S               base seed (default 1); trial i uses S + i\n"
                 "  -b, --gmm-bias B           mixture sampling bias (default: the configuration's, 0.95)\n"
                 "  -h, --help                 this help\n");
}

static bool parse_number(const char *s, double *out)
{
    char *end = nullptr;
    errno = 0;
    const double v = std::strtod(s, &end);
    if (errno || end == s || *end != '\0' || !std::isfinite(v))
        return false;
    *out = v;
    return true;
}

int main(int argc, char **argv)
{
    std::string task, model_path;
    double trials = 20, time_ms = 1000, seed = 1, gmm_bias = -1;
    static const struct option opts[] = {
        {"task", required_argument, nullptr, 'T'},    {"model", required_argument, nullptr, 'm'},
        {"trials", required_argument, nullptr, 'n'},  {"time-ms", required_argument, nullptr, 't'},
        {"seed", required_argument, nullptr, 's'},    {"gmm-bias", required_argument, nullptr, 'b'},
        {"help", no_argument, nullptr, 'h'},          {nullptr, 0, nullptr, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "T:m:n:t:s:b:h", opts, nullptr)) != -1) {
        bool ok = true;
        switch (c) {
        case 'T': task = optarg; break;
        case 'm': model_path = optarg; break;
        case 'n': ok = parse_number(optarg, &trials) && trials >= 1 && trials <= 100000 && trials == std::floor(trials); break;
        case 't': ok = parse_number(optarg, &time_ms) && time_ms > 0 && time_ms <= 3.6e6; break;
        case 's': ok = parse_number(optarg, &seed) && seed >= 0 && seed == std::floor(seed) && seed < 9e15; break;
        case 'b': ok = parse_number(optarg, &gmm_bias) && gmm_bias >= 0 && gmm_bias <= 1; break;
        case 'h': usage(stdout); return 0;
        default: usage(stderr); return 2;
        }
        if (!ok) {
            std::fprintf(stderr, "gmmrrt-bench-social: bad value '%s' for --%s (see --help)\n", optarg,
                         c == 'n' ? "trials" : c == 't' ? "time-ms" : c == 's' ? "seed" : "gmm-bias");
            return 2;
        }
    }
    if (optind < argc) {
        std::fprintf(stderr, "gmmrrt-bench-social: unexpected argument '%s'\n", argv[optind]);
        return 2;
    }
    if (task != "avoid" && task != "approach") {
        std::fprintf(stderr, "gmmrrt-bench-social: --task must be 'avoid' or 'approach'\n");
        return 2;
    }
    if (model_path.empty()) {
        std::fprintf(stderr, "gmmrrt-bench-social: --model FILE is required\n");
        return 2;
    }
    gmmrrt_model_t model;
    char err[256] = "";
    gmmrrt_status_t st = gmmrrt_model_load_file(model_path.c_str(), &model, err, sizeof err);
    if (st != GMMRRT_OK) {
        std::fprintf(stderr, "gmmrrt-bench-social: %s\n", err);
        return 1;
    }
    if (model.kind != GMMRRT_MODEL_KIND_FEATURES) {
        std::fprintf(stderr, "gmmrrt-bench-social: %s is not a (d, theta) FEATURES model\n", model_path.c_str());
        return 1;
    }

    gmmrrt_problem_t pb{};
    pb.obstacles.bounds = {-6.0, -5.0, 6.0, 5.0};
    pb.obstacles.num_people = 1;
    pb.goal_tolerance_m = 0.1;
    pb.model = &model;
    if (task == "avoid") {
        pb.task = GMMRRT_TASK_AVOID;
        pb.target_person = -1;
        pb.obstacles.people[0] = {0.0, 0.0, M_PI};
        pb.start_x = -4.0, pb.start_y = 0.0, pb.goal_x = 4.0, pb.goal_y = 0.0;
    } else {
        pb.task = GMMRRT_TASK_APPROACH;
        pb.target_person = 0;
        pb.obstacles.people[0] = {0.0, 0.0, 0.0};
        pb.start_x = -4.0, pb.start_y = 0.5, pb.goal_x = 1.2, pb.goal_y = 0.0;
    }

    std::vector<unsigned char> block;
    for (long i = 0; i < static_cast<long>(trials); ++i) {
        gmmrrt_planner_config_t cfg;
        gmmrrt_planner_config_default(&cfg);
        cfg.seed = static_cast<uint64_t>(seed) + static_cast<uint64_t>(i);
        if (gmm_bias >= 0)
            cfg.gmm_bias = gmm_bias;
        const size_t need = gmmrrt_planner_mem_size(&cfg);
        if (block.size() < need + 8)
            block.assign(need + 8, 0);
        void *mem = block.data();
        size_t size = block.size();
        void *aligned = std::align(8, need, mem, size);
        gmmrrt_planner_t *p = nullptr;
        st = gmmrrt_planner_init(&p, aligned, size, &cfg);
        if (st == GMMRRT_OK)
            st = gmmrrt_planner_set_problem(p, &pb);
        if (st != GMMRRT_OK) {
            std::fprintf(stderr, "gmmrrt-bench-social: %s task: %s\n", task.c_str(), gmmrrt_status_str(st));
            return 1;
        }
        TrialResult r;
        r.planner = "gmmrrt_gmm_rrtstar";
        r.objective = task;
        r.trial = static_cast<int>(i);
        r.seed = cfg.seed;
        run_sliced(p, time_ms, cfg.history_capacity, &r);
        write_trial_json(std::cout, r);
        std::cout << '\n' << std::flush;
    }
    return std::cout ? 0 : 1;
}
