// background_fit.cpp - the background mixture of `gmmrrt-learn fit --background` (background_fit.hpp).
#include "background_fit.hpp"

#include <cstdio>

#include "gmmrrt_learner/bic.hpp"
#include "gmmrrt_learner/mixture.hpp"

namespace gmmrrt {
namespace learn {
namespace cli {

Status FitBackground(const char* cmd, DataSpec spec, const FitOptions& options, const KPolicy& k_policy,
                     double delta, gmmrrt_model_t* out) {
  spec.straight_lines = true;
  Eigen::MatrixXd points;
  uint32_t mask = 0;
  Status s = LoadPoints(cmd, spec, &points, &mask);
  if (!s.ok()) return Status::Error(s.code, "background (straight lines) of " + DescribeData(spec) + ": " + s.message);
  FitOptions o = options;
  o.progress = nullptr;
  Mixture mixture;
  FitSummary summary;
  if (k_policy.auto_k) {
    BicSweepResult sweep;
    s = SweepBic(points, mask, o, k_policy.k_min, k_policy.k_max, &sweep, nullptr, k_policy.patience,
                 k_policy.split_starts, k_policy.fresh_starts);
    mixture = sweep.best;
    summary = sweep.best_summary;
  } else {
    s = FitMixture(points, mask, o, &mixture, &summary);
  }
  if (!s.ok()) return Status::Error(s.code, "background (straight lines) of " + DescribeData(spec) + ": " + s.message);
  if (!spec.quiet)
    std::fprintf(stderr, "gmmrrt-learn %s: background (straight lines): %s\n", cmd, summary.BriefReport().c_str());
  return MixtureToModel(mixture, spec.kind, spec.task, spec.homotopy, delta, out);
}

}  // namespace cli
}  // namespace learn
}  // namespace gmmrrt
