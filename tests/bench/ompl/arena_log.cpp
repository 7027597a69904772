/*
 * arena_log.cpp - the ompl::tools::Benchmark log format (arena_log.hpp), field for field as
 * OMPL 1.5 writes it (see bench/ompl_length.log, written by ompl::tools::Benchmark itself).
 */
#include "arena_log.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>

#include <ompl/config.h>

namespace gmmrrt_bench {

namespace {

std::string value(double v, double scale)
{
    if (!std::isfinite(v))
        return "";
    char b[64];
    std::snprintf(b, sizeof b, "%.9g", v * scale);
    return b;
}

} // namespace

bool write_arena_log(const std::string &path, const std::string &experiment, const std::string &setup,
                     double budget_ms, unsigned seed, double total_seconds, const std::vector<ArenaPlanner> &planners,
                     std::string *err)
{
    const std::string tmp = path + ".tmp";
    std::ofstream out(tmp);
    char host[256] = "unknown";
    if (gethostname(host, sizeof host - 1) != 0)
        std::snprintf(host, sizeof host, "unknown");
    char date[64] = "";
    const std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S", std::gmtime(&now));
    size_t runs = 0;
    for (const ArenaPlanner &p : planners)
        runs = std::max(runs, p.runs.size());
    out << "OMPL version " << OMPL_MAJOR_VERSION << "." << OMPL_MINOR_VERSION << "." << OMPL_PATCH_VERSION << "\n"
        << "Experiment " << experiment << "\n"
        << "0 experiment properties\n"
        << "Running on " << host << "\n"
        << "Starting at " << date << "\n"
        << "<<<|\n" << setup << "\n|>>>\n"
        << "<<<|\n|>>>\n"
        << seed << " is the random seed\n"
        << budget_ms / 1000.0 << " seconds per run\n"
        << "0 MB per run\n"
        << runs << " runs per planner\n"
        << total_seconds << " seconds spent to collect the data\n"
        << "0 enum types\n"
        << planners.size() << " planners\n";
    for (const ArenaPlanner &p : planners) {
        out << "geometric_" << p.name << "\n"
            << "0 common properties\n"
            << "5 properties for each run\n"
            << "best cost REAL\nfirst solution time REAL\nsetup time REAL\nsolved BOOLEAN\ntime REAL\n"
            << p.runs.size() << " runs\n";
        for (const ArenaRun &r : p.runs) {
            const bool solved = std::isfinite(r.cost);
            out << value(r.cost, 1.0) << "; " << value(r.first_ms, 1e-3) << "; " << value(r.setup_ms, 1e-3) << "; "
                << (solved ? 1 : 0) << "; " << value(r.setup_ms + r.solve_ms, 1e-3) << "; \n";
        }
        out << ".\n";
    }
    out.close();
    if (!out || std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::remove(tmp.c_str());
        *err = "cannot write the Planner Arena log '" + path + "'";
        return false;
    }
    return true;
}

} // namespace gmmrrt_bench
