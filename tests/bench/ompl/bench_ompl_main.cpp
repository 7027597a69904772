/*
 * bench_ompl_main.cpp - gmmrrt-bench-ompl: our RRT* against OMPL's RRTstar on the benchmark
 * problem (problem.hpp), runs interleaved (OMPL first on even trials, ours first on odd ones),
 * one JSON object per trial on stdout or --out. tools/bench.py takes medians and ratios.
 * Optionally also writes an ompl::tools::Benchmark log of both planners (--ompl-log).
 */
#include <algorithm>
#include <getopt.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "gmmrrt_runner.hpp"
#include "ompl_log.hpp"
#include "ompl_runner.hpp"
#include "problem.hpp"
#include "trial.hpp"

using namespace gmmrrt_bench;

static void usage(FILE *f)
{
    std::fprintf(f,
                 "usage: gmmrrt-bench-ompl [options]\n"
                 "Our RRT* against OMPL's RRTstar on [-10,10]^2 with a disc of radius 2 at the origin,\n"
                 "start (-5,0), goal (5,0), point robot. Runs are interleaved; one JSON object per trial.\n\n"
                 "  -o, --objective length|task  cost to minimise (default length); task needs --model\n"
                 "  -m, --model FILE             FEATURES (d, theta) avoid model for the task cost\n"
                 "  -n, --trials N               trials per planner (default 10)\n"
                 "  -t, --time-ms MS             planning time per trial, ms (default 1000)\n"
                 "  -s, --seed S                 base seed (default 1); trial i uses S + i\n"
                 "  -N, --max-nodes N            our node pool (default 2000000)\n"
                 "  -p, --planners LIST          comma-separated, of ompl (RRTstar, defaults), gmmrrt\n"
                 "                               (ours, defaults), gmmrrt-plain (ours without informed\n"
                 "                               sampling), ompl-informed (RRTstar with informed sampling,\n"
                 "                               length only); default ompl,gmmrrt. Each trial runs them\n"
                 "                               in turn, the order rotated from trial to trial\n"
                 "      --out FILE               JSON lines to FILE instead of stdout\n"
                 "      --ompl-log FILE          also run ompl::tools::Benchmark on both planners\n"
                 "                               (not interleaved) and save its log to FILE\n"
                 "  -h, --help                   this help\n");
}

static bool parse_double(const char *s, double *out)
{
    char *end = nullptr;
    errno = 0;
    const double v = std::strtod(s, &end);
    if (errno || end == s || *end != '\0')
        return false;
    *out = v;
    return true;
}

static bool parse_long(const char *s, long long *out)
{
    char *end = nullptr;
    errno = 0;
    const long long v = std::strtoll(s, &end, 10);
    if (errno || end == s || *end != '\0')
        return false;
    *out = v;
    return true;
}

int main(int argc, char **argv)
{
    std::string objective = "length", model_path, out_path, ompl_log_path, planners = "ompl,gmmrrt";
    long long trials = 10, seed = 1, max_nodes = 2000000;
    double time_ms = 1000.0;
    enum { OPT_OUT = 1000, OPT_OMPL_LOG };
    static const struct option opts[] = {
        {"objective", required_argument, nullptr, 'o'}, {"model", required_argument, nullptr, 'm'},
        {"trials", required_argument, nullptr, 'n'},    {"time-ms", required_argument, nullptr, 't'},
        {"seed", required_argument, nullptr, 's'},      {"max-nodes", required_argument, nullptr, 'N'},
        {"planners", required_argument, nullptr, 'p'},  {"out", required_argument, nullptr, OPT_OUT},
        {"ompl-log", required_argument, nullptr, OPT_OMPL_LOG}, {"help", no_argument, nullptr, 'h'},
        {nullptr, 0, nullptr, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "o:m:n:t:s:N:p:h", opts, nullptr)) != -1) {
        switch (c) {
        case 'o': objective = optarg; break;
        case 'm': model_path = optarg; break;
        case 'n':
            if (!parse_long(optarg, &trials) || trials < 1 || trials > 100000) {
                std::fprintf(stderr, "gmmrrt-bench-ompl: --trials must be an integer in 1..100000, got '%s'\n", optarg);
                return 2;
            }
            break;
        case 't':
            if (!parse_double(optarg, &time_ms) || !(time_ms > 0.0) || time_ms > 3.6e6) {
                std::fprintf(stderr, "gmmrrt-bench-ompl: --time-ms must be a number in (0, 3600000], got '%s'\n", optarg);
                return 2;
            }
            break;
        case 's':
            if (!parse_long(optarg, &seed) || seed < 0) {
                std::fprintf(stderr, "gmmrrt-bench-ompl: --seed must be a non-negative integer, got '%s'\n", optarg);
                return 2;
            }
            break;
        case 'N':
            if (!parse_long(optarg, &max_nodes) || max_nodes < 2 || max_nodes > GMMRRT_MAX_NODES_CEILING) {
                std::fprintf(stderr, "gmmrrt-bench-ompl: --max-nodes must be in 2..%d, got '%s'\n",
                             GMMRRT_MAX_NODES_CEILING, optarg);
                return 2;
            }
            break;
        case 'p': planners = optarg; break;
        case OPT_OUT: out_path = optarg; break;
        case OPT_OMPL_LOG: ompl_log_path = optarg; break;
        case 'h': usage(stdout); return 0;
        default: usage(stderr); return 2;
        }
    }
    if (optind < argc) {
        std::fprintf(stderr, "gmmrrt-bench-ompl: unexpected argument '%s'\n", argv[optind]);
        return 2;
    }
    if (objective != "length" && objective != "task") {
        std::fprintf(stderr, "gmmrrt-bench-ompl: --objective must be 'length' or 'task', got '%s'\n", objective.c_str());
        return 2;
    }
    std::vector<std::string> lineup;
    {
        std::string rest = planners + ",";
        for (size_t at; (at = rest.find(',')) != std::string::npos; rest.erase(0, at + 1)) {
            const std::string name = rest.substr(0, at);
            if (name != "ompl" && name != "gmmrrt" && name != "gmmrrt-plain" && name != "ompl-informed") {
                std::fprintf(stderr,
                             "gmmrrt-bench-ompl: --planners: unknown planner '%s' (ompl, gmmrrt, gmmrrt-plain, "
                             "ompl-informed)\n",
                             name.c_str());
                return 2;
            }
            if (name == "ompl-informed" && objective != "length") {
                std::fprintf(stderr, "gmmrrt-bench-ompl: ompl-informed needs --objective length (OMPL samples "
                                     "the informed set of path length only)\n");
                return 2;
            }
            lineup.push_back(name);
        }
    }

    gmmrrt_model_t model;
    TaskSettings task;
    if (objective == "task") {
        if (model_path.empty()) {
            std::fprintf(stderr, "gmmrrt-bench-ompl: --objective task needs --model FILE\n");
            return 2;
        }
        std::string err;
        if (!load_model_file(model_path, &model, &err)) {
            std::fprintf(stderr, "gmmrrt-bench-ompl: %s\n", err.c_str());
            return 1;
        }
        task.model = &model;
        gmmrrt_planner_config_t defaults;
        gmmrrt_planner_config_default(&defaults);
        task.delta = defaults.delta > 0.0 ? defaults.delta : model.delta;
        task.w_length = defaults.w_length;
        task.w_task = defaults.w_task;
    }

    std::ofstream file_out;
    if (!out_path.empty()) {
        file_out.open(out_path);
        if (!file_out) {
            std::fprintf(stderr, "gmmrrt-bench-ompl: cannot write '%s'\n", out_path.c_str());
            return 1;
        }
    }
    std::ostream &out = out_path.empty() ? std::cout : file_out;

    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(seed + 1));

    std::vector<unsigned char> block;
    const size_t m = lineup.size();
    for (long long i = 0; i < trials; ++i) {
        for (size_t k = 0; k < m; ++k) {
            const std::string &name = lineup[(k + static_cast<size_t>(i)) % m]; /* rotated per trial */
            TrialResult r;
            if (name == "ompl" || name == "ompl-informed") {
                r = run_ompl_trial(objective, task.model ? &task : nullptr, time_ms, static_cast<int>(i),
                                   name == "ompl-informed");
            } else {
                std::string err;
                if (!run_gmmrrt_trial(objective, task.model ? &task : nullptr, time_ms, static_cast<int>(i),
                                      static_cast<uint64_t>(seed + i), static_cast<int32_t>(max_nodes), &block, &r,
                                      &err, name == "gmmrrt-plain")) {
                    std::fprintf(stderr, "gmmrrt-bench-ompl: %s\n", err.c_str());
                    return 1;
                }
            }
            write_trial_json(out, r);
            out << '\n';
            out.flush();
        }
    }

    if (!ompl_log_path.empty()) {
        std::string err;
        if (!write_ompl_benchmark_log(ompl_log_path, objective, task.model ? &task : nullptr, time_ms,
                                      static_cast<unsigned>(trials), static_cast<int32_t>(max_nodes),
                                      static_cast<uint64_t>(seed), &err)) {
            std::fprintf(stderr, "gmmrrt-bench-ompl: %s\n", err.c_str());
            return 1;
        }
    }
    return out ? 0 : 1;
}
