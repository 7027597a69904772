// main.cpp - gmmrrt-learn, the offline model export tool:
// fit / score / inspect / import / dump / segment / plot. Each subcommand lives in its own cmd_*.cpp.
#include <cstdio>
#include <cstring>

#include "commands.hpp"

namespace {
const char kHelp[] =
    "usage: gmmrrt-learn COMMAND [options]   (gmmrrt-learn COMMAND --help for each)\n"
    "\n"
    "  fit      learn a Gaussian mixture from demonstrations or a features CSV (EM) -> MODEL\n"
    "  score    mean log-likelihood per point of data under a MODEL\n"
    "  inspect  validate and print a MODEL\n"
    "  import   convert a JSON mixture (priors, means, covariances) -> MODEL\n"
    "  dump     print the episodes of demonstration logs / episode CSVs as JSON\n"
    "  segment  cut continuous logs (ROBOT_POSE, PEOPLE) into labelled episodes -> episode CSV\n"
    "  plot     draw a MODEL's density and components as an image (needs python3-matplotlib)\n"
    "\n"
    "Model format: docs/model-format.md. Guide: docs/learner.md.\n";
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fputs(kHelp, stderr);
    return 2;
  }
  const char* cmd = argv[1];
  if (!std::strcmp(cmd, "-h") || !std::strcmp(cmd, "--help") || !std::strcmp(cmd, "help")) {
    std::fputs(kHelp, stdout);
    return 0;
  }
  using namespace gmmrrt::learn::cli;
  if (!std::strcmp(cmd, "fit")) return RunFit(argc - 1, argv + 1);
  if (!std::strcmp(cmd, "score")) return RunScore(argc - 1, argv + 1);
  if (!std::strcmp(cmd, "inspect")) return RunInspect(argc - 1, argv + 1);
  if (!std::strcmp(cmd, "import")) return RunImport(argc - 1, argv + 1);
  if (!std::strcmp(cmd, "dump")) return RunDump(argc - 1, argv + 1);
  if (!std::strcmp(cmd, "segment")) return RunSegment(argc - 1, argv + 1);
  if (!std::strcmp(cmd, "plot")) return RunPlot(argc - 1, argv + 1);
  std::fprintf(stderr, "gmmrrt-learn: unknown command '%s'\n\n%s", cmd, kHelp);
  return 2;
}
