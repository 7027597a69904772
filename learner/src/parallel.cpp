// parallel.cpp - ParallelFor and AvailableCores (contract in parallel.hpp).
//
// The helper threads are kept between calls: a fit makes about a hundred parallel passes (each
// E-step, k-means assignment, update and seeding step), and starting and joining threads for
// each cost 20-200 microseconds a pass on the 2-core development machine (more under load),
// a few percent of a 50 ms fit and the part that did not shrink with a second core. A call that
// finds the pool busy (another thread's pass, or a pass started from inside a task) or runs in
// a process forked after the pool started takes its own threads as before.
#include "parallel.hpp"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace gmmrrt {
namespace learn {
namespace detail {

namespace {

thread_local bool in_pool_task = false;

// How long a pool thread polls before it sleeps: for the helpers, after a pass, for the next one;
// for the caller, at the end of a pass, for the helpers' last tasks. A fit's passes follow one
// another with little serial work between them (a few to tens of microseconds), and waking a
// sleeping thread through the scheduler costs more on a virtual machine (an idle vCPU is
// halted); the polling is bounded so that an idle pool costs nothing after it, and short (100 us
// gave the same wall time on the benchmark fit for more CPU: docs/learner.md).
constexpr auto kPollFor = std::chrono::microseconds(20);

inline void CpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#else
  std::this_thread::yield();
#endif
}

// Polls done() for up to kPollFor; true when it held.
template <typename F>
bool PollUntil(const F& done) {
  const auto until = std::chrono::steady_clock::now() + kPollFor;
  for (unsigned i = 1;; ++i) {
    if (done()) return true;
    CpuRelax();
    if (i % 64 == 0 && std::chrono::steady_clock::now() > until) return done();
  }
}

void RunTasks(std::atomic<long>* next, long n_tasks, const std::function<void(long task)>& task) {
  for (long t = next->fetch_add(1); t < n_tasks; t = next->fetch_add(1)) task(t);
}

// Helper threads waiting for passes. Never destroyed (a static destructor would have to join
// threads that may be blocked at exit); the threads end with the process.
class Pool {
 public:
  // Runs the pass with up to `helpers` pool threads beside the caller; false (nothing run) when
  // the pool is in use or belongs to another process (fork).
  bool TryRun(int helpers, long n_tasks, const std::function<void(long task)>& task) {
    if (in_pool_task || getpid() != pid_) return false;
    std::unique_lock<std::mutex> busy(busy_, std::try_to_lock);
    if (!busy.owns_lock()) return false;
    std::unique_lock<std::mutex> lock(m_);
    while (static_cast<int>(threads_.size()) < helpers) {
      const int id = static_cast<int>(threads_.size());
      threads_.emplace_back([this, id] { Work(id); });
      threads_.back().detach();
    }
    task_ = &task;
    n_tasks_ = n_tasks;
    next_.store(0);
    helpers_ = helpers;
    active_.store(helpers);
    generation_.store(generation_.load() + 1);
    lock.unlock();
    wake_.notify_all();
    // A task that throws on this thread ends only this thread's share: the helpers still hold
    // `task` (the caller's) and the pass's counters, so the exception waits for them before it
    // leaves, and the pool is whole for the next pass. (A throw on a helper ends the process,
    // as it did from a std::thread.)
    std::exception_ptr failed;
    in_pool_task = true;
    try {
      RunTasks(&next_, n_tasks, task);
    } catch (...) {
      failed = std::current_exception();
    }
    in_pool_task = false;
    PollUntil([this] { return active_.load() == 0; });
    lock.lock();
    done_.wait(lock, [this] { return active_.load() == 0; });
    task_ = nullptr;
    if (failed) std::rethrow_exception(failed);
    return true;
  }

 private:
  void Work(int id) {
    in_pool_task = true;
    uint64_t seen = 0;
    for (;;) {
      PollUntil([this, seen] { return generation_.load() != seen; });
      std::unique_lock<std::mutex> lock(m_);
      wake_.wait(lock, [this, seen] { return generation_.load() != seen; });
      seen = generation_.load();
      if (id >= helpers_) continue;  // not wanted for this pass
      const std::function<void(long task)>* task = task_;
      const long n_tasks = n_tasks_;
      lock.unlock();
      RunTasks(&next_, n_tasks, *task);
      lock.lock();
      if (active_.fetch_sub(1) == 1) done_.notify_one();
    }
  }

  const pid_t pid_ = getpid();
  std::mutex busy_;  // held for a whole pass
  std::mutex m_;     // guards the fields below
  std::condition_variable wake_, done_;
  std::vector<std::thread> threads_;
  const std::function<void(long task)>* task_ = nullptr;
  long n_tasks_ = 0;
  std::atomic<long> next_{0};
  int helpers_ = 0;
  // Written under m_; also polled without it (PollUntil), hence atomic.
  std::atomic<int> active_{0};  // wanted helpers still running this pass
  std::atomic<uint64_t> generation_{0};
};

Pool& ThePool() {
  static Pool* pool = new Pool;  // never deleted: see Pool
  return *pool;
}

}  // namespace

void ParallelFor(int threads, long n_tasks, const std::function<void(long task)>& task) {
  const long workers = std::min<long>(std::max(threads, 1), n_tasks);
  if (workers <= 1) {
    for (long t = 0; t < n_tasks; ++t) task(t);
    return;
  }
  if (ThePool().TryRun(static_cast<int>(workers - 1), n_tasks, task)) return;
  std::atomic<long> next{0};
  auto work = [&next, n_tasks, &task]() { RunTasks(&next, n_tasks, task); };
  std::vector<std::thread> pool;
  pool.reserve(static_cast<size_t>(workers - 1));
  for (long w = 1; w < workers; ++w) pool.emplace_back(work);
  std::exception_ptr failed;  // as in the pool: a throw here waits for the other threads
  try {
    work();
  } catch (...) {
    failed = std::current_exception();
  }
  for (std::thread& t : pool) t.join();
  if (failed) std::rethrow_exception(failed);
}

int AvailableCores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1u, std::thread::hardware_concurrency());
}

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt
