// json_import.hpp - a mixture given as priors, means and covariances in JSON, for
// `gmmrrt-learn import --json`. Two shapes are read:
//   1. the lab's published approach models (../shared/data/real/upo_approach_gmms.json):
//      {"sets": {SET: {TASK_NAME: {"components": [{"weight", "mean", "cov"}, ...]}}}}, one task
//      picked by set and task name (e.g. set "tasks", task "1-front");
//   2. a plain mixture: {"priors": [K], "means": [K][D], "covs": [K][D][D]} (no names needed).
// Covariances are Cholesky-factorised here (Sigma = L L^T, as model.h stores them); one that is
// not symmetric or not positive definite is an error naming the component. Parsing uses
// nlohmann-json (no hand-written parser).
#ifndef GMMRRT_LEARNER_JSON_IMPORT_HPP
#define GMMRRT_LEARNER_JSON_IMPORT_HPP

#include <cstdint>
#include <string>

#include "gmmrrt_learner/mixture.hpp"
#include "gmmrrt_learner/status.hpp"

namespace gmmrrt {
namespace learn {

struct JsonImportOptions {
  std::string set = "tasks";  // shape 1: which "sets" entry
  std::string task_name;      // shape 1: which task in it (required there)
  uint32_t angle_mask = 0;    // dimensions that are wrapped angles (their means get wrapped)
};

// Reads path into *out (validated, weights renormalised when their sum is within 1e-6 of 1).
// A task flagged "two_homotopies": true holds two concatenated mixtures whose priors sum to 2;
// it is imported as their equal-weight union (weights / 2) and *note (may be null) says so.
// kIoError: unreadable; kBadInput: not JSON or the wrong shape (the message says which key and,
// for an unknown set or task, lists the known ones); kBadModel: a covariance that is not
// symmetric positive definite or a bad weight, naming the component.
Status ImportJsonMixture(const std::string& path, const JsonImportOptions& options, Mixture* out,
                         std::string* note = nullptr);

}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_JSON_IMPORT_HPP
