#pragma once

// LibTorch on the CPU: how many threads a piece of work gets, and the allocator setting that training needs.

namespace pixelcloth::learn {

/// Sets LibTorch's intra-op threads (and so OpenBLAS's and oneDNN's) for a scope and puts the old count back.
/// `threads` > 0 is taken as given; 0 means one per core, unless OMP_NUM_THREADS is set, which then has the last word
/// (LibTorch on its own starts with one thread on these machines).
class ThreadScope {
 public:
  explicit ThreadScope(int threads);
  ~ThreadScope();
  ThreadScope(const ThreadScope&) = delete;
  ThreadScope& operator=(const ThreadScope&) = delete;

 private:
  int before_;
};

/// Tells glibc's malloc to keep the memory LibTorch frees for the next allocation rather than hand it back to the
/// system. A training step frees and reallocates the same activation buffers (tens of MB each), which glibc serves by
/// mmap and munmap above 32 MB: every step then page-faults its buffers in again, a third of an epoch's time on a
/// whole-garment decoder. The price is a resident size that stays at its peak. Takes effect once per process.
void keepFreedMemory();

}  // namespace pixelcloth::learn
