#pragma once
/// @file Parallel.h
/// The only door to threads (oneTBB behind it, kept out of this header).
#include <cstddef>
#include <functional>

namespace octrace {

/// Runs body(i) for every i in [0, count). With threads == 1 it runs serially, in order, on
/// the calling thread; otherwise on up to `threads` workers (0 = all cores). The body must be
/// safe to call concurrently for different i. Exceptions thrown by body propagate.
void parallelFor(std::size_t count, int threads, const std::function<void(std::size_t)>& body);

/// Number of hardware threads.
int hardwareThreads();

}  // namespace octrace
