/*
 * trial.cpp - JSON form of a trial record (see trial.hpp). Hand-written because the record
 * is flat and small; non-finite numbers are written as null, as JSON has no infinity.
 */
#include "trial.hpp"

#include <cmath>
#include <cstdio>
#include <ctime>

namespace gmmrrt_bench {

static void put_number(std::ostream &out, double v)
{
    if (!std::isfinite(v)) {
        out << "null";
        return;
    }
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    out << buf;
}

static void put_string(std::ostream &out, const std::string &s)
{
    out << '"';
    for (char c : s) {
        if (c == '"' || c == '\\') {
            out << '\\' << c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
            out << buf;
        } else {
            out << c;
        }
    }
    out << '"';
}

double thread_cpu_ms()
{
    struct timespec ts;
    if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0)
        return std::nan("");
    return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

void write_trial_json(std::ostream &out, const TrialResult &r)
{
    out << "{\"planner\":";
    put_string(out, r.planner);
    out << ",\"objective\":";
    put_string(out, r.objective);
    out << ",\"trial\":" << r.trial << ",\"seed\":" << r.seed << ",\"setup_ms\":";
    put_number(out, r.setup_ms);
    out << ",\"time_ms\":";
    put_number(out, r.time_ms);
    out << ",\"cpu_ms\":";
    put_number(out, r.cpu_ms);
    out << ",\"iterations\":" << r.iterations << ",\"nodes\":" << r.nodes << ",\"first_solution_ms\":";
    put_number(out, r.first_solution_ms);
    out << ",\"first_solution_iteration\":" << r.first_solution_iteration << ",\"final_cost\":";
    put_number(out, r.final_cost);
    out << ",\"status\":";
    put_string(out, r.status);
    out << ",\"history\":[";
    for (size_t i = 0; i < r.history.size(); ++i) {
        if (i)
            out << ',';
        out << '[';
        put_number(out, r.history[i].time_ms);
        out << ',' << r.history[i].iterations << ',';
        put_number(out, r.history[i].cost);
        out << ']';
    }
    out << "]}";
}

} // namespace gmmrrt_bench
