// labels.cpp - the task and homotopy words (labels.hpp): one table each, read both ways.
#include "gmmrrt_learner/labels.hpp"

#include <cstddef>

#include "gmmrrt/model.h"

namespace gmmrrt {
namespace learn {
namespace {

struct Label {
  const char* text;
  int value;
};

constexpr Label kTasks[] = {{"avoid", GMMRRT_TASK_AVOID}, {"approach", GMMRRT_TASK_APPROACH}};
constexpr Label kHomotopies[] = {{"all", GMMRRT_HOMOTOPY_ALL},
                                 {"left", GMMRRT_HOMOTOPY_LEFT},
                                 {"right", GMMRRT_HOMOTOPY_RIGHT},
                                 {"frontal", GMMRRT_HOMOTOPY_FRONTAL}};

template <std::size_t N>
Status Parse(const Label (&labels)[N], const char* what, const std::string& name, int* out) {
  std::string known;
  for (const Label& l : labels) {
    if (name == l.text) {
      *out = l.value;
      return Status::Ok();
    }
    known += (known.empty() ? "" : ", ") + std::string(l.text);
  }
  return Status::Error(StatusCode::kInvalidArgument,
                       std::string("unknown ") + what + " '" + name + "' (known: " + known + ")");
}

template <std::size_t N>
const char* Name(const Label (&labels)[N], int value) {
  for (const Label& l : labels)
    if (l.value == value) return l.text;
  return "unknown";
}

}  // namespace

Status ParseTask(const std::string& name, int* task) { return Parse(kTasks, "task", name, task); }

Status ParseHomotopy(const std::string& name, int* homotopy) {
  return Parse(kHomotopies, "homotopy", name, homotopy);
}

const char* TaskName(int task) { return task == GMMRRT_TASK_NONE ? "none" : Name(kTasks, task); }

const char* HomotopyName(int homotopy) { return Name(kHomotopies, homotopy); }

}  // namespace learn
}  // namespace gmmrrt
