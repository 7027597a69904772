// fuzz_demo_log.cpp - libFuzzer target for the learner's demonstration log reader
// gmmrrt::learn::ReadDemoLog (learner/src/demo_io.cpp; the demonstrations of paper Sect. 4
// as LCM event logs, docs/demonstrations.md). The seed corpus is cut from logs/demos/ by
// tools/fuzz_corpus.py. Checks: no memory error or UB (sanitizers), no exception escapes,
// and the ReadResult contract of demo_io.hpp (fuzz_reader_common.hpp). The same bytes are also read
// as a continuous recording (ReadRecording) and cut by the segmenter (`gmmrrt-learn segment`).
#include <cstdlib>

#include "fuzz_reader_common.hpp"
#include "gmmrrt_learner/segment.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = fuzzio::AsFile(data, size);
    std::vector<gmmrrt::learn::Episode> out(1);  // one old entry: a failure must leave it alone
    out[0].id = "old";
    const auto r = gmmrrt::learn::ReadDemoLog(path, &out);
    fuzzio::CheckResult(r, out, 1);
    // ReadEpisodes picks the reader by content: the same bytes through it must agree on ok.
    std::vector<gmmrrt::learn::Episode> again;
    const auto r2 = gmmrrt::learn::ReadEpisodes(path, &again);
    fuzzio::CheckResult(r2, again, 0);
    gmmrrt::learn::Recording rec;
    const auto r3 = gmmrrt::learn::ReadRecording(path, &rec);
    if (r3.ok != r3.error.empty() || (r3.ok && (rec.robot.empty() || rec.people.empty())))
        std::abort();  // ok exactly when there is no error, and then both streams are there
    if (r3.ok) {
        const auto seg = gmmrrt::learn::SegmentRecording(rec, path, gmmrrt::learn::SegmentOptions());
        for (const auto& e : seg.episodes)
            if (e.episode.samples.size() < 3 || e.episode.samples[0].t_s != 0.0)
                std::abort();  // an encounter has at least 3 poses and starts at t = 0
    }
    return 0;
}
