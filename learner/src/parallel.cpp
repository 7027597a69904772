// parallel.cpp - ParallelFor and AvailableCores (contract in parallel.hpp).
#include "parallel.hpp"

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace gmmrrt {
namespace learn {
namespace detail {

void ParallelFor(int threads, long n_tasks, const std::function<void(long task)>& task) {
  const long workers = std::min<long>(std::max(threads, 1), n_tasks);
  if (workers <= 1) {
    for (long t = 0; t < n_tasks; ++t) task(t);
    return;
  }
  std::atomic<long> next{0};
  auto work = [&next, n_tasks, &task]() {
    for (long t = next.fetch_add(1); t < n_tasks; t = next.fetch_add(1)) task(t);
  };
  std::vector<std::thread> pool;
  pool.reserve(static_cast<size_t>(workers - 1));
  for (long w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
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
