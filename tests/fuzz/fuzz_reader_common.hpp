// fuzz_reader_common.hpp - shared by the learner reader fuzz targets: the readers take a
// path, so each input is written into one memory file (memfd, no disk I/O) and handed
// over as /proc/self/fd/N. Also the checks every reader result must pass.
#ifndef GMMRRT_FUZZ_READER_COMMON_HPP
#define GMMRRT_FUZZ_READER_COMMON_HPP

#include <sys/mman.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "gmmrrt_learner/demo_io.hpp"

namespace fuzzio {

// The path of a memory file holding exactly data[0..size). Aborts when the kernel refuses.
inline std::string AsFile(const uint8_t* data, size_t size) {
    static int fd = -1;
    if (fd < 0) {
        fd = memfd_create("gmmrrt-fuzz", 0);
        if (fd < 0) {
            std::perror("memfd_create");
            std::abort();
        }
    }
    if (ftruncate(fd, 0) != 0 || (size > 0 && pwrite(fd, data, size, 0) != static_cast<ssize_t>(size))) {
        std::perror("memfd write");
        std::abort();
    }
    return "/proc/self/fd/" + std::to_string(fd);
}

[[noreturn]] inline void Fail(const char* what) {
    std::fprintf(stderr, "fuzz reader: %s\n", what);
    std::abort();
}

// What demo_io.hpp promises: an error names the problem; on failure *out is unchanged;
// warnings are capped; on success every sample is finite where the reader says it is
// and t_s never decreases within an episode.
inline void CheckResult(const gmmrrt::learn::ReadResult& r, const std::vector<gmmrrt::learn::Episode>& out,
                        size_t before) {
    if (!r.ok) {
        if (r.error.empty())
            Fail("failure without a message");
        if (out.size() != before)
            Fail("failure changed the output");
        return;
    }
    if (r.warnings.size() > gmmrrt::learn::kMaxWarnings + 1)
        Fail("more warnings than kMaxWarnings (+1 summary line)");
    for (size_t e = before; e < out.size(); ++e) {
        const auto& ep = out[e];
        if (ep.samples.empty())
            Fail("an episode without samples");
        for (size_t i = 0; i < ep.samples.size(); ++i) {
            const auto& s = ep.samples[i];
            if (!std::isfinite(s.t_s) || !std::isfinite(s.robot_x) || !std::isfinite(s.robot_y) ||
                !std::isfinite(s.person_x) || !std::isfinite(s.person_y) || !std::isfinite(s.person_yaw))
                Fail("a sample with a non-finite value");
            if (i > 0 && s.t_s < ep.samples[i - 1].t_s)
                Fail("time goes backwards inside an episode");
        }
    }
}

}  // namespace fuzzio

#endif  // GMMRRT_FUZZ_READER_COMMON_HPP
