#pragma once

#include <functional>

namespace pixelcloth::core {

/// The threads a job of `jobs` items runs on: `requested`, or one per core when 0; at least 1, at most `jobs`.
int threadCount(int requested, int jobs);

/// Runs job(k) for every k in [0, count) on threadCount(threads, count) threads, the calling thread among them. The
/// first exception stops the others (no new k starts) and is rethrown once all have joined.
void parallelFor(int count, int threads, const std::function<void(int)>& job);

}  // namespace pixelcloth::core
