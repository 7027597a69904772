// cmd_inspect.cpp - `gmmrrt-learn inspect MODEL`: validates a model file through the C loader
// (model.h: magic, version, sizes, CRC-32, finite numbers, positive-definite factors, weights)
// and prints it: kind, task, homotopy, D, K, delta, angle dimensions, then each component; with
// --json, the same as one JSON object for scripts.
#include <getopt.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gmmrrt_learner/episode_features.hpp"
#include "gmmrrt_learner/mixture.hpp"
#include "nlohmann/json.hpp"

namespace gmmrrt {
namespace learn {
namespace cli {

namespace {
const char kInspectHelp[] =
    "usage: gmmrrt-learn inspect [--json] MODEL\n"
    "\n"
    "Validates MODEL and prints its header and components (weight, mean, standard deviations,\n"
    "correlations, and the Cholesky factor L of the covariance, Sigma = L L^T).\n"
    "  -j, --json   print one JSON object instead: model, kind, task, homotopy, dim, k, delta,\n"
    "               angle_dims (1-based), components [{weight, mean, covariance, chol}],\n"
    "               provenance (the learner's record: data SHA-256, command line, seed, K,\n"
    "               BIC, log-likelihood, version, UTC time; null when the file has none)\n"
    "Exit status: 0 valid; 1 not a valid model (the reason is printed); 2 usage error.\n";
}  // namespace

int RunInspect(int argc, char** argv) {
  const char* cmd = "inspect";
  static const struct option kLong[] = {
      {"help", no_argument, nullptr, 'h'}, {"json", no_argument, nullptr, 'j'}, {nullptr, 0, nullptr, 0}};
  optind = 1;
  int c;
  bool json = false;
  while ((c = getopt_long(argc, argv, "hj", kLong, nullptr)) != -1) {
    if (c == 'h') {
      std::fputs(kInspectHelp, stdout);
      return kExitOk;
    }
    if (c == 'j') {
      json = true;
      continue;
    }
    return UsageError(cmd, "unknown option");
  }
  if (argc - optind != 1) return UsageError(cmd, "give exactly one MODEL");
  const std::string path = argv[optind];
  gmmrrt_model_t model;
  std::string provenance_text;
  Status s = LoadModel(path, &model, &provenance_text);
  if (!s.ok()) return Fail(cmd, "invalid model: " + s.message);
  // The background section's K (0: none), for gmmrrt-plan --task-cost background.
  int background_k = 0;
  if (!(s = BackgroundK(path, &background_k)).ok()) return Fail(cmd, "invalid model: " + s.message);
  // The learner writes a JSON object; any other text (another writer's) is shown as a string.
  nlohmann::ordered_json provenance = nullptr;
  if (!provenance_text.empty()) {
    provenance = nlohmann::ordered_json::parse(provenance_text, nullptr, false);
    if (provenance.is_discarded()) provenance = provenance_text;
  }

  if (json) {
    const Mixture mj = MixtureFromModel(model);
    nlohmann::ordered_json out;
    out["model"] = path;
    out["kind"] = KindName(model.kind);
    out["task"] = TaskName(model.task);
    out["homotopy"] = HomotopyName(model.homotopy);
    out["dim"] = model.dim;
    out["k"] = model.k;
    out["delta"] = model.delta;
    out["angle_dims"] = nlohmann::json::array();
    for (int j = 0; j < model.dim; ++j)
      if ((model.angle_mask >> j) & 1u) out["angle_dims"].push_back(j + 1);
    out["components"] = nlohmann::json::array();
    for (int i = 0; i < mj.k(); ++i) {
      const Eigen::MatrixXd cov = mj.chol[i] * mj.chol[i].transpose();
      nlohmann::ordered_json comp;
      comp["weight"] = mj.weights[i];
      comp["mean"] = std::vector<double>(mj.means.col(i).data(), mj.means.col(i).data() + mj.dim);
      std::vector<std::vector<double>> c_rows(mj.dim), l_rows(mj.dim);
      for (int r = 0; r < mj.dim; ++r)
        for (int col = 0; col < mj.dim; ++col) {
          c_rows[r].push_back(cov(r, col));
          l_rows[r].push_back(mj.chol[i](r, col));
        }
      comp["covariance"] = c_rows;
      comp["chol"] = l_rows;
      out["components"].push_back(comp);
    }
    out["background_k"] = background_k;
    out["provenance"] = provenance;
    // 17 significant digits: the doubles of the file round-trip exactly.
    std::printf("%s\n", out.dump(1).c_str());
    return kExitOk;
  }
  std::printf("model    %s\n", path.c_str());
  std::printf("kind     %s\n", KindName(model.kind));
  std::printf("task     %s\n", TaskName(model.task));
  std::printf("homotopy %s\n", HomotopyName(model.homotopy));
  std::printf("D        %d\n", model.dim);
  std::printf("K        %d\n", model.k);
  std::printf("delta    %.6g\n", model.delta);
  std::printf("angles  ");
  bool any = false;
  for (int j = 0; j < model.dim; ++j)
    if ((model.angle_mask >> j) & 1u) {
      std::printf(" %d", j + 1);
      any = true;
    }
  std::printf("%s\n", any ? " (1-based dimensions, wrapped)" : " none");
  if (background_k > 0)
    std::printf("background K = %d (a mixture over the episodes' straight lines, for --task-cost background)\n",
                background_k);
  else
    std::printf("background none\n");
  if (provenance.is_object()) {
    std::printf("provenance\n");
    for (const auto& item : provenance.items())
      std::printf("  %-20s %s\n", item.key().c_str(),
                  item.value().is_string() ? item.value().get<std::string>().c_str()
                                           : item.value().dump(-1, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
  } else if (provenance.is_string()) {
    std::printf("provenance %s\n", provenance.get<std::string>().c_str());
  } else {
    std::printf("provenance none (the file has no provenance trailer)\n");
  }
  const Mixture m = MixtureFromModel(model);
  for (int i = 0; i < m.k(); ++i) {
    const Eigen::MatrixXd cov = m.chol[i] * m.chol[i].transpose();
    std::printf("component %d  weight %.6f\n  mean   ", i, m.weights[i]);
    for (int j = 0; j < m.dim; ++j) std::printf(" %12.6f", m.means(j, i));
    std::printf("\n  stddev ");
    for (int j = 0; j < m.dim; ++j) std::printf(" %12.6f", std::sqrt(cov(j, j)));
    std::printf("\n");
    for (int r = 1; r < m.dim; ++r) {
      std::printf("  corr %d ", r + 1);
      for (int col = 0; col < r; ++col) std::printf(" %12.6f", cov(r, col) / std::sqrt(cov(r, r) * cov(col, col)));
      std::printf("\n");
    }
    for (int r = 0; r < m.dim; ++r) {
      std::printf("  L row %d", r + 1);
      for (int col = 0; col <= r; ++col) std::printf(" %12.6g", m.chol[i](r, col));
      std::printf("\n");
    }
  }
  return kExitOk;
}

}  // namespace cli
}  // namespace learn
}  // namespace gmmrrt
