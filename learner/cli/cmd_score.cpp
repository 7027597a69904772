// cmd_score.cpp - `gmmrrt-learn score MODEL ...`: the mean log-likelihood per point of held-out
// data under a model (paper eq. 1, wrapped normal of gmm.h, evaluated by mixture.hpp).
#include <getopt.h>

#include <cstdio>
#include <string>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gmmrrt_learner/episode_features.hpp"
#include "gmmrrt_learner/mixture.hpp"

namespace gmmrrt {
namespace learn {
namespace cli {

namespace {
const char kScoreHelp[] =
    "usage: gmmrrt-learn score MODEL (--input FILE... [--task T] | --features-csv FILE) [options]\n"
    "\n"
    "Prints the mean log-likelihood per point of the data under MODEL (held-out evaluation):\n"
    "  mean_log_likelihood <value>\n"
    "  points <N>\n"
    "\n"
    "  -i, --input FILE        episode CSV or LCM demonstration log (repeatable)\n"
    "  -t, --task T            avoid | approach (default: the model's task)\n"
    "  -H, --homotopy H        all | left | right | frontal (default: the model's homotopy)\n"
    "  -x, --index FILE        index CSV with a split column (repeatable)\n"
    "  -s, --split S           train | test (needs --index)\n"
    "  -f, --features-csv FILE rows of D numbers, D the model's dimension (angle dimensions\n"
    "                          are the model's)\n"
    "  -q, --quiet             no counts on stderr\n"
    "  -h, --help              this text\n"
    "\n"
    "Exit status: 0 scored; 1 bad model or data; 2 usage error.\n";
}  // namespace

int RunScore(int argc, char** argv) {
  const char* cmd = "score";
  static const struct option kLong[] = {
      {"input", required_argument, nullptr, 'i'},    {"task", required_argument, nullptr, 't'},
      {"homotopy", required_argument, nullptr, 'H'}, {"index", required_argument, nullptr, 'x'},
      {"split", required_argument, nullptr, 's'},    {"features-csv", required_argument, nullptr, 'f'},
      {"quiet", no_argument, nullptr, 'q'},          {"help", no_argument, nullptr, 'h'},
      {nullptr, 0, nullptr, 0}};
  DataSpec spec;
  std::string task_name, homotopy_name;
  std::vector<std::string> positional;
  optind = 1;
  int c;
  while ((c = getopt_long(argc, argv, "i:t:H:x:s:f:qh", kLong, nullptr)) != -1) {
    const std::string arg = optarg ? optarg : "";
    switch (c) {
      case 'i': spec.inputs.push_back(arg); break;
      case 't': task_name = arg; break;
      case 'H': homotopy_name = arg; break;
      case 'x': spec.indexes.push_back(arg); break;
      case 's':
        if (arg != "train" && arg != "test") return UsageError(cmd, "--split must be train or test, not '" + arg + "'");
        spec.split = arg;
        break;
      case 'f':
        if (!spec.features_csv.empty()) return UsageError(cmd, "--features-csv given twice");
        spec.features_csv = arg;
        break;
      case 'q': spec.quiet = true; break;
      case 'h': std::fputs(kScoreHelp, stdout); return kExitOk;
      default: return UsageError(cmd, "unknown option or missing argument");
    }
  }
  for (int a = optind; a < argc; ++a) positional.push_back(argv[a]);
  if (positional.empty()) return UsageError(cmd, "no MODEL given");
  const std::string model_path = positional[0];
  spec.inputs.insert(spec.inputs.end(), positional.begin() + 1, positional.end());
  if (spec.inputs.empty() == spec.features_csv.empty())
    return UsageError(cmd, "give either --input FILE... or --features-csv FILE (exactly one kind of data)");
  if (!spec.split.empty() && spec.indexes.empty()) return UsageError(cmd, "--split needs --index FILE");
  if (spec.split.empty() && !spec.indexes.empty()) return UsageError(cmd, "--index needs --split train|test");
  Status s;
  if (!task_name.empty() && !(s = ParseTask(task_name, &spec.task)).ok()) return UsageError(cmd, s.message);
  int homotopy = -1;
  if (!homotopy_name.empty() && !(s = ParseHomotopy(homotopy_name, &homotopy)).ok()) return UsageError(cmd, s.message);

  gmmrrt_model_t model;
  if (!(s = LoadModel(model_path, &model)).ok()) return Fail(cmd, s.message);
  if (!spec.inputs.empty()) {
    if (model.kind == GMMRRT_MODEL_KIND_GENERIC)
      return Fail(cmd, model_path + ": a generic model scores --features-csv data, not episodes");
    spec.kind = model.kind;
    if (task_name.empty()) spec.task = model.task;
    if (spec.task == GMMRRT_TASK_NONE) return UsageError(cmd, "the model names no task: give --task");
    spec.homotopy = homotopy >= 0 ? homotopy : model.homotopy;
  } else {
    spec.angle_mask = model.angle_mask;
  }
  Eigen::MatrixXd points;
  uint32_t mask = 0;
  if (!(s = LoadPoints(cmd, spec, &points, &mask)).ok()) return Fail(cmd, s.message);
  if (points.rows() != model.dim)
    return Fail(cmd, "the data has D = " + std::to_string(points.rows()) + " but the model " + model_path +
                         " has D = " + std::to_string(model.dim));
  if (points.cols() == 0) return Fail(cmd, "no data points");
  if (!spec.features_csv.empty()) WrapAngleRows(mask, &points);
  const Mixture m = MixtureFromModel(model);
  const double ll = MeanLogLikelihood(m, points);
  std::printf("mean_log_likelihood %.10f\npoints %ld\n", ll, static_cast<long>(points.cols()));
  return kExitOk;
}

}  // namespace cli
}  // namespace learn
}  // namespace gmmrrt
