// Work spread over a few host threads: each takes the next index until none is left. The
// material shaders' GLSL compiles and the wavefront's compute pipelines use it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

namespace memograph::runtime {

// Threads to use for `requested` (0: one per hardware thread), at most `items`, at least 1.
std::uint32_t workerThreads(std::uint32_t requested, std::size_t items);

// Calls work(index, thread) for every index in [0, count) on workerThreads(threads, count)
// threads (`thread` in [0, that)). The first exception is rethrown once every thread has
// stopped; the others stop after their current index.
void parallelFor(std::size_t count, std::uint32_t threads,
                 const std::function<void(std::size_t index, std::uint32_t thread)>& work);

}  // namespace memograph::runtime
