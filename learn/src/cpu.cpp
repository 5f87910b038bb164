#include "pixelcloth/learn/cpu.h"

#include <malloc.h>
#include <torch/torch.h>

#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <thread>

namespace pixelcloth::learn {

ThreadScope::ThreadScope(int threads) : before_(torch::get_num_threads()) {
  if (threads > 0)
    torch::set_num_threads(threads);
  else if (std::getenv("OMP_NUM_THREADS") == nullptr)
    torch::set_num_threads(std::max(1, static_cast<int>(std::thread::hardware_concurrency())));
}

ThreadScope::~ThreadScope() { torch::set_num_threads(before_); }

void keepFreedMemory() {
  static std::once_flag once;
  std::call_once(once, [] {
#if defined(__GLIBC__)
    mallopt(M_MMAP_MAX, 0);              // large blocks from the heap, where freed ones are reused
    mallopt(M_TRIM_THRESHOLD, 1 << 30);  // and the heap's top is not given back while below 1 GB
#endif
  });
}

}  // namespace pixelcloth::learn
