// The driver's pipeline cache (VkPipelineCache) kept on disk beside the SPIR-V cache, one
// file per device, so a second start creates its pipelines from the driver's cached
// binaries instead of compiling them again (the classroom's first frame on an H200 spent 8 of
// its 9 s creating pipelines without one).
//
// A file is the driver's data (vkGetPipelineCacheData) behind a header of ours: a magic
// number, a format version, the data's byte count and its 64-bit FNV-1a checksum. Before the
// data reaches the driver, the header the driver wrote at its start
// (VkPipelineCacheHeaderVersionOne) must name this device: its vendor and device ids and its
// pipelineCacheUUID (which changes with the driver). A file that does not match (another GPU,
// an updated driver) is ignored silently; one that is truncated, corrupt or larger than
// kMaxPipelineCacheFileBytes is ignored with a warning. Either way the driver starts from an
// empty cache and the file is replaced after pipeline creation. Writes go through
// files::writeFileAtomically (a unique temporary, then rename), so concurrent renders never
// tear the file: the last one to write wins, after merging in what another process wrote
// since this one read it.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <vulkan/vulkan.h>

namespace memograph::runtime {

// The largest pipeline cache file read or written: 256 MiB. A larger file is ignored (and
// replaced); a cache whose data grows past it is not written and its file is removed, so the
// next run starts afresh and keeps only its own pipelines.
constexpr std::uint64_t kMaxPipelineCacheFileBytes = 256ull << 20;
constexpr std::size_t kPipelineCacheFileHeaderBytes = 24;

// "pipeline-cache-<vendorID>-<deviceID>.bin" (hexadecimal): one file per kind of device;
// the driver version is checked through the header's UUID, so a driver update replaces the
// file instead of adding one.
std::string pipelineCacheFileName(const VkPhysicalDeviceProperties& device);

// The file's bytes for the driver's `data`.
std::string encodePipelineCacheFile(std::string_view data);

// Why a file's bytes are unusable on `device`.
enum class PipelineCacheRejection {
  None,         // usable
  OtherDevice,  // a valid file of another device or driver version (not worth a warning)
  Corrupt,      // truncated, wrong magic or version, bad checksum, no driver header
};

// The driver's data in `file` when it is whole and its driver header names `device`; else
// nothing, with `rejection` and `why` saying why.
std::optional<std::string_view> decodePipelineCacheFile(std::string_view file,
                                                        const VkPhysicalDeviceProperties& device,
                                                        PipelineCacheRejection& rejection,
                                                        std::string& why);

// Pipelines created through the cache and what the driver said of them
// (VK_EXT_pipeline_creation_feedback): `reported` of them carried valid feedback, `hits` of
// those were found in the application's pipeline cache; `creationNanoseconds`: the time their
// creation calls took, summed (calls on several threads overlap).
struct PipelineCacheCounts {
  std::uint32_t created = 0;
  std::uint32_t reported = 0;
  std::uint32_t hits = 0;
  std::uint64_t creationNanoseconds = 0;
};

// One device's pipeline cache. Thread-safe: the VkPipelineCache is internally synchronised,
// so any thread may create pipelines with handle() while others do; counts are atomic; save()
// takes a lock.
class PipelineCache {
 public:
  // `file` empty: no cache at all (handle() is VK_NULL_HANDLE, as with --no-shader-cache).
  // Otherwise the driver starts from `file`'s data when it is usable on `properties`'s device,
  // else from an empty cache. Throws VulkanError when the driver cannot create a cache.
  PipelineCache(VkDevice device, const VkPhysicalDeviceProperties& properties,
                std::filesystem::path file);
  ~PipelineCache();
  PipelineCache(const PipelineCache&) = delete;
  PipelineCache& operator=(const PipelineCache&) = delete;

  VkPipelineCache handle() const { return cache_; }
  VkDevice device() const { return device_; }
  const std::filesystem::path& file() const { return file_; }
  // Bytes of driver data handed to the driver from the file (0: none, or it was ignored).
  std::uint64_t loadedBytes() const { return loadedBytes_; }

  // Writes the driver's data to the file when it differs from what was read or last
  // written; first merges in a usable file another process wrote since. Returns whether
  // the file was written. A write that fails is a warning (once a process), never an error.
  bool save();

  // Merges `others` (caches of this device that pipelines were created with instead of
  // handle(), now idle) into this one, so that save() writes their pipelines too. Takes
  // save()'s lock: the spec wants the destination externally synchronised.
  void mergeIn(const std::vector<VkPipelineCache>& others);

  // Counts a pipeline created with handle(): `feedback` is the pipeline's
  // VkPipelineCreationFeedback (flags 0 when the driver gave none), `took` its creation
  // call's wall time.
  void countCreated(const VkPipelineCreationFeedback& feedback, std::chrono::nanoseconds took);
  PipelineCacheCounts counts() const;

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
  std::filesystem::path file_;
  VkPipelineCache cache_ = VK_NULL_HANDLE;
  std::uint64_t loadedBytes_ = 0;
  std::mutex saveMutex_;
  std::string onDisk_;  // the file's bytes as last read or written ("" when none)
  std::atomic<std::uint32_t> created_{0};
  std::atomic<std::uint32_t> reported_{0};
  std::atomic<std::uint32_t> hits_{0};
  std::atomic<std::uint64_t> creationNanoseconds_{0};

  std::string driverData() const;
};

}  // namespace memograph::runtime
