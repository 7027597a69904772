// commands.hpp - the gmmrrt-learn subcommands: each parses its own options with
// getopt_long (argv[0] is the subcommand name) and returns the process exit status.
#ifndef GMMRRT_LEARN_COMMANDS_HPP
#define GMMRRT_LEARN_COMMANDS_HPP

namespace gmmrrt {
namespace learn {
namespace cli {

int RunFit(int argc, char** argv);
int RunScore(int argc, char** argv);
int RunInspect(int argc, char** argv);
int RunImport(int argc, char** argv);
int RunDump(int argc, char** argv);
int RunSegment(int argc, char** argv);
int RunPlot(int argc, char** argv);

}  // namespace cli
}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARN_COMMANDS_HPP
