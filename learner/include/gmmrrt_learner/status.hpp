// status.hpp - the learner's status: a code plus a message, returned instead of thrown
// (the Ceres style of ../shared/STYLE.md item 11). No exception crosses the learner API.
#ifndef GMMRRT_LEARNER_STATUS_HPP
#define GMMRRT_LEARNER_STATUS_HPP

#include <string>
#include <utility>

namespace gmmrrt {
namespace learn {

enum class StatusCode {
  kOk = 0,
  kInvalidArgument,  // an option or argument out of range (the message names it)
  kNotEnoughData,    // no points, or fewer points than the model needs
  kBadInput,         // unparsable or non-finite input; the message names file and line
  kIoError,          // a file could not be opened, read or written
  kBadModel,         // a model that fails validation (not positive definite, bad weights, ...)
  kNumericalFailure  // the fit produced no usable mixture (e.g. every component degenerate)
};

struct Status {
  StatusCode code = StatusCode::kOk;
  std::string message;

  bool ok() const { return code == StatusCode::kOk; }
  static Status Ok() { return Status(); }
  static Status Error(StatusCode c, std::string msg) {
    Status s;
    s.code = c;
    s.message = std::move(msg);
    return s;
  }
};

}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_STATUS_HPP
