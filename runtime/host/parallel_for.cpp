#include "runtime/host/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace memograph::runtime {

std::uint32_t workerThreads(std::uint32_t requested, std::size_t items) {
  const std::uint32_t threads =
      requested ? requested : std::max(1u, std::thread::hardware_concurrency());
  return static_cast<std::uint32_t>(
      std::max<std::size_t>(1, std::min<std::size_t>(threads, items)));
}

void parallelFor(std::size_t count, std::uint32_t threads,
                 const std::function<void(std::size_t index, std::uint32_t thread)>& work) {
  if (count == 0)
    return;
  const std::uint32_t threadCount = workerThreads(threads, count);
  std::atomic<std::size_t> next{0};
  std::vector<std::exception_ptr> errors(threadCount);
  auto run = [&](std::uint32_t thread) {
    try {
      for (std::size_t index = next++; index < count; index = next++)
        work(index, thread);
    } catch (...) {
      errors[thread] = std::current_exception();
      next = count;  // the others stop after their current index
    }
  };
  std::vector<std::thread> workers;
  for (std::uint32_t t = 1; t < threadCount; ++t)
    workers.emplace_back(run, t);
  run(0);
  for (auto& worker : workers)
    worker.join();
  for (const auto& error : errors)
    if (error)
      std::rethrow_exception(error);
}

}  // namespace memograph::runtime
