// parallel.hpp (private to learner/src) - running independent tasks on a few threads for the
// E-step sums. Determinism is the caller's part of the contract: each task writes only its own
// slot, and the caller adds the slots up in task order afterwards, so the result is the same
// bits for any thread count (the split into tasks depends on the data size only).
#ifndef GMMRRT_LEARNER_PARALLEL_HPP
#define GMMRRT_LEARNER_PARALLEL_HPP

#include <functional>

namespace gmmrrt {
namespace learn {
namespace detail {

// Runs task(0) .. task(n_tasks - 1), each exactly once, on up to `threads` threads (the
// calling thread is one of them; threads <= 1 or n_tasks <= 1 runs them in order on the caller).
// Tasks are handed out in order from a shared counter; a pool helper that is slow to start
// (asleep, or its CPU taken) is not waited for: its tasks go to the threads that are running (a
// call that finds the pool busy makes its own threads and joins them).
// Returns when all have finished. A task that throws on the calling thread (bad_alloc) ends the
// pass: no task is claimed after it (tasks other threads had claimed run and finish; some may
// come after it in task order), then the exception leaves ParallelFor. A task that throws on
// another thread ends the process (std::terminate), as from any std::thread.
void ParallelFor(int threads, long n_tasks, const std::function<void(long task)>& task);

// Counts of the pool's helper threads since the process started (for tests): passes they joined,
// and times they went to sleep waiting for one.
long PoolHelperJoins();
long PoolHelperSleeps();

// Points per task of the fit's passes over all points outside the E-step (the input's checks and
// copies, the spatial order, the data moments, the hard assignment's sums): fixed, so what is
// summed per task and then added in task order is the same bits for any thread count.
constexpr long kPassTaskPoints = 8192;

// Tasks of kPassTaskPoints points that cover n points.
inline long PassTasks(long n) { return (n + kPassTaskPoints - 1) / kPassTaskPoints; }

// Points [*first, *last) of pass task t over n points: the one rule every pass cuts its tasks by.
template <typename Index>
inline void PassRange(long t, Index n, Index* first, Index* last) {
  *first = static_cast<Index>(t) * static_cast<Index>(kPassTaskPoints);
  *last = n < *first + static_cast<Index>(kPassTaskPoints) ? n : *first + static_cast<Index>(kPassTaskPoints);
}

// CPUs this process may run on (sched_getaffinity), at least 1: the default thread count.
int AvailableCores();

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_PARALLEL_HPP
