// parallel.cpp - ParallelFor and AvailableCores (contract in parallel.hpp).
//
// The helper threads are kept between calls: a fit makes about a hundred parallel passes (each
// E-step, k-means assignment, update and seeding step), and starting and joining threads for
// each cost 20-200 microseconds a pass on the 2-core development machine (more under load),
// a few percent of a 50 ms fit and the part that did not shrink with a second core. A call that
// finds the pool busy (another thread's pass, or a pass started from inside a task) or runs in
// a process forked after the pool started takes its own threads as before.
//
// Helpers join a pass; the caller waits only for those that joined. A helper that slept is woken
// through the scheduler, which on this 2-CPU virtual machine took about 250 us a pass on the
// benchmark fit (measured: docs/learner.md), longer than many of a fit's passes; a caller that
// waited for it would run those passes at one thread's speed plus the wake-up. Now the caller
// runs the pass with whoever is there, and a late helper joins what is left, or nothing. No
// thread takes a lock on the way of a pass unless a thread is asleep or is to be made (a thread
// blocked on a taken mutex is woken through the scheduler too, and Linux puts it on the waker's
// CPU).
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
#include <new>
#include <system_error>
#include <thread>
#include <vector>

namespace gmmrrt {
namespace learn {
namespace detail {

namespace {

using Task = std::function<void(long task)>;

thread_local bool in_pool_task = false;

// How long a thread polls before it sleeps: a helper, after a pass, for the next one; the
// caller, at the end of a pass, for the joined helpers' last tasks. A fit's passes follow one
// another with a few to tens of microseconds of serial work between them. Short and bounded,
// so an idle pool costs nothing after it, and so that a polling thread takes little from the
// other CPU: longer polls (100 us to 1 ms, or polling through a whole fit) were no faster on
// this machine, and polling through a fit was slower (docs/learner.md).
constexpr auto kPollFor = std::chrono::microseconds(20);

inline void CpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#else
  std::this_thread::yield();
#endif
}

// Polls done() for up to kPollFor; true when it held.
template <typename Done>
bool PollUntil(const Done& done) {
  const auto until = std::chrono::steady_clock::now() + kPollFor;
  for (unsigned i = 1;; ++i) {
    if (done()) return true;
    CpuRelax();
    if (i % 64 == 0 && std::chrono::steady_clock::now() > until) return done();
  }
}

// Runs the tasks left in the pass (claimed from *next) on this thread. On the caller (failed set)
// a throwing task ends the pass: the exception is kept and the counter is moved past the end,
// so that no task is claimed after it (tasks other threads have claimed still run and finish).
// On a helper a throw ends the process.
void RunTasks(std::atomic<long>* next, long n_tasks, const Task* task, std::exception_ptr* failed) {
  for (long t = next->fetch_add(1); t < n_tasks; t = next->fetch_add(1)) {
    if (failed == nullptr) {
      (*task)(t);
      continue;
    }
    try {
      (*task)(t);
    } catch (...) {
      *failed = std::current_exception();
      next->store(n_tasks);
      return;
    }
  }
}

// Helper threads waiting for passes. Never destroyed (a static destructor would have to join
// threads that may be blocked at exit); the threads end with the process.
//
// A pass is published as a sequence lock: the generation is odd while the caller writes its
// fields, the next even number when they are complete. A helper joins a pass by counting itself
// into joined_ and then finding the generation unchanged; the caller, before it writes the next
// pass's fields, makes the generation odd and waits until no helper is counted in (a helper that
// counted in after that sees the odd generation and counts out without touching anything). So
// the fields never change under a joined helper, and a helper that joins late finds the task
// counter past the end and runs nothing.
class Pool {
 public:
  // Runs the pass with up to `helpers` pool threads beside the caller; false (nothing run) when
  // the pool is in use or belongs to another process (fork).
  bool TryRun(int helpers, long n_tasks, const Task& task) {
    if (in_pool_task || getpid() != pid_) return false;
    std::unique_lock<std::mutex> busy(busy_, std::try_to_lock);
    if (!busy.owns_lock()) return false;
    // threads_ grows only here, under busy_; m_ is taken only when a thread is to be made.
    if (made_.load() < helpers) {
      std::lock_guard<std::mutex> lock(m_);
      const uint64_t published = generation_.load();
      try {
        while (static_cast<int>(threads_.size()) < helpers) {
          const int id = static_cast<int>(threads_.size());
          threads_.emplace_back([this, id, published] { Work(id, published); });
          threads_.back().detach();
          made_.store(static_cast<int>(threads_.size()));
        }
      } catch (const std::system_error&) {  // no more threads: run with those there are
      } catch (const std::bad_alloc&) {     // no memory for one more: the same
      }
    }
    helpers = std::min(helpers, made_.load());
    if (helpers == 0) return false;
    generation_.fetch_add(1);  // odd: the fields are being written
    WaitUntilNoneJoined();     // late joiners of the last pass count out
    task_.store(&task);
    n_tasks_.store(n_tasks);
    next_.store(0);
    helpers_.store(helpers);
    generation_.fetch_add(1);  // even: published
    if (sleeping_.load() > 0) {
      // A helper counts itself asleep under m_ before it looks at the generation a last time:
      // taking m_ here waits until it is in wait(), so the notification cannot come too early.
      { std::lock_guard<std::mutex> lock(m_); }
      wake_.notify_all();
    }
    std::exception_ptr failed;
    in_pool_task = true;
    RunTasks(&next_, n_tasks, &task, &failed);
    in_pool_task = false;
    WaitUntilNoneJoined();  // every task is claimed; joined helpers finish theirs
    if (failed) std::rethrow_exception(failed);
    return true;
  }

  long Joins() const { return joins_.load(); }
  long Sleeps() const { return sleeps_.load(); }

 private:
  // Waits until no helper is counted into a pass: polling first, then asleep on done_ (the last
  // helper out wakes a caller that counted itself asleep, the same way as wake_ above).
  void WaitUntilNoneJoined() {
    const auto done = [this] { return joined_.load() == 0; };
    if (PollUntil(done)) return;
    std::unique_lock<std::mutex> lock(m_);
    caller_sleeping_.store(true);
    done_.wait(lock, done);
    caller_sleeping_.store(false);
  }

  // A helper thread: `seen` is the last generation it has looked at (at first, the one published
  // when it was made: it was made for the next pass).
  void Work(int id, uint64_t seen) {
    in_pool_task = true;
    const auto published = [this, &seen] {
      const uint64_t g = generation_.load();
      return g != seen && g % 2 == 0;
    };
    for (;;) {
      if (!PollUntil(published)) {
        std::unique_lock<std::mutex> lock(m_);
        sleeping_.fetch_add(1);
        if (!published()) sleeps_.fetch_add(1);
        wake_.wait(lock, published);
        sleeping_.fetch_sub(1);
      }
      const uint64_t g = generation_.load();
      if (g == seen || g % 2 != 0) continue;
      seen = g;
      joined_.fetch_add(1);
      if (generation_.load() == g && id < helpers_.load()) {
        joins_.fetch_add(1, std::memory_order_relaxed);
        RunTasks(&next_, n_tasks_.load(), task_.load(), nullptr);
      }
      if (joined_.fetch_sub(1) == 1 && caller_sleeping_.load()) {
        { std::lock_guard<std::mutex> lock(m_); }  // as for wake_: the caller is in wait()
        done_.notify_one();
      }
    }
  }

  const pid_t pid_ = getpid();
  std::mutex busy_;  // held for a whole pass
  std::mutex m_;     // guards threads_' growth; orders going to sleep against waking (above)
  std::condition_variable wake_, done_;
  std::vector<std::thread> threads_;
  std::atomic<int> made_{0};  // threads_.size()
  std::atomic<long> joins_{0}, sleeps_{0};
  // The pass (published by the generation, above) and the sleepers. Sequentially consistent
  // atomics throughout: the handshakes (count in, then read the generation, against: make it
  // odd, then read the count; count asleep, then read the generation, against: publish, then
  // read the sleepers) need it, and the cost is nothing next to a pass.
  std::atomic<const Task*> task_{nullptr};
  std::atomic<long> n_tasks_{0};
  std::atomic<long> next_{0};
  std::atomic<int> helpers_{0};
  std::atomic<int> joined_{0};               // helpers in the current pass
  std::atomic<uint64_t> generation_{0};
  std::atomic<int> sleeping_{0};             // helpers asleep on wake_ (counted under m_)
  std::atomic<bool> caller_sleeping_{false};  // the caller asleep on done_ (set under m_)
};

Pool& ThePool() {
  static Pool* pool = new Pool;  // never deleted: see Pool
  return *pool;
}

}  // namespace

void ParallelFor(int threads, long n_tasks, const Task& task) {
  const long workers = std::min<long>(std::max(threads, 1), n_tasks);
  if (workers <= 1) {
    for (long t = 0; t < n_tasks; ++t) task(t);
    return;
  }
  if (ThePool().TryRun(static_cast<int>(workers - 1), n_tasks, task)) return;
  std::atomic<long> next{0};
  std::vector<std::thread> pool;
  try {
    pool.reserve(static_cast<size_t>(workers - 1));
    for (long w = 1; w < workers; ++w)
      pool.emplace_back([&next, n_tasks, &task] { RunTasks(&next, n_tasks, &task, nullptr); });
  } catch (const std::system_error&) {  // no more threads: run with those there are
  } catch (const std::bad_alloc&) {     // no memory for one more: the same
  }
  std::exception_ptr failed;  // as in the pool: the pass ends, running tasks finish, then it leaves
  RunTasks(&next, n_tasks, &task, &failed);
  for (std::thread& t : pool) t.join();
  if (failed) std::rethrow_exception(failed);
}

long PoolHelperJoins() { return ThePool().Joins(); }
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
