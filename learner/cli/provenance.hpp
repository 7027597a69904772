// provenance.hpp - the provenance record `gmmrrt-learn fit` stores in a model file's trailer
// (model.h, docs/model-format.md, docs/learner.md): a JSON object naming the training data by
// SHA-256, the command line, seed, K, BIC, log-likelihood, learner version and UTC time.
#ifndef GMMRRT_LEARN_PROVENANCE_HPP
#define GMMRRT_LEARN_PROVENANCE_HPP

#include <cstdint>
#include <string>
#include <vector>

#include "gmmrrt_learner/status.hpp"

namespace gmmrrt {
namespace learn {
namespace cli {

// SHA-256 of the file's bytes (nettle), as 64 lower-case hex digits, and its size.
Status Sha256File(const std::string& path, std::string* hex, uint64_t* bytes);

struct FitRecord {
  std::vector<std::string> command_line;  // argv, program name first
  std::vector<std::string> data_files;    // training data in the order read (inputs or features CSV)
  std::vector<std::string> index_files;   // index CSVs that chose the split (may be empty)
  uint64_t seed = 0;
  bool k_auto = false;
  int k = 0;
  int64_t points = 0;
  int dim = 0;
  double bic = 0.0;
  double mean_log_likelihood = 0.0;
  int iterations = 0;
  bool converged = false;
  double delta = 0.0;
};

// The record as compact JSON, at most GMMRRT_MAX_PROVENANCE_BYTES bytes: hashes every file (an
// unreadable file is an error naming it); when too long, drops the per-file list, then shortens
// the command line, and says so ("data_files_omitted", "command_line_truncated"). The time is
// now, or SOURCE_DATE_EPOCH when set (reproducible outputs).
Status ProvenanceJson(const FitRecord& record, std::string* json);

}  // namespace cli
}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARN_PROVENANCE_HPP
