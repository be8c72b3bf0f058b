// One empty VkPipelineCache per thread of a batch of pipeline creations, merged into the
// device's cache (PipelineCache) once the batch is done: for a cold start, when the device's
// cache holds nothing a thread could look up. The shared cache is internally synchronised,
// and a driver may hold its lock for longer than the lookup and the insertion (the spec only
// asks it to "make every effort" not to): threads creating pipelines through one cache could
// then compile one at a time. With a cache of its own, a thread shares no lock with the
// others. A warm start (pipelines loaded from the file, or created earlier in the process)
// keeps the shared cache, where the threads find them.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "runtime/vk/pipeline_cache.h"

namespace memograph::runtime {

class ThreadPipelineCaches {
 public:
  // Caches for `threads` threads when `cache` is the device's and holds nothing yet (no
  // data from its file, no pipeline created through it); otherwise none, and every thread
  // uses cache.handle().
  ThreadPipelineCaches(PipelineCache& cache, std::uint32_t threads);
  ~ThreadPipelineCaches();  // destroys the caches not merged (an exception on the way)
  ThreadPipelineCaches(const ThreadPipelineCaches&) = delete;
  ThreadPipelineCaches& operator=(const ThreadPipelineCaches&) = delete;

  // The cache thread `thread` (< threads) creates its pipelines with.
  VkPipelineCache forThread(std::uint32_t thread) const;
  bool split() const { return !caches_.empty(); }

  // Folds every thread's cache into the device's, then destroys them; call after the
  // threads stopped (vkMergePipelineCaches needs the source caches idle).
  void merge();

 private:
  PipelineCache& cache_;
  std::vector<VkPipelineCache> caches_;
  void destroy();
};

}  // namespace memograph::runtime
