// background_fit.hpp - `gmmrrt-learn fit --background straight`: the task model's background
// mixture (background.hpp), fitted with the same EM options and K policy as the task model and
// stored in the same file (model.h, background section).
#ifndef GMMRRT_LEARN_CLI_BACKGROUND_FIT_HPP
#define GMMRRT_LEARN_CLI_BACKGROUND_FIT_HPP

#include "cli_common.hpp"
#include "gmmrrt_learner/bic.hpp"
#include "gmmrrt_learner/em.hpp"

namespace gmmrrt {
namespace learn {
namespace cli {

// How the task model's K was chosen, to choose the background's the same way.
struct KPolicy {
  bool auto_k = false;  // BIC sweep over k_min..k_max, else options.k
  int k_min = 1, k_max = 30, patience = kBicStopAfterRises, split_starts = kBicSplitStarts,
      fresh_starts = kBicFreshStarts;
};

// Fits the background of spec's episodes (spec.straight_lines set here) with options and the K
// policy, and builds it as a model of spec's kind, task and homotopy with the task model's delta
// (the cost reads delta from the task model; the background's is stored only because every
// model has one). The status names the data on failure.
Status FitBackground(const char* cmd, DataSpec spec, const FitOptions& options, const KPolicy& k_policy,
                     double delta, gmmrrt_model_t* out);

}  // namespace cli
}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARN_CLI_BACKGROUND_FIT_HPP
