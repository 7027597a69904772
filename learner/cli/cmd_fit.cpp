// cmd_fit.cpp - `gmmrrt-learn fit`: learns a mixture (paper Sect. 3, eq. 1) from demonstrations
// or a features CSV by k-means++-seeded EM (em.hpp), K given or chosen by a BIC sweep
// (bic.hpp), and writes it atomically as a model file (model.h, docs/model-format.md).
#include <getopt.h>

#include <cstdio>
#include <string>
#include <vector>

#include "background_fit.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "provenance.hpp"
#include "gmmrrt_learner/bic.hpp"
#include "gmmrrt_learner/delta_quantile.hpp"
#include "gmmrrt_learner/em.hpp"
#include "gmmrrt_learner/episode_features.hpp"
#include "gmmrrt_learner/features_csv.hpp"

namespace gmmrrt {
namespace learn {
namespace cli {

namespace {

const char kFitHelp[] =
    "usage: gmmrrt-learn fit (--input FILE... --task avoid|approach | --features-csv FILE)\n"
    "                        -o MODEL [options]\n"
    "\n"
    "Fits a Gaussian mixture by EM (k-means++ seeding) and writes it atomically to MODEL.\n"
    "\n"
    "data:\n"
    "  -i, --input FILE        episode CSV or LCM demonstration log (repeatable; further\n"
    "                          non-option arguments are inputs too)\n"
    "  -t, --task T            avoid | approach (required with --input)\n"
    "  -H, --homotopy H        all | left | right | frontal (default all)\n"
    "  -x, --index FILE        index CSV with a split column (repeatable)\n"
    "  -s, --split S           train | test: only episodes of that split (needs --index)\n"
    "  -K, --kind KIND         features: (d [m], theta [rad]) (default) | xy: (s, x', y')\n"
    "  -f, --features-csv FILE rows of D = 1..8 numbers (model kind generic)\n"
    "  -a, --angle-dims LIST   with --features-csv: 1-based wrapped angle dimensions, e.g. 2\n"
    "model:\n"
    "  -k, --k N|auto          components (default 19, the paper's); auto = BIC sweep\n"
    "  -r, --k-range A..B      range of the BIC sweep (default 1..30; implies --k auto)\n"
    "  -P, --bic-patience N    stop the sweep once N K in a row have a BIC above the lowest\n"
    "                          so far (default 3; 0 fits the whole range)\n"
    "  -L, --split-starts N    BIC sweep: splits of the K - 1 fit screened as extra starts for K\n"
    "                          (default 4; 0: fresh k-means++ starts only)\n"
    "  -F, --sweep-restarts N  BIC sweep: k-means++ candidates of each K that has split starts\n"
    "                          (default 2, at most --restarts; the first K uses --restarts)\n"
    "  -S, --seed S            random seed (default 1); same seed, same model\n"
    "  -R, --restarts N        candidate starts (k-means++ + Lloyd + 20 EM steps each, on a\n"
    "                          seeded sample of 20 000 points when there are more); the best\n"
    "                          log-likelihood is run to convergence on all points (default 8)\n"
    "  -p, --screen-points N   sample size for the candidates when there are more points\n"
    "                          (default 20000; 0 screens on all points)\n"
    "  -m, --max-iter N        EM iteration cap (default 500)\n"
    "  -T, --tol X             stop when an EM step changes the mean log-likelihood per point\n"
    "                          by less than X (default 1e-6)\n"
    "  -A, --accel M           squarem (default): EM accelerated by SQUAREM, never lowering the\n"
    "                          log-likelihood | none: plain EM\n"
    "  -j, --threads N         E-step threads (default: the cores available, here %d); the model\n"
    "                          is the same for any N\n"
    "  -Q, --delta-quantile Q  the delta of the task cost stored in the model is the Q-quantile\n"
    "                          (0..1) of the fitted density over the training points (default 0.25;\n"
    "                          evidence in docs/planner.md, \"What delta does\")\n"
    "  -d, --delta X           store this fixed delta instead (the paper's: --delta 0.001)\n"
    "  -B, --background B      none (default) | straight: also fit the background, a mixture over\n"
    "                          each episode's straight line start-goal, with the same options, and\n"
    "                          store it in the model file (for gmmrrt-plan --task-cost background;\n"
    "                          kind features only; docs/planner.md, \"The background cost\")\n"
    "  -o, --output MODEL      model file to write (required)\n"
    "  -N, --no-provenance     write no provenance trailer (the SHA-256 of the data files, the\n"
    "                          command line, seed, K, BIC, log-likelihood, version, UTC time;\n"
    "                          written by default, docs/learner.md): a file that loaders built\n"
    "                          before the trailer existed also read\n"
    "  -q, --quiet             no progress on stderr\n"
    "  -h, --help              this text\n"
    "\n"
    "Exit status: 0 model written; 1 bad data or failed fit (no file written); 2 usage error.\n";

bool ParseKRange(const std::string& text, int* a, int* b) {
  const size_t dots = text.find("..");
  if (dots == std::string::npos) return false;
  long lo = 0, hi = 0;
  if (!ParseInt(text.substr(0, dots), 1, GMMRRT_MAX_K, &lo) ||
      !ParseInt(text.substr(dots + 2), 1, GMMRRT_MAX_K, &hi) || hi < lo)
    return false;
  *a = static_cast<int>(lo);
  *b = static_cast<int>(hi);
  return true;
}

}  // namespace

int RunFit(int argc, char** argv) {
  const char* cmd = "fit";
  static const struct option kLong[] = {
      {"input", required_argument, nullptr, 'i'},    {"task", required_argument, nullptr, 't'},
      {"homotopy", required_argument, nullptr, 'H'}, {"index", required_argument, nullptr, 'x'},
      {"split", required_argument, nullptr, 's'},    {"kind", required_argument, nullptr, 'K'},
      {"features-csv", required_argument, nullptr, 'f'}, {"angle-dims", required_argument, nullptr, 'a'},
      {"k", required_argument, nullptr, 'k'},        {"k-range", required_argument, nullptr, 'r'},
      {"seed", required_argument, nullptr, 'S'},     {"restarts", required_argument, nullptr, 'R'},
      {"max-iter", required_argument, nullptr, 'm'}, {"tol", required_argument, nullptr, 'T'},
      {"delta", required_argument, nullptr, 'd'},    {"delta-quantile", required_argument, nullptr, 'Q'},
      {"output", required_argument, nullptr, 'o'},
      {"quiet", no_argument, nullptr, 'q'},          {"help", no_argument, nullptr, 'h'},
      {"bic-patience", required_argument, nullptr, 'P'}, {"screen-points", required_argument, nullptr, 'p'},
      {"accel", required_argument, nullptr, 'A'},    {"split-starts", required_argument, nullptr, 'L'},
      {"sweep-restarts", required_argument, nullptr, 'F'},    {"threads", required_argument, nullptr, 'j'},
      {"no-provenance", no_argument, nullptr, 'N'},  {"background", required_argument, nullptr, 'B'},
      {nullptr, 0, nullptr, 0}};
  // The command line as given, for the provenance record (getopt_long reorders argv).
  std::vector<std::string> command_line = {"gmmrrt-learn"};
  for (int a = 0; a < argc; ++a) command_line.push_back(argv[a]);
  bool provenance = true, background = false;
  DataSpec spec;
  FitOptions options;
  std::string output, task_name, homotopy_name = "all", kind_name, angle_dims, k_text;
  int k_min = 1, k_max = 30, bic_patience = kBicStopAfterRises, split_starts = kBicSplitStarts,
      fresh_starts = kBicFreshStarts;
  bool auto_k = false, k_range_given = false;
  double delta = GMMRRT_MODEL_DEFAULT_DELTA;
  // Data-driven delta by default (delta_quantile.hpp); --delta X stores a fixed one (the paper's 0.001).
  constexpr double kDefaultDeltaQuantile = 0.25;
  double delta_quantile = -1.0;  // < 0: not given
  bool delta_given = false;
  optind = 1;
  int c;
  while ((c = getopt_long(argc, argv, "i:t:H:x:s:K:f:a:k:r:P:L:F:p:S:R:m:T:A:j:d:Q:o:qhNB:", kLong, nullptr)) != -1) {
    const std::string arg = optarg ? optarg : "";
    long v = 0;
    switch (c) {
      case 'i': spec.inputs.push_back(arg); break;
      case 't': task_name = arg; break;
      case 'H': homotopy_name = arg; break;
      case 'x': spec.indexes.push_back(arg); break;
      case 's':
        if (arg != "train" && arg != "test") return UsageError(cmd, "--split must be train or test, not '" + arg + "'");
        spec.split = arg;
        break;
      case 'K': kind_name = arg; break;
      case 'f':
        if (!spec.features_csv.empty()) return UsageError(cmd, "--features-csv given twice");
        spec.features_csv = arg;
        break;
      case 'a': angle_dims = arg; break;
      case 'k': k_text = arg; break;
      case 'r':
        if (!ParseKRange(arg, &k_min, &k_max))
          return UsageError(cmd, "--k-range '" + arg + "' is not A..B with 1 <= A <= B <= " +
                                     std::to_string(GMMRRT_MAX_K));
        k_range_given = true;
        break;
      case 'P':
        if (!ParseInt(arg, 0, GMMRRT_MAX_K, &v))
          return UsageError(cmd, "--bic-patience '" + arg + "' is not in 0.." + std::to_string(GMMRRT_MAX_K));
        bic_patience = static_cast<int>(v);
        break;
      case 'L':
        if (!ParseInt(arg, 0, GMMRRT_MAX_K, &v))
          return UsageError(cmd, "--split-starts '" + arg + "' is not in 0.." + std::to_string(GMMRRT_MAX_K));
        split_starts = static_cast<int>(v);
        break;
      case 'F':
        if (!ParseInt(arg, 1, 1000, &v)) return UsageError(cmd, "--sweep-restarts '" + arg + "' is not in 1..1000");
        fresh_starts = static_cast<int>(v);
        break;
      case 'p':
        if (!ParseInt(arg, 0, 1000000000, &v)) return UsageError(cmd, "--screen-points '" + arg + "' is not in 0..1e9");
        options.screen_points = v;
        break;
      case 'S':
        if (!ParseUint64(arg, &options.seed)) return UsageError(cmd, "--seed '" + arg + "' is not an unsigned integer");
        break;
      case 'R':
        if (!ParseInt(arg, 1, 1000, &v)) return UsageError(cmd, "--restarts '" + arg + "' is not in 1..1000");
        options.restarts = static_cast<int>(v);
        break;
      case 'm':
        if (!ParseInt(arg, 0, 1000000, &v)) return UsageError(cmd, "--max-iter '" + arg + "' is not in 0..1000000");
        options.max_iterations = static_cast<int>(v);
        break;
      case 'T':
        if (!ParseDouble(arg, &options.tolerance) || options.tolerance <= 0.0)
          return UsageError(cmd, "--tol '" + arg + "' is not a positive number");
        break;
      case 'A':
        if (arg == "squarem") options.accelerate = true;
        else if (arg == "none") options.accelerate = false;
        else return UsageError(cmd, "--accel '" + arg + "' is not squarem or none");
        break;
      case 'j':
        if (!ParseInt(arg, 1, 256, &v)) return UsageError(cmd, "--threads '" + arg + "' is not in 1..256");
        options.threads = static_cast<int>(v);
        break;
      case 'd':
        if (!ParseDouble(arg, &delta) || delta <= 0.0) return UsageError(cmd, "--delta '" + arg + "' is not a positive number");
        delta_given = true;
        break;
      case 'Q':
        if (!ParseDouble(arg, &delta_quantile) || !(delta_quantile >= 0.0 && delta_quantile <= 1.0))
          return UsageError(cmd, "--delta-quantile '" + arg + "' is not a number in [0, 1]");
        break;
      case 'o': output = arg; break;
      case 'q': spec.quiet = true; break;
      case 'N': provenance = false; break;
      case 'B':
        if (arg == "straight") background = true;
        else if (arg == "none") background = false;
        else return UsageError(cmd, "--background '" + arg + "' is not none or straight");
        break;
      case 'h': std::printf(kFitHelp, DefaultThreadCount()); return kExitOk;
      default: return UsageError(cmd, "unknown option or missing argument");
    }
  }
  for (int a = optind; a < argc; ++a) spec.inputs.push_back(argv[a]);

  if (output.empty()) return UsageError(cmd, "no output model (-o MODEL)");
  if (delta_given && delta_quantile >= 0.0) return UsageError(cmd, "give --delta or --delta-quantile, not both");
  if (!delta_given && delta_quantile < 0.0) delta_quantile = kDefaultDeltaQuantile;
  if (spec.inputs.empty() == spec.features_csv.empty())
    return UsageError(cmd, "give either --input FILE... or --features-csv FILE (exactly one kind of data)");
  if (!spec.split.empty() && spec.indexes.empty()) return UsageError(cmd, "--split needs --index FILE");
  if (spec.split.empty() && !spec.indexes.empty()) return UsageError(cmd, "--index needs --split train|test");
  int kind = GMMRRT_MODEL_KIND_GENERIC;
  if (!spec.inputs.empty()) {
    if (task_name.empty()) return UsageError(cmd, "--task avoid|approach is required with --input");
    if (!angle_dims.empty()) return UsageError(cmd, "--angle-dims applies to --features-csv only");
    if (kind_name.empty() || kind_name == "features") kind = GMMRRT_MODEL_KIND_FEATURES;
    else if (kind_name == "xy") kind = GMMRRT_MODEL_KIND_XY;
    else return UsageError(cmd, "unknown --kind '" + kind_name + "' (known: features, xy)");
  } else {
    if (!kind_name.empty() && kind_name != "generic")
      return UsageError(cmd, "--kind " + kind_name + " needs episodes (--input); --features-csv gives kind generic");
    if (!spec.indexes.empty()) return UsageError(cmd, "--index/--split apply to --input episodes only");
  }
  Status s;
  if (!task_name.empty() && !(s = ParseTask(task_name, &spec.task)).ok()) return UsageError(cmd, s.message);
  if (!(s = ParseHomotopy(homotopy_name, &spec.homotopy)).ok()) return UsageError(cmd, s.message);
  spec.kind = kind;
  if (background && kind != GMMRRT_MODEL_KIND_FEATURES)
    return UsageError(cmd, "--background straight needs episodes (--input) and --kind features: the background "
                           "cost is over the features (d, theta)");
  if (k_text == "auto" || (k_text.empty() && k_range_given)) {
    auto_k = true;
  } else if (!k_text.empty()) {
    long v = 0;
    if (!ParseInt(k_text, 1, GMMRRT_MAX_K, &v))
      return UsageError(cmd, "--k '" + k_text + "' is not auto or a number in 1.." + std::to_string(GMMRRT_MAX_K));
    if (k_range_given) return UsageError(cmd, "--k-range goes with --k auto, not --k " + k_text);
    options.k = static_cast<int>(v);
  }

  Eigen::MatrixXd points;
  uint32_t mask = 0;
  if (!spec.features_csv.empty() && !angle_dims.empty()) {
    // The dimension is known only after reading; parse against the maximum, check after.
    if (!(s = ParseAngleDims(angle_dims, GMMRRT_MAX_DIM, &spec.angle_mask)).ok()) return UsageError(cmd, s.message);
  }
  if (!(s = LoadPoints(cmd, spec, &points, &mask)).ok()) return Fail(cmd, s.message);

  if (!spec.quiet) {
    options.progress = [](int restart, int it, double ll) {
      std::fprintf(stderr, "restart %d iteration %4d  mean log-likelihood %.10f\n", restart, it, ll);
    };
  }
  options.warn = [](const std::string& w) { std::fprintf(stderr, "warning: %s\n", w.c_str()); };

  Mixture mixture;
  FitSummary summary;
  std::vector<BicRow> sweep_rows;
  if (auto_k) {
    BicSweepResult sweep;
    options.progress = nullptr;  // one line per K is progress enough
    const bool quiet = spec.quiet;
    auto on_row = [quiet](const BicRow& r) {
      if (!quiet)
        std::fprintf(stderr, "K = %d: mean log-likelihood %.6f, BIC %.3f, %d iterations\n", r.k,
                     r.mean_log_likelihood, r.bic, r.iterations);
    };
    if (!(s = SweepBic(points, mask, options, k_min, k_max, &sweep, on_row, bic_patience, split_starts,
                      fresh_starts)).ok())
      return Fail(cmd, DescribeData(spec) + ": " + s.message);
    std::fputs(FormatBicTable(sweep).c_str(), stdout);
    std::printf("chosen K = %d (lowest BIC)\n", sweep.best_k);
    mixture = sweep.best;
    summary = sweep.best_summary;
    sweep_rows = sweep.rows;
  } else {
    if (!(s = FitMixture(points, mask, options, &mixture, &summary)).ok())
      return Fail(cmd, DescribeData(spec) + ": " + s.message);
  }
  // Stopping at the cap is said even with --quiet: the model is usable but not converged.
  if (auto_k) {
    int capped = 0;
    for (const BicRow& r : sweep_rows) capped += r.converged ? 0 : 1;
    if (capped > 0)
      std::fprintf(stderr,
                   "gmmrrt-learn fit: warning: %d of the %zu fits of the sweep stopped at the iteration cap "
                   "(--max-iter %d) before converging to --tol %g; raise --max-iter\n",
                   capped, sweep_rows.size(), options.max_iterations, options.tolerance);
  } else if (!summary.converged) {
    const std::vector<double>& h = summary.log_likelihood;
    const double last_change = h.size() >= 2 ? h.back() - h[h.size() - 2] : 0.0;
    std::fprintf(stderr,
                 "gmmrrt-learn fit: warning: stopped at the iteration cap (--max-iter %d) before converging "
                 "to --tol %g (last step changed the mean log-likelihood by %.3g); raise --max-iter\n",
                 options.max_iterations, options.tolerance, last_change);
  }
  if (kind == GMMRRT_MODEL_KIND_XY) SortComponentsByProgress(&mixture);
  if (!spec.quiet) std::fprintf(stderr, "gmmrrt-learn fit: %s\n", summary.BriefReport().c_str());

  if (delta_quantile >= 0.0) {
    if (!(s = DensityQuantile(mixture, points, delta_quantile, &delta)).ok()) return Fail(cmd, s.message);
    if (!spec.quiet) std::fprintf(stderr, "gmmrrt-learn fit: delta = %.6g (the %g-quantile of the training densities)\n",
                                  delta, delta_quantile);
  }
  gmmrrt_model_t model;
  if (!(s = MixtureToModel(mixture, kind, spec.task, spec.homotopy, delta, &model)).ok()) return Fail(cmd, s.message);
  std::string record;
  if (provenance) {
    FitRecord r;
    r.command_line = command_line;
    r.data_files = spec.features_csv.empty() ? spec.inputs : std::vector<std::string>{spec.features_csv};
    r.index_files = spec.indexes;
    r.seed = options.seed;
    r.k_auto = auto_k;
    r.k = mixture.k();
    r.points = summary.n_points;
    r.dim = static_cast<int>(points.rows());
    r.bic = summary.bic;
    r.mean_log_likelihood = summary.final_mean_log_likelihood;
    r.iterations = summary.iterations;
    r.converged = summary.converged;
    r.delta = delta;
    if (!(s = ProvenanceJson(r, &record)).ok()) return Fail(cmd, s.message);
  }
  gmmrrt_model_t background_model;
  if (background) {
    KPolicy policy;
    policy.auto_k = auto_k;
    policy.k_min = k_min;
    policy.k_max = k_max;
    policy.patience = bic_patience;
    policy.split_starts = split_starts;
    policy.fresh_starts = fresh_starts;
    if (!(s = FitBackground(cmd, spec, options, policy, delta, &background_model)).ok()) return Fail(cmd, s.message);
  }
  if (!(s = SaveModel(output, model, provenance ? &record : nullptr, background ? &background_model : nullptr)).ok())
    return Fail(cmd, s.message);
  if (!spec.quiet) std::fprintf(stderr, "gmmrrt-learn fit: wrote %s\n", output.c_str());
  return kExitOk;
}

}  // namespace cli
}  // namespace learn
}  // namespace gmmrrt
