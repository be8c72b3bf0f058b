#include "runtime/vk/thread_pipeline_caches.h"

#include "runtime/vk/vulkan_error.h"

namespace memograph::runtime {

ThreadPipelineCaches::ThreadPipelineCaches(PipelineCache& cache, std::uint32_t threads)
    : cache_(cache) {
  if (cache.handle() == VK_NULL_HANDLE || cache.loadedBytes() > 0 || cache.counts().created > 0 ||
      threads < 2)
    return;
  VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  for (std::uint32_t thread = 0; thread < threads; ++thread) {
    VkPipelineCache created = VK_NULL_HANDLE;
    const VkResult result = vkCreatePipelineCache(cache.device(), &info, nullptr, &created);
    if (result != VK_SUCCESS) {
      destroy();
      checkVk(result, "vkCreatePipelineCache");
    }
    caches_.push_back(created);
  }
}

ThreadPipelineCaches::~ThreadPipelineCaches() {
  destroy();
}

VkPipelineCache ThreadPipelineCaches::forThread(std::uint32_t thread) const {
  return caches_.empty() ? cache_.handle() : caches_.at(thread);
}

void ThreadPipelineCaches::merge() {
  if (caches_.empty())
    return;
  cache_.mergeIn(caches_);
  destroy();
}

void ThreadPipelineCaches::destroy() {
  for (VkPipelineCache cache : caches_)
    vkDestroyPipelineCache(cache_.device(), cache, nullptr);
  caches_.clear();
}

}  // namespace memograph::runtime
