// cmd_import.cpp - `gmmrrt-learn import --json FILE -o MODEL`: a mixture published as priors,
// means and covariances (e.g. ../shared/data/real/upo_approach_gmms.json) into a model file,
// covariances Cholesky-factorised (json_import.hpp), written atomically (model.h).
#include <getopt.h>

#include <cstdio>
#include <string>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gmmrrt_learner/episode_features.hpp"
#include "gmmrrt_learner/features_csv.hpp"
#include "gmmrrt_learner/json_import.hpp"

namespace gmmrrt {
namespace learn {
namespace cli {

namespace {
const char kImportHelp[] =
    "usage: gmmrrt-learn import --json FILE -o MODEL [options]\n"
    "\n"
    "Converts a JSON mixture into a model file. Two shapes: the lab's task sets\n"
    "({\"sets\": {SET: {TASK: {\"components\": [{\"weight\", \"mean\", \"cov\"}]}}}}), one task picked\n"
    "by --set and --task-name; or a plain {\"priors\", \"means\", \"covs\"} object.\n"
    "\n"
    "  -j, --json FILE         the JSON mixture (required)\n"
    "  -n, --task-name NAME    task of a task set, e.g. 1-front, 5-back (required for sets)\n"
    "  -e, --set SET           task set (default tasks; the UPO file also has\n"
    "                          only_one_homotopy_tasks)\n"
    "  -t, --task T            avoid | approach stored in the model (default approach)\n"
    "  -H, --homotopy H        all | left | right | frontal stored in the model (default all)\n"
    "  -a, --angle-dims LIST   1-based wrapped angle dimensions, or none (default 2: theta of\n"
    "                          (d, theta)); a 2-D mixture with angle 2 is kind features, any\n"
    "                          other kind generic\n"
    "  -d, --delta X           default delta of the task cost (default 0.001)\n"
    "  -o, --output MODEL      model file to write (required)\n"
    "  -h, --help              this text\n"
    "\n"
    "Exit status: 0 model written; 1 bad JSON or mixture (no file written); 2 usage error.\n";
}  // namespace

int RunImport(int argc, char** argv) {
  const char* cmd = "import";
  static const struct option kLong[] = {
      {"json", required_argument, nullptr, 'j'},      {"task-name", required_argument, nullptr, 'n'},
      {"set", required_argument, nullptr, 'e'},       {"task", required_argument, nullptr, 't'},
      {"homotopy", required_argument, nullptr, 'H'},  {"angle-dims", required_argument, nullptr, 'a'},
      {"delta", required_argument, nullptr, 'd'},     {"output", required_argument, nullptr, 'o'},
      {"help", no_argument, nullptr, 'h'},            {nullptr, 0, nullptr, 0}};
  JsonImportOptions options;
  std::string json_path, output, task_name = "approach", homotopy_name = "all", angle_dims = "2";
  double delta = GMMRRT_MODEL_DEFAULT_DELTA;
  optind = 1;
  int c;
  while ((c = getopt_long(argc, argv, "j:n:e:t:H:a:d:o:h", kLong, nullptr)) != -1) {
    const std::string arg = optarg ? optarg : "";
    switch (c) {
      case 'j': json_path = arg; break;
      case 'n': options.task_name = arg; break;
      case 'e': options.set = arg; break;
      case 't': task_name = arg; break;
      case 'H': homotopy_name = arg; break;
      case 'a': angle_dims = arg; break;
      case 'd':
        if (!ParseDouble(arg, &delta) || delta <= 0.0) return UsageError(cmd, "--delta '" + arg + "' is not a positive number");
        break;
      case 'o': output = arg; break;
      case 'h': std::fputs(kImportHelp, stdout); return kExitOk;
      default: return UsageError(cmd, "unknown option or missing argument");
    }
  }
  if (optind < argc) return UsageError(cmd, std::string("unexpected argument '") + argv[optind] + "'");
  if (json_path.empty()) return UsageError(cmd, "no --json FILE");
  if (output.empty()) return UsageError(cmd, "no output model (-o MODEL)");
  int task = 0, homotopy = 0;
  Status s;
  if (!(s = ParseTask(task_name, &task)).ok()) return UsageError(cmd, s.message);
  if (!(s = ParseHomotopy(homotopy_name, &homotopy)).ok()) return UsageError(cmd, s.message);
  if (angle_dims != "none" && !(s = ParseAngleDims(angle_dims, GMMRRT_MAX_DIM, &options.angle_mask)).ok())
    return UsageError(cmd, s.message);

  Mixture m;
  std::string note;
  if (!(s = ImportJsonMixture(json_path, options, &m, &note)).ok()) return Fail(cmd, s.message);
  if (!note.empty()) std::fprintf(stderr, "gmmrrt-learn import: note: %s\n", note.c_str());
  const int kind = (m.dim == 2 && m.angle_mask == (1u << 1)) ? GMMRRT_MODEL_KIND_FEATURES : GMMRRT_MODEL_KIND_GENERIC;
  gmmrrt_model_t model;
  if (!(s = MixtureToModel(m, kind, task, homotopy, delta, &model)).ok()) return Fail(cmd, s.message);
  if (!(s = SaveModel(output, model)).ok()) return Fail(cmd, s.message);
  std::fprintf(stderr, "gmmrrt-learn import: wrote %s (%s, D = %d, K = %d)\n", output.c_str(), KindName(kind), m.dim, m.k());
  return kExitOk;
}

}  // namespace cli
}  // namespace learn
}  // namespace gmmrrt
