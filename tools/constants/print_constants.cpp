// print_constants.cpp - writes gmmrrt_constants.py, the numbers the Python tools judge the
// programs by, as the compiler reads them from the one header that defines each: the
// walking-people model of the core (planner.h), the planning bounds' margin (problem_bounds.h), the path status codes (status.h),
// gmmrrtd's accepted utime range (planner/daemon/clock.h) and the demonstration reader's pairing
// limit (learner demo_io.hpp), and the task and homotopy words with their wire values (the learner's
// labels.hpp over model.h's enums). Python imports the module instead
// of writing the numbers again. Usage: gmmrrt-print-constants OUT.py (written whole or not at all).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "clock.h"
#include "gmmrrt/planner.h"
#include "gmmrrt/problem_bounds.h"
#include "gmmrrt_learner/demo_io.hpp"
#include "gmmrrt_learner/labels.hpp"

// A Python float literal of v: the shortest of 15 or 17 significant digits that reads back to v,
// with ".0" where it would otherwise read as an int.
static std::string py_float(double v)
{
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.15g", v);
    if (std::strtod(buf, nullptr) != v)
        std::snprintf(buf, sizeof buf, "%.17g", v);
    std::string s = buf;
    if (s.find_first_of(".eEn") == std::string::npos)
        s += ".0";
    return s;
}

static void print_float(std::FILE *f, const char *name, double v)
{
    std::fprintf(f, "%s = %s\n", name, py_float(v).c_str());
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUT.py\n", argv[0]);
        return 2;
    }
    const std::string out = argv[1], tmp = out + ".tmp";
    std::FILE *f = std::fopen(tmp.c_str(), "w");
    if (f == nullptr) {
        std::perror(tmp.c_str());
        return 1;
    }
    std::fprintf(f, "\"\"\"Constants of the C and C++ code, for the Python tools; generated at build time by\n"
                    "tools/constants/print_constants.cpp from the headers that define them. Do not edit.\"\"\"\n\n");
    std::fprintf(f, "# planner/include/gmmrrt/planner.h: walking people\n");
    print_float(f, "GMMRRT_STANDING_SPEED_M_S", GMMRRT_STANDING_SPEED_M_S);
    print_float(f, "GMMRRT_DEFAULT_NOMINAL_SPEED_M_S", GMMRRT_DEFAULT_NOMINAL_SPEED_M_S);
    print_float(f, "GMMRRT_DEFAULT_PREDICTION_HORIZON_S", GMMRRT_DEFAULT_PREDICTION_HORIZON_S);
    std::fprintf(f, "# planner/include/gmmrrt/problem_bounds.h: margin of the bounds round start and goal (m)\n");
    print_float(f, "GMMRRT_DEFAULT_BOUNDS_MARGIN_M", GMMRRT_DEFAULT_BOUNDS_MARGIN_M);
    std::fprintf(f, "# planner/daemon/clock.h: utimes gmmrrtd accepts, 0..this (microseconds)\n");
    std::fprintf(f, "GMMRRTD_MAX_UTIME = %lld\n", static_cast<long long>(GMMRRTD_MAX_UTIME));
    std::fprintf(f, "# learner/include/gmmrrt_learner/demo_io.hpp: oldest PEOPLE a pose is paired with (s)\n");
    print_float(f, "LEARNER_MAX_PERSON_AGE_S", gmmrrt::learn::kMaxPersonAgeS);
    std::fprintf(f, "# planner/include/gmmrrt/status.h: PLAN.status of a path that escapes a contact, and of one\n"
                    "# flagged for a corner tighter than the turning radius\n");
    std::fprintf(f, "GMMRRT_ESCAPE = %d\n", static_cast<int>(GMMRRT_ESCAPE));
    std::fprintf(f, "GMMRRT_TIGHT_TURNS = %d\n", static_cast<int>(GMMRRT_TIGHT_TURNS));
    std::fprintf(f, "# learner/include/gmmrrt_learner/labels.hpp: episode labels, word -> gmmrrt_task_t /\n"
                    "# gmmrrt_homotopy_t (the values of nav_goal_t.TASK_* and demo_info_t.HOMOTOPY_*)\n");
    std::fprintf(f, "TASKS = {");
    for (int t = GMMRRT_TASK_AVOID; t <= GMMRRT_TASK_APPROACH; ++t)
        std::fprintf(f, "%s\"%s\": %d", t == GMMRRT_TASK_AVOID ? "" : ", ", gmmrrt::learn::TaskName(t), t);
    std::fprintf(f, "}\nHOMOTOPIES = {");
    for (int h = GMMRRT_HOMOTOPY_LEFT; h <= GMMRRT_HOMOTOPY_FRONTAL; ++h)
        std::fprintf(f, "%s\"%s\": %d", h == GMMRRT_HOMOTOPY_LEFT ? "" : ", ", gmmrrt::learn::HomotopyName(h), h);
    std::fprintf(f, "}\n");
    const bool ok = std::ferror(f) == 0;
    if (std::fclose(f) != 0 || !ok || std::rename(tmp.c_str(), out.c_str()) != 0) {
        std::perror(out.c_str());
        std::remove(tmp.c_str());
        return 1;
    }
    return 0;
}
