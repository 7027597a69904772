// dump_episodes.cpp - test helper: prints what the learner's reader (learner/src/demo_io.cpp)
// makes of a demonstration log or episode CSV, so the Python reader (tools/gmmrrt_tools/demolog.py)
// can be checked against it (tests/unit/demos/test_parity.py).
//
// Usage: demos_dump_episodes FILE
// Output: "ok" or "error<TAB>message", then "warnings<TAB>count", then per sample
// "id,task,homotopy,t,robot_x,robot_y,robot_yaw,person_x,person_y,person_yaw" (%.17g).
// Exit status 0 when read, 1 on a read error, 2 on bad usage.
#include <cstdio>
#include <vector>

#include "gmmrrt_learner/demo_io.hpp"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: demos_dump_episodes FILE\n");
        return 2;
    }
    std::vector<gmmrrt::learn::Episode> eps;
    const gmmrrt::learn::ReadResult r = gmmrrt::learn::ReadEpisodes(argv[1], &eps);
    if (!r.ok) {
        std::printf("error\t%s\n", r.error.c_str());
        return 1;
    }
    std::printf("ok\nwarnings\t%zu\n", r.warnings.size());
    for (const auto& e : eps)
        for (const auto& s : e.samples)
            std::printf("%s,%d,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", e.id.c_str(), e.task, e.homotopy,
                        s.t_s, s.robot_x, s.robot_y, s.robot_yaw, s.person_x, s.person_y, s.person_yaw);
    return 0;
}
