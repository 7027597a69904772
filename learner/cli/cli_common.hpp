// cli_common.hpp - what the gmmrrt-learn subcommands share: strict number parsing, loading the
// data points a command works on (episode files filtered by task / homotopy / split, or a
// features CSV), and model file access through gmmrrt_io (atomic save, validating load).
#ifndef GMMRRT_LEARN_CLI_COMMON_HPP
#define GMMRRT_LEARN_CLI_COMMON_HPP

#include <Eigen/Dense>
#include <cstdint>
#include <string>
#include <vector>

#include "gmmrrt/model.h"
#include "gmmrrt_learner/mixture.hpp"
#include "gmmrrt_learner/status.hpp"

namespace gmmrrt {
namespace learn {
namespace cli {

constexpr int kExitOk = 0;
constexpr int kExitError = 1;  // bad data, unreadable file, failed fit
constexpr int kExitUsage = 2;  // bad command line

// Prints "gmmrrt-learn <cmd>: error: <message>" on stderr and returns kExitError.
int Fail(const char* cmd, const std::string& message);
// Same with a hint to --help; returns kExitUsage.
int UsageError(const char* cmd, const std::string& message);

// Whole-string conversions; false when text is not entirely a number in range.
bool ParseInt(const std::string& text, long min, long max, long* out);
bool ParseUint64(const std::string& text, uint64_t* out);
bool ParseDouble(const std::string& text, double* out);  // finite only

// What to read: either episode files or one features CSV.
struct DataSpec {
  std::vector<std::string> inputs;   // episode CSVs / LCM demonstration logs
  std::vector<std::string> indexes;  // index CSVs with a split column
  std::string split;                 // "train" / "test" / "" (all)
  int task = GMMRRT_TASK_NONE;
  int homotopy = GMMRRT_HOMOTOPY_ALL;
  int kind = GMMRRT_MODEL_KIND_FEATURES;  // features or xy for episodes
  std::string features_csv;          // kind generic
  uint32_t angle_mask = 0;           // for features_csv
  bool straight_lines = false;       // each episode's straight line instead (background.hpp)
  bool quiet = false;
};

// Reads and converts the data of spec into points (D x N) and their angle mask. Warnings of the
// readers go to stderr unless quiet; counts of episodes and points too.
Status LoadPoints(const char* cmd, const DataSpec& spec, Eigen::MatrixXd* points, uint32_t* angle_mask);

// The data of spec in a few words for error messages: the features CSV, or the episode files
// with the task, homotopy and split chosen.
std::string DescribeData(const DataSpec& spec);

// Loads and validates a model file into *model (scratch copy first, as model.h asks); with
// provenance, its provenance text too ("" when the file has none or an empty one).
Status LoadModel(const std::string& path, gmmrrt_model_t* model, std::string* provenance = nullptr);

// The K of the file's background model (model.h, background section) into *k, 0 when it has none.
Status BackgroundK(const std::string& path, int* k);

// Encodes and writes atomically (temporary file + rename; nothing left behind on failure).
// With provenance, the file ends with a provenance trailer holding it (model.h); with background,
// the file carries it as the model's background section (model.h).
Status SaveModel(const std::string& path, const gmmrrt_model_t& model, const std::string* provenance = nullptr,
                 const gmmrrt_model_t* background = nullptr);

}  // namespace cli
}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARN_CLI_COMMON_HPP
