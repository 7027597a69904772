// cmd_dump.cpp - `gmmrrt-learn dump --json [--index INDEX] FILE...`: the episodes the learner's reader
// (demo_io.hpp: ReadEpisodes, a demonstration log or an episode CSV chosen by content) makes
// of each FILE, as one JSON object on stdout. The Python tools get their episodes from here
// (gmmrrt_tools.episodes.read_episodes), so the reading rules exist once, in demo_io.cpp.
//
// Output: {"episodes": [{"id", "task", "homotopy" (gmmrrt_task_t / gmmrrt_homotopy_t values),
// "source" (the FILE), "t", "robot_x", "robot_y", "robot_yaw", "person_x", "person_y",
// "person_yaw" (one number per sample; a robot_yaw that cannot be estimated is null), "split"
// (from INDEX, read by ReadSplitIndex; "" when not listed or without INDEX)}, ...],
// "warnings": [...]} with the episodes of the files in order. Numbers are printed with 17
// significant digits, so they read back to the same doubles.
#include <getopt.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gmmrrt_learner/demo_io.hpp"

namespace gmmrrt {
namespace learn {
namespace cli {

namespace {
const char kDumpHelp[] =
    "usage: gmmrrt-learn dump --json [--index INDEX] FILE...\n"
    "\n"
    "Reads each FILE (a demonstration log or an episode CSV, by content; docs/demonstrations.md)\n"
    "with the learner's reader and prints its episodes and the reader's warnings as one JSON\n"
    "object: {\"episodes\": [{\"id\", \"task\", \"homotopy\", \"source\", \"t\", \"robot_x\", \"robot_y\",\n"
    "\"robot_yaw\", \"person_x\", \"person_y\", \"person_yaw\", \"split\"}], \"warnings\": [...]}.\n"
    "  --index INDEX  an index CSV (episode_id and split columns): each episode's split\n"
    "Exit status: 0 read; 1 a FILE could not be read (the reason names the file and place); 2 usage.\n";

nlohmann::json Column(const Episode& e, double PoseSample::*field) {
  nlohmann::json out = nlohmann::json::array();
  for (const PoseSample& s : e.samples) {
    const double v = s.*field;
    if (std::isfinite(v))
      out.push_back(v);
    else
      out.push_back(nullptr);  // robot_yaw where the motion gives no heading
  }
  return out;
}
}  // namespace

int RunDump(int argc, char** argv) {
  const char* cmd = "dump";
  static const struct option kLong[] = {
      {"json", no_argument, nullptr, 'j'},
      {"index", required_argument, nullptr, 'i'},
      {"help", no_argument, nullptr, 'h'},
      {nullptr, 0, nullptr, 0}};
  optind = 1;
  bool json = false;
  std::map<std::string, std::string> split;
  int c;
  while ((c = getopt_long(argc, argv, "h", kLong, nullptr)) != -1) {
    if (c == 'h') {
      std::fputs(kDumpHelp, stdout);
      return kExitOk;
    }
    if (c == 'j') {
      json = true;
      continue;
    }
    if (c == 'i') {
      const ReadResult r = ReadSplitIndex(optarg, &split);
      if (!r.ok) return Fail(cmd, r.error);
      continue;
    }
    return UsageError(cmd, "unknown option");
  }
  if (!json) return UsageError(cmd, "give --json (the only output format)");
  if (optind >= argc) return UsageError(cmd, "give at least one FILE");

  nlohmann::json episodes = nlohmann::json::array(), warnings = nlohmann::json::array();
  for (int i = optind; i < argc; ++i) {
    std::vector<Episode> eps;
    const ReadResult r = ReadEpisodes(argv[i], &eps);
    if (!r.ok) return Fail(cmd, r.error);
    for (const std::string& w : r.warnings) warnings.push_back(w);
    for (const Episode& e : eps) {
      const auto listed = split.find(e.id);
      episodes.push_back({{"id", e.id},
                          {"task", e.task},
                          {"homotopy", e.homotopy},
                          {"source", argv[i]},
                          {"t", Column(e, &PoseSample::t_s)},
                          {"robot_x", Column(e, &PoseSample::robot_x)},
                          {"robot_y", Column(e, &PoseSample::robot_y)},
                          {"robot_yaw", Column(e, &PoseSample::robot_yaw)},
                          {"person_x", Column(e, &PoseSample::person_x)},
                          {"person_y", Column(e, &PoseSample::person_y)},
                          {"person_yaw", Column(e, &PoseSample::person_yaw)},
                          {"split", listed == split.end() ? std::string() : listed->second}});
    }
  }
  const nlohmann::json out = {{"episodes", episodes}, {"warnings", warnings}};
  const std::string text = out.dump();
  std::fwrite(text.data(), 1, text.size(), stdout);
  std::fputc('\n', stdout);
  return kExitOk;
}

}  // namespace cli
}  // namespace learn
}  // namespace gmmrrt
