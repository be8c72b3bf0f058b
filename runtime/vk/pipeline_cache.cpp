#include "runtime/vk/pipeline_cache.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <vector>

#include "runtime/host/atomic_file.h"
#include "runtime/vk/vulkan_error.h"

namespace memograph::runtime {

namespace {

constexpr std::uint32_t kFileMagic = 0x4350474du;  // "MGPC"
constexpr std::uint32_t kFileVersion = 1;
// VkPipelineCacheHeaderVersionOne: headerSize, headerVersion, vendorID, deviceID, then the
// 16-byte pipelineCacheUUID.
constexpr std::size_t kDriverHeaderBytes = 16 + VK_UUID_SIZE;

std::uint32_t readWord(std::string_view bytes, std::size_t offset) {
  std::uint32_t word = 0;
  std::memcpy(&word, bytes.data() + offset, sizeof word);
  return word;
}

std::uint64_t fnv1a(std::string_view bytes) {
  std::uint64_t hash = 14695981039346656037ull;
  for (unsigned char c : bytes) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  return hash;
}

// The file's bytes; nothing when it does not exist or cannot be read, and nothing with
// `tooLarge` set for a file over the cap (never read).
std::optional<std::string> readFile(const std::filesystem::path& path, bool& tooLarge) {
  tooLarge = false;
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::is_regular_file(status))
    return std::nullopt;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec)
    return std::nullopt;
  if (size > kMaxPipelineCacheFileBytes) {
    tooLarge = true;
    return std::nullopt;
  }
  std::string bytes(size, '\0');
  std::ifstream in(path, std::ios::binary);
  in.read(bytes.data(), std::streamsize(size));
  if (!in)
    return std::nullopt;
  return bytes;
}

void warnUnusable(const std::filesystem::path& path, const std::string& why) {
  std::cerr << "memograph: warning: pipeline cache " << path.string() << " is unusable (" << why
            << "); pipelines are created afresh and the file is replaced\n";
}

// Once a process, as the shader cache's unwritable entries.
void warnUnwritable(const std::filesystem::path& path, const std::string& why) {
  static std::atomic_flag warned = ATOMIC_FLAG_INIT;
  if (warned.test_and_set())
    return;
  std::cerr << "memograph: warning: cannot write the pipeline cache " << path.string() << " ("
            << why << "); pipelines are created again on the next run\n";
}

VkPipelineCache createCache(VkDevice device, std::string_view data) {
  VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  info.initialDataSize = data.size();
  info.pInitialData = data.empty() ? nullptr : data.data();
  VkPipelineCache cache = VK_NULL_HANDLE;
  checkVk(vkCreatePipelineCache(device, &info, nullptr, &cache), "vkCreatePipelineCache");
  return cache;
}

}  // namespace

std::string pipelineCacheFileName(const VkPhysicalDeviceProperties& device) {
  char name[64];
  std::snprintf(name, sizeof name, "pipeline-cache-%04x-%04x.bin", device.vendorID,
                device.deviceID);
  return name;
}

std::string encodePipelineCacheFile(std::string_view data) {
  std::string file(kPipelineCacheFileHeaderBytes, '\0');
  const std::uint64_t size = data.size();
  const std::uint64_t sum = fnv1a(data);
  std::memcpy(file.data(), &kFileMagic, 4);
  std::memcpy(file.data() + 4, &kFileVersion, 4);
  std::memcpy(file.data() + 8, &size, 8);
  std::memcpy(file.data() + 16, &sum, 8);
  file.append(data);
  return file;
}

std::optional<std::string_view> decodePipelineCacheFile(std::string_view file,
                                                        const VkPhysicalDeviceProperties& device,
                                                        PipelineCacheRejection& rejection,
                                                        std::string& why) {
  rejection = PipelineCacheRejection::Corrupt;
  if (file.size() < kPipelineCacheFileHeaderBytes) {
    why = "shorter than its header";
    return std::nullopt;
  }
  if (readWord(file, 0) != kFileMagic || readWord(file, 4) != kFileVersion) {
    why = "not a memograph pipeline cache of this version";
    return std::nullopt;
  }
  std::uint64_t size = 0, sum = 0;
  std::memcpy(&size, file.data() + 8, 8);
  std::memcpy(&sum, file.data() + 16, 8);
  const std::string_view data = file.substr(kPipelineCacheFileHeaderBytes);
  if (size != data.size()) {
    why = (data.size() < size ? "truncated: " : "overlong: ") + std::to_string(data.size()) +
          " of " + std::to_string(size) + " bytes";
    return std::nullopt;
  }
  if (fnv1a(data) != sum) {
    why = "checksum mismatch";
    return std::nullopt;
  }
  // The driver's own header (VkPipelineCacheHeaderVersionOne), which it wrote at the start
  // of its data: a driver is not required to survive data of another device or version.
  if (data.size() < kDriverHeaderBytes) {
    why = "no driver header";
    return std::nullopt;
  }
  const std::uint32_t headerSize = readWord(data, 0);
  if (headerSize < kDriverHeaderBytes || headerSize > data.size() ||
      readWord(data, 4) != VK_PIPELINE_CACHE_HEADER_VERSION_ONE) {
    why = "its driver header is malformed";
    return std::nullopt;
  }
  rejection = PipelineCacheRejection::OtherDevice;
  if (readWord(data, 8) != device.vendorID || readWord(data, 12) != device.deviceID) {
    why = "written for another device";
    return std::nullopt;
  }
  if (std::memcmp(data.data() + 16, device.pipelineCacheUUID, VK_UUID_SIZE) != 0) {
    why = "written by another driver version (pipelineCacheUUID)";
    return std::nullopt;
  }
  rejection = PipelineCacheRejection::None;
  why.clear();
  return data;
}

PipelineCache::PipelineCache(VkDevice device, const VkPhysicalDeviceProperties& properties,
                             std::filesystem::path file)
    : device_(device), properties_(properties), file_(std::move(file)) {
  if (file_.empty())
    return;
  std::string_view data;
  bool tooLarge = false;
  if (auto bytes = readFile(file_, tooLarge)) {
    PipelineCacheRejection rejection;
    std::string why;
    if (auto decoded = decodePipelineCacheFile(*bytes, properties_, rejection, why)) {
      onDisk_ = std::move(*bytes);
      data = std::string_view(onDisk_).substr(kPipelineCacheFileHeaderBytes);
    } else if (rejection == PipelineCacheRejection::Corrupt) {
      warnUnusable(file_, why);
    }
  } else if (tooLarge) {
    warnUnusable(file_, "larger than " + std::to_string(kMaxPipelineCacheFileBytes >> 20) + " MiB");
  }
  // The driver may still refuse data it wrote (it must not crash on it): then it starts empty.
  VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  info.initialDataSize = data.size();
  info.pInitialData = data.empty() ? nullptr : data.data();
  const VkResult result = vkCreatePipelineCache(device_, &info, nullptr, &cache_);
  if (result == VK_SUCCESS) {
    loadedBytes_ = data.size();
    return;
  }
  if (data.empty())
    checkVk(result, "vkCreatePipelineCache");
  warnUnusable(file_, std::string("the driver refused it: ") + resultName(result));
  cache_ = createCache(device_, {});
}

PipelineCache::~PipelineCache() {
  if (cache_ != VK_NULL_HANDLE)
    vkDestroyPipelineCache(device_, cache_, nullptr);
}

std::string PipelineCache::driverData() const {
  std::size_t size = 0;
  checkVk(vkGetPipelineCacheData(device_, cache_, &size, nullptr), "vkGetPipelineCacheData");
  std::string data(size, '\0');
  // VK_INCOMPLETE only if the cache grew between the calls (another thread creating a
  // pipeline): what was written is a valid, shorter cache.
  const VkResult result = vkGetPipelineCacheData(device_, cache_, &size, data.data());
  if (result != VK_INCOMPLETE)
    checkVk(result, "vkGetPipelineCacheData");
  data.resize(size);
  return data;
}

bool PipelineCache::save() {
  if (cache_ == VK_NULL_HANDLE)
    return false;
  const std::lock_guard lock(saveMutex_);
  // Another process may have written the file since it was read: keep its pipelines too.
  bool tooLarge = false;
  const std::string current = readFile(file_, tooLarge).value_or(std::string());
  if (!current.empty() && current != onDisk_) {
    PipelineCacheRejection rejection;
    std::string why;
    if (auto theirs = decodePipelineCacheFile(current, properties_, rejection, why)) {
      VkPipelineCache other = createCache(device_, *theirs);
      const VkResult merged = vkMergePipelineCaches(device_, cache_, 1, &other);
      vkDestroyPipelineCache(device_, other, nullptr);
      checkVk(merged, "vkMergePipelineCaches");
    }
  }
  std::string encoded = encodePipelineCacheFile(driverData());
  if (encoded == current) {
    onDisk_ = current;
    return false;  // nothing new: every pipeline came from the file
  }
  std::error_code ignored;
  if (encoded.size() > kMaxPipelineCacheFileBytes) {
    // Kept, it would be refused by the next run: that run starts afresh instead.
    std::filesystem::remove(file_, ignored);
    warnUnwritable(file_, "it grew past " + std::to_string(kMaxPipelineCacheFileBytes >> 20) +
                              " MiB; removed, the next run starts an empty one");
    onDisk_.clear();
    return false;
  }
  std::error_code error;
  std::filesystem::create_directories(file_.parent_path(), error);
  std::string why;
  if (error) {
    warnUnwritable(file_, "cannot create its folder: " + error.message());
    return false;
  }
  if (!files::writeFileAtomically(file_, encoded, why)) {
    warnUnwritable(file_, why);
    return false;
  }
  onDisk_ = std::move(encoded);
  return true;
}

void PipelineCache::mergeIn(const std::vector<VkPipelineCache>& others) {
  if (cache_ == VK_NULL_HANDLE || others.empty())
    return;
  const std::lock_guard lock(saveMutex_);
  checkVk(vkMergePipelineCaches(device_, cache_, static_cast<std::uint32_t>(others.size()),
                                others.data()),
          "vkMergePipelineCaches");
}

void PipelineCache::countCreated(const VkPipelineCreationFeedback& feedback,
                                 std::chrono::nanoseconds took) {
  ++created_;
  creationNanoseconds_ += static_cast<std::uint64_t>(std::max<std::int64_t>(0, took.count()));
  if (feedback.flags & VK_PIPELINE_CREATION_FEEDBACK_VALID_BIT) {
    ++reported_;
    if (feedback.flags & VK_PIPELINE_CREATION_FEEDBACK_APPLICATION_PIPELINE_CACHE_HIT_BIT)
      ++hits_;
  }
}

PipelineCacheCounts PipelineCache::counts() const {
  return {created_.load(), reported_.load(), hits_.load(), creationNanoseconds_.load()};
}

}  // namespace memograph::runtime
