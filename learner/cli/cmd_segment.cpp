// cmd_segment.cpp - `gmmrrt-learn segment LOG... -o EPISODES.csv`: continuous recordings of
// ROBOT_POSE and PEOPLE (no DEMO_INFO) -> labelled episodes as an episode CSV that `fit` reads.
// The recordings are read by demo_io.hpp's ReadRecording (the learner's log reader: LCM's
// eventlog, the daemon's validating decoders), the rules are segment.hpp's.
#include <getopt.h>

#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gmmrrt_learner/demo_io.hpp"
#include "gmmrrt_learner/segment.hpp"

namespace gmmrrt {
namespace learn {
namespace cli {

namespace {
const char kSegmentHelp[] =
    "usage: gmmrrt-learn segment LOG... -o EPISODES.csv [-q]\n"
    "\n"
    "Cuts continuous LCM logs of ROBOT_POSE and PEOPLE (no DEMO_INFO needed) into episodes of the\n"
    "robot passing (avoid) or approaching a person who stands still, labels each one's task and\n"
    "homotopy from the geometry, and writes them as an episode CSV for `gmmrrt-learn fit --input`.\n"
    "Rules: docs/learner.md, \"Raw recordings in\". Episode ids: <log file stem>_seg<NNNN>.\n"
    "  -o, --output FILE  the episode CSV (written whole or not at all)\n"
    "  -q, --quiet        no per-log summary and no notes (reader warnings stay)\n"
    "Notes (a person who never stands still, an encounter that is not a pass) and the reader's\n"
    "warnings go to stderr naming the file, the person and the time.\n"
    "Exit status: 0 written; 1 a LOG cannot be read, has no ROBOT_POSE or no person, or no episode\n"
    "was found in any LOG (nothing is written then); 2 usage.\n";

const char* TaskText(int task) { return task == GMMRRT_TASK_APPROACH ? "approach" : "avoid"; }

const char* HomotopyText(int h) {
  return h == GMMRRT_HOMOTOPY_LEFT ? "left" : h == GMMRRT_HOMOTOPY_RIGHT ? "right" : "frontal";
}
}  // namespace

int RunSegment(int argc, char** argv) {
  const char* cmd = "segment";
  static const struct option kLong[] = {{"output", required_argument, nullptr, 'o'},
                                        {"quiet", no_argument, nullptr, 'q'},
                                        {"help", no_argument, nullptr, 'h'},
                                        {nullptr, 0, nullptr, 0}};
  optind = 1;
  std::string output;
  bool quiet = false;
  int c;
  while ((c = getopt_long(argc, argv, "ho:q", kLong, nullptr)) != -1) {
    if (c == 'h') {
      std::fputs(kSegmentHelp, stdout);
      return kExitOk;
    }
    if (c == 'o') {
      output = optarg;
    } else if (c == 'q') {
      quiet = true;
    } else {
      return UsageError(cmd, "unknown option");
    }
  }
  if (output.empty()) return UsageError(cmd, "give the output episode CSV with -o");
  if (optind >= argc) return UsageError(cmd, "give at least one LOG");

  const SegmentOptions options;
  std::vector<Episode> episodes;
  std::map<std::string, std::string> log_of_id;
  for (int i = optind; i < argc; ++i) {
    const std::string log = argv[i];
    Recording rec;
    const ReadResult r = ReadRecording(log, &rec);
    for (const std::string& w : r.warnings) std::fprintf(stderr, "gmmrrt-learn segment: warning: %s\n", w.c_str());
    if (!r.ok) return Fail(cmd, r.error + ": nothing written");
    SegmentResult seg = SegmentRecording(rec, log, options);
    std::map<std::pair<std::string, std::string>, int> counts;
    for (SegmentedEpisode& s : seg.episodes) {
      const auto seen = log_of_id.emplace(s.episode.id, log);
      if (!seen.second)
        return Fail(cmd, log + ": episode id " + s.episode.id + " is also one of " + seen.first->second +
                             "'s (two logs with the same file stem): rename one; nothing written");
      ++counts[{TaskText(s.episode.task), HomotopyText(s.episode.homotopy)}];
      episodes.push_back(std::move(s.episode));
    }
    if (!quiet) {
      for (const std::string& n : seg.notes) std::fprintf(stderr, "gmmrrt-learn segment: note: %s\n", n.c_str());
      std::string summary;
      for (const auto& kv : counts)
        summary += (summary.empty() ? "" : ", ") + kv.first.first + " " + kv.first.second + ": " +
                   std::to_string(kv.second);
      std::fprintf(stderr, "gmmrrt-learn segment: %s: %zu episodes (%s)\n", log.c_str(), seg.episodes.size(),
                   summary.c_str());
    }
  }
  if (episodes.empty()) {
    std::string logs;
    for (int i = optind; i < argc; ++i) logs += std::string(i > optind ? ", " : "") + argv[i];
    return Fail(cmd, "no episode found in " + logs + ": nothing written");
  }
  const ReadResult w = WriteEpisodeCsv(output, episodes);
  if (!w.ok) return Fail(cmd, w.error);
  if (!quiet)
    std::fprintf(stderr, "gmmrrt-learn segment: wrote %zu episodes to %s\n", episodes.size(), output.c_str());
  return kExitOk;
}

}  // namespace cli
}  // namespace learn
}  // namespace gmmrrt
