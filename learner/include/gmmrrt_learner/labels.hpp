// labels.hpp - the words for tasks and homotopies (model.h, gmmrrt_task_t / gmmrrt_homotopy_t;
// paper Sect. 2: the avoid and approach tasks, passing left, right or head-on), one table for
// every reader and writer of the learner: the command-line flags (--task, --homotopy) and the
// episode CSV's task and homotopy columns (../shared/data/real/README.md). The C core defines
// the values only; their names live here.
#ifndef GMMRRT_LEARNER_LABELS_HPP
#define GMMRRT_LEARNER_LABELS_HPP

#include <string>

#include "gmmrrt_learner/status.hpp"

namespace gmmrrt {
namespace learn {

// "avoid" / "approach" -> gmmrrt_task_t; "all" / "left" / "right" / "frontal" -> gmmrrt_homotopy_t
// ("all", GMMRRT_HOMOTOPY_ALL, is every homotopy in a selection and no label on an episode).
// kInvalidArgument naming the unknown word and the known ones; *out untouched then.
Status ParseTask(const std::string& name, int* task);
Status ParseHomotopy(const std::string& name, int* homotopy);

// The names back: "none" for GMMRRT_TASK_NONE, "unknown" for a value with no name.
const char* TaskName(int task);          // "none", "avoid", "approach" or "unknown"
const char* HomotopyName(int homotopy);  // "all", "left", "right", "frontal" or "unknown"

}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_LABELS_HPP
