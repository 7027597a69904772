// features_csv.hpp - reading user feature vectors for `gmmrrt-learn --features-csv`: one point
// per line, D comma-separated decimal numbers (D = 1..GMMRRT_MAX_DIM, the same on every line).
// Blank lines and lines starting with '#' are skipped; a first line that is not numeric is a
// header and is skipped. Anything else that is not a finite number is an error naming file:line.
#ifndef GMMRRT_LEARNER_FEATURES_CSV_HPP
#define GMMRRT_LEARNER_FEATURES_CSV_HPP

#include <Eigen/Dense>
#include <cstdint>
#include <string>

#include "gmmrrt_learner/status.hpp"

namespace gmmrrt {
namespace learn {

// Reads path into *points (D x N). kIoError when the file cannot be read; kBadInput with
// "path:line: reason" for a malformed, non-finite or wrong-width row; kNotEnoughData when the
// file holds no rows.
Status ReadFeaturesCsv(const std::string& path, Eigen::MatrixXd* points);

// Parses "1,3" (1-based dimension numbers, as a user writes them) into an angle mask for D
// dimensions. kInvalidArgument naming the bad entry.
Status ParseAngleDims(const std::string& text, int dim, uint32_t* mask);

}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_FEATURES_CSV_HPP
