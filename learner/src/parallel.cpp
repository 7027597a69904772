// parallel.cpp - ParallelFor, ParallelSession and AvailableCores (contract in parallel.hpp).
//
// The helper threads are kept between calls: a fit makes about a hundred parallel passes (each
// E-step, k-means assignment, update and seeding step), and starting and joining threads for
// each cost 20-200 microseconds a pass on the 2-core development machine (more under load),
// a few percent of a 50 ms fit and the part that did not shrink with a second core. A call that
// finds the pool busy (another thread's pass, or a pass started from inside a task) or runs in
// a process forked after the pool started takes its own threads as before.
//
// A pass is handed over without a lock: the caller publishes the pass and then bumps the
// generation; a polling helper sees the generation and starts. Locks and condition variables
// are only for threads that went to sleep. That matters beyond the cost of a system call:
// Linux puts a thread woken by another on the waker's CPU when it can (wake-affine placement),
// so a helper woken for a pass, or blocked for a moment on a mutex the caller holds, starts
// its share on the caller's CPU, and the two share one CPU until the load balancer moves one.
// On the benchmark fit with 2 threads the helper slept between 65 and 90 of a fit's 85-100
// passes, and started on the caller's CPU in 77-96 of them (docs/learner.md). Hence
// ParallelSession: while one is open the threads do not sleep between passes.
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

// Open ParallelSessions of more than one thread, in the whole process.
std::atomic<int> open_sessions{0};

// How long a pool thread polls before it sleeps when no session is open: for the helpers, after
// a pass, for the next one; for the caller, at the end of a pass, for the helpers' last tasks.
// Short, so that an idle pool costs nothing after it (100 us gave the same wall time on the
// benchmark fit for more CPU: docs/learner.md).
constexpr auto kPollFor = std::chrono::microseconds(20);

inline void CpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#else
  std::this_thread::yield();
#endif
}

// Polls done() until it holds, or for kPollFor while no session is open; true when it held.
template <typename F>
bool PollUntil(const F& done) {
  auto until = std::chrono::steady_clock::now() + kPollFor;
  for (unsigned i = 1;; ++i) {
    if (done()) return true;
    CpuRelax();
    if (i % 64 == 0) {
      const auto now = std::chrono::steady_clock::now();
      if (open_sessions.load(std::memory_order_relaxed) > 0)
        until = now + kPollFor;  // the poll's limit starts when the last session closes
      else if (now > until)
        return done();
    }
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
    bool wake;
    {
      std::lock_guard<std::mutex> lock(m_);
      const uint64_t published = generation_.load(std::memory_order_relaxed);
      while (static_cast<int>(threads_.size()) < helpers) {
        const int id = static_cast<int>(threads_.size());
        threads_.emplace_back([this, id, published] { Work(id, published); });
        threads_.back().detach();
      }
    }
    // The pass is published as a sequence lock: an odd generation while its fields are written,
    // the next even one when they are complete. A wanted helper is waited for (active_), so the
    // fields change only when every wanted helper of the last pass has counted out; a helper the
    // last pass did not want may still be reading them, and tells by the generation.
    // (Release stores: a helper that reads a new field's value also sees the odd generation.)
    generation_.store(generation_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
    task_.store(&task, std::memory_order_release);
    n_tasks_.store(n_tasks, std::memory_order_release);
    next_.store(0, std::memory_order_release);
    helpers_.store(helpers, std::memory_order_release);
    active_.store(helpers, std::memory_order_release);
    {
      std::lock_guard<std::mutex> lock(m_);
      // Under m_, so that a helper about to sleep either sees it or is already waiting.
      generation_.store(generation_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
      wake = sleeping_ > 0;
    }
    if (wake) wake_.notify_all();
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
    if (!PollUntil([this] { return active_.load(std::memory_order_acquire) == 0; })) {
      std::unique_lock<std::mutex> lock(m_);
      done_.wait(lock, [this] { return active_.load(std::memory_order_acquire) == 0; });
    }
    if (failed) std::rethrow_exception(failed);
    return true;
  }

  long Sleeps() const { return sleeps_.load(); }

 private:
  // A helper thread: `seen` is the last generation it has acted on (at first, the one published
  // when it was made: it was made for the next pass).
  void Work(int id, uint64_t seen) {
    in_pool_task = true;
    for (;;) {
      const auto started = [this, &seen] {
        const uint64_t g = generation_.load(std::memory_order_acquire);
        return g != seen && g % 2 == 0;
      };
      if (!PollUntil(started)) {
        std::unique_lock<std::mutex> lock(m_);
        ++sleeping_;
        if (!started()) sleeps_.fetch_add(1);
        wake_.wait(lock, started);
        --sleeping_;
      }
      const uint64_t g = generation_.load(std::memory_order_acquire);
      if (g == seen || g % 2 != 0) continue;
      const int helpers = helpers_.load(std::memory_order_acquire);
      const long n_tasks = n_tasks_.load(std::memory_order_acquire);
      const std::function<void(long task)>* task = task_.load(std::memory_order_acquire);
      if (generation_.load(std::memory_order_relaxed) != g) continue;  // rewritten meanwhile
      seen = g;
      if (id >= helpers) continue;  // not wanted for this pass
      // Wanted: the pass cannot end, nor its fields change, before this thread counts out.
      RunTasks(&next_, n_tasks, *task);
      if (active_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        std::lock_guard<std::mutex> lock(m_);  // the caller checks active_ under m_ before it sleeps
        done_.notify_one();
      }
    }
  }

  const pid_t pid_ = getpid();
  std::mutex busy_;  // held for a whole pass
  std::mutex m_;     // guards threads_ and sleeping_, and orders sleeping against waking
  std::condition_variable wake_, done_;
  std::vector<std::thread> threads_;
  int sleeping_ = 0;             // helpers waiting on wake_
  std::atomic<long> sleeps_{0};  // times a helper went to sleep (for tests)
  // The pass, published by the generation (TryRun).
  std::atomic<const std::function<void(long task)>*> task_{nullptr};
  std::atomic<long> n_tasks_{0};
  std::atomic<long> next_{0};
  std::atomic<int> helpers_{0};
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

ParallelSession::ParallelSession(int threads) : open_(threads > 1 && threads <= AvailableCores()) {
  if (open_) open_sessions.fetch_add(1);
}

ParallelSession::~ParallelSession() {
  if (open_) open_sessions.fetch_sub(1);
}

long PoolHelperSleeps() { return ThePool().Sleeps(); }

int AvailableCores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1u, std::thread::hardware_concurrency());
}

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt
