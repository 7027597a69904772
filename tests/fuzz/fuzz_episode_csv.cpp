// fuzz_episode_csv.cpp - libFuzzer target for the learner's episode CSV reader
// gmmrrt::learn::ReadEpisodeCsv and the split index reader ReadSplitIndex
// (learner/src/demo_io.cpp; CSV layout of ../shared/data/real/README.md, the UPO/UCY
// demonstrations of paper Sect. 6). Seeds: small CSVs written by tools/fuzz_corpus.py.
// Checks: no memory error or UB, no exception escapes, the ReadResult contract.
#include <map>

#include "fuzz_reader_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = fuzzio::AsFile(data, size);
    std::vector<gmmrrt::learn::Episode> out;
    const auto r = gmmrrt::learn::ReadEpisodeCsv(path, &out);
    fuzzio::CheckResult(r, out, 0);
    if (r.ok) {
        for (auto& ep : out)
            gmmrrt::learn::EstimateHeadingsFromMotion(&ep.samples);
    }
    std::map<std::string, std::string> split{{"old", "train"}};
    const auto s = gmmrrt::learn::ReadSplitIndex(path, &split);
    if (!s.ok && (s.error.empty() || split.size() != 1 || split.count("old") != 1))
        fuzzio::Fail("ReadSplitIndex failed without a message or changed its output");
    return 0;
}
