#include "pixelcloth/core/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace pixelcloth::core {

int threadCount(int requested, int jobs) {
  return std::max(1, std::min(jobs, requested > 0 ? requested : static_cast<int>(std::thread::hardware_concurrency())));
}

void parallelFor(int count, int threads, const std::function<void(int)>& job) {
  std::atomic<int> next{0};
  std::exception_ptr failure;
  std::mutex failureMutex;
  auto work = [&] {
    try {
      for (int k = next++; k < count; k = next++) job(k);
    } catch (...) {
      std::lock_guard<std::mutex> lock(failureMutex);
      if (!failure) failure = std::current_exception();
      next = count;
    }
  };
  std::vector<std::thread> workers;
  for (int t = 1; t < threadCount(threads, count); ++t) workers.emplace_back(work);
  work();
  for (std::thread& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace pixelcloth::core
