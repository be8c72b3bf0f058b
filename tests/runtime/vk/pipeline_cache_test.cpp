// The device's pipeline cache on disk (runtime/vk/pipeline_cache.h): its file format, a warm
// start from the file, files that must never reach the driver, and atomic writes.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_support.h"
#include "runtime/host/atomic_file.h"
#include "runtime/vk/compute_pipeline.h"
#include "runtime/vk/pipeline_cache.h"
#include "runtime/vk/shader_compiler.h"
#include "runtime/vk/thread_pipeline_caches.h"

namespace memograph::runtime {
namespace {

namespace fs = std::filesystem;

// A device's properties as the file check reads them, and driver data of that device: the
// header VkPipelineCacheHeaderVersionOne, then `payload`.
VkPhysicalDeviceProperties fakeDevice() {
  VkPhysicalDeviceProperties device{};
  device.vendorID = 0x10de;
  device.deviceID = 0x2335;
  for (std::uint32_t i = 0; i < VK_UUID_SIZE; ++i)
    device.pipelineCacheUUID[i] = std::uint8_t(i * 7 + 1);
  return device;
}

std::string driverData(const VkPhysicalDeviceProperties& device, std::string_view payload) {
  VkPipelineCacheHeaderVersionOne header{};
  header.headerSize = sizeof header;
  header.headerVersion = VK_PIPELINE_CACHE_HEADER_VERSION_ONE;
  header.vendorID = device.vendorID;
  header.deviceID = device.deviceID;
  std::memcpy(header.pipelineCacheUUID, device.pipelineCacheUUID, VK_UUID_SIZE);
  std::string data(reinterpret_cast<const char*>(&header), sizeof header);
  data.append(payload);
  return data;
}

PipelineCacheRejection rejectionOf(std::string_view file,
                                   const VkPhysicalDeviceProperties& device) {
  PipelineCacheRejection rejection = PipelineCacheRejection::None;
  std::string why;
  const auto data = decodePipelineCacheFile(file, device, rejection, why);
  EXPECT_EQ(data.has_value(), rejection == PipelineCacheRejection::None) << why;
  EXPECT_EQ(why.empty(), rejection == PipelineCacheRejection::None);
  return rejection;
}

std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void writeBytes(const fs::path& path, std::string_view bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), bytes.size());
}

std::vector<std::string> folderNames(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

fs::path freshFolder(const std::string& name) {
  const fs::path folder =
      fs::temp_directory_path() / ("memograph-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

TEST(PipelineCacheFile, KeepsTheDriversDataForItsDevice) {
  const VkPhysicalDeviceProperties device = fakeDevice();
  const std::string data = driverData(device, "the driver's pipelines");
  const std::string file = encodePipelineCacheFile(data);
  EXPECT_EQ(file.size(), kPipelineCacheFileHeaderBytes + data.size());
  PipelineCacheRejection rejection;
  std::string why;
  const auto decoded = decodePipelineCacheFile(file, device, rejection, why);
  ASSERT_TRUE(decoded.has_value()) << why;
  EXPECT_EQ(*decoded, data);
  EXPECT_EQ(pipelineCacheFileName(device), "pipeline-cache-10de-2335.bin");
}

// Another GPU, or the same one after a driver update (a new pipelineCacheUUID): a valid
// file, not for this device.
TEST(PipelineCacheFile, RefusesAnotherDeviceOrDriverVersion) {
  const VkPhysicalDeviceProperties device = fakeDevice();
  for (int field = 0; field < 3; ++field) {
    VkPhysicalDeviceProperties other = device;
    if (field == 0)
      other.vendorID ^= 1;
    else if (field == 1)
      other.deviceID ^= 1;
    else
      other.pipelineCacheUUID[VK_UUID_SIZE - 1] ^= 0x80;
    const std::string file = encodePipelineCacheFile(driverData(other, "pipelines"));
    EXPECT_EQ(rejectionOf(file, device), PipelineCacheRejection::OtherDevice) << field;
  }
}

TEST(PipelineCacheFile, RefusesTruncatedCorruptAndForeignFiles) {
  const VkPhysicalDeviceProperties device = fakeDevice();
  const std::string good = encodePipelineCacheFile(driverData(device, "the driver's pipelines"));
  ASSERT_EQ(rejectionOf(good, device), PipelineCacheRejection::None);
  std::vector<std::pair<std::string, std::string>> bad = {
      {"empty", ""},
      {"shorter than our header", good.substr(0, kPipelineCacheFileHeaderBytes - 1)},
      {"truncated", good.substr(0, good.size() - 1)},
      {"overlong", good + "x"},
      {"garbage", std::string(good.size(), '\x5a')},
      {"the driver's data alone", driverData(device, "the driver's pipelines")},
      {"no driver header", encodePipelineCacheFile("short")},
      {"a driver header of size 0",
       encodePipelineCacheFile(std::string(4, '\0') + driverData(device, "").substr(4))},
  };
  std::string flipped = good;
  flipped[good.size() - 3] ^= 0x01;  // in the driver's payload: the checksum catches it
  bad.emplace_back("a flipped byte", flipped);
  std::string version = good;
  version[4] = 9;  // our format version
  bad.emplace_back("another format version", version);
  std::string headerVersion = driverData(device, "pipelines");
  headerVersion[4] = 2;  // VkPipelineCacheHeaderVersion
  bad.emplace_back("another driver header version", encodePipelineCacheFile(headerVersion));
  for (const auto& [name, file] : bad)
    EXPECT_EQ(rejectionOf(file, device), PipelineCacheRejection::Corrupt) << name;
}

// A device context whose pipeline cache lives in `folder`, and a trivial compute pipeline
// created through it (seconds on lavapipe, where a path tracer's pipeline takes minutes).
struct TinyPipeline {
  explicit TinyPipeline(const fs::path& folder) : context(options(folder)) {
    ShaderCompiler compiler(
        {{"tiny.comp", "#version 460\nlayout(local_size_x = 1) in;\nvoid main() {}\n"}}, {});
    module = createShaderModule(context.device(),
                                compiler.compile({"tiny.comp", ShaderStage::Compute, {}}));
    layout = createPipelineLayout(context.device(), VK_NULL_HANDLE);
    pipeline = createComputePipeline(context, module.get(), layout.get(), "tiny");
  }
  static ContextOptions options(const fs::path& folder) {
    ContextOptions options = testing::testOptions().context;
    options.pipelineCacheDirectory = folder;
    return options;
  }
  VkPhysicalDeviceProperties properties() const {
    VkPhysicalDeviceProperties properties{};
    vkGetPhysicalDeviceProperties(context.physicalDevice(), &properties);
    return properties;
  }
  fs::path file() const { return context.pipelineCache().file(); }

  VulkanContext context;
  VulkanHandle<VkShaderModule> module;
  VulkanHandle<VkPipelineLayout> layout;
  VulkanHandle<VkPipeline> pipeline;
};

// A warm start: the second context hands the first's file to the driver and finds nothing
// new to write. Where the driver keeps pipelines in the cache and says so (creation
// feedback), its second creation is a hit. lavapipe keeps none (its data is its header
// alone) and reports every pipeline as compiled: there the test checks the bytes fed and the
// unchanged file, and prints what the driver said.
TEST(PipelineCache, ASecondStartFeedsTheFileToTheDriverAndWritesNothingNew) {
  const fs::path folder = freshFolder("pipeline-cache-warm");
  std::string written;
  fs::path file;
  {
    TinyPipeline first(folder);
    PipelineCache& cache = first.context.pipelineCache();
    EXPECT_EQ(cache.loadedBytes(), 0u);
    EXPECT_EQ(cache.counts().created, 1u);
    EXPECT_EQ(cache.counts().hits, 0u);
    EXPECT_EQ(first.file(), folder / pipelineCacheFileName(first.properties()));
    EXPECT_TRUE(cache.save());
    EXPECT_FALSE(cache.save());  // nothing new since
    file = first.file();
    written = readBytes(file);
    PipelineCacheRejection rejection;
    std::string why;
    ASSERT_TRUE(decodePipelineCacheFile(written, first.properties(), rejection, why)) << why;
  }
  struct stat before {};
  ASSERT_EQ(::stat(file.c_str(), &before), 0);
  TinyPipeline second(folder);
  PipelineCache& cache = second.context.pipelineCache();
  EXPECT_EQ(cache.loadedBytes(), written.size() - kPipelineCacheFileHeaderBytes);
  EXPECT_EQ(cache.counts().created, 1u);
  EXPECT_FALSE(cache.save());
  EXPECT_EQ(readBytes(second.file()), written);
  struct stat after {};
  ASSERT_EQ(::stat(second.file().c_str(), &after), 0);
  EXPECT_EQ(after.st_ino, before.st_ino);  // not even rewritten with the same bytes
  const bool driverKeepsPipelines =
      written.size() > kPipelineCacheFileHeaderBytes + sizeof(VkPipelineCacheHeaderVersionOne);
  const PipelineCacheCounts counts = cache.counts();
  if (driverKeepsPipelines && counts.reported > 0) {
    EXPECT_EQ(counts.hits, counts.created);
  }
  std::printf(
      "pipeline cache on %s: %zu bytes of driver data; the second start created %u pipeline(s), "
      "%u with feedback, %u found in the cache\n",
      second.context.info().name.c_str(), written.size() - kPipelineCacheFileHeaderBytes,
      counts.created, counts.reported, counts.hits);
  EXPECT_EQ(folderNames(folder), std::vector<std::string>{second.file().filename().string()});
  fs::remove_all(folder);
}

// Files that must not reach the driver: one of another driver version (the UUID), a
// truncated one, garbage, an empty one and one over the size cap. Each is ignored without an
// error (the driver starts empty: nothing loaded), and the first save replaces it with this
// device's cache.
TEST(PipelineCache, AnUnusableFileIsIgnoredAndReplaced) {
  const fs::path folder = freshFolder("pipeline-cache-unusable");
  std::string good;
  VkPhysicalDeviceProperties properties{};
  fs::path file;
  {
    TinyPipeline reference(folder);
    ASSERT_TRUE(reference.context.pipelineCache().save());
    file = reference.file();
    good = readBytes(file);
    properties = reference.properties();
  }
  VkPhysicalDeviceProperties otherDriver = properties;
  otherDriver.pipelineCacheUUID[0] ^= 0xff;
  std::string foreign = encodePipelineCacheFile(driverData(otherDriver, "another driver's"));
  std::string garbage(256, '\0');
  for (std::size_t i = 0; i < garbage.size(); ++i)
    garbage[i] = char(i * 37 + 11);
  const std::vector<std::pair<std::string, std::function<void()>>> cases = {
      {"another driver version", [&] { writeBytes(file, foreign); }},
      {"truncated", [&] { writeBytes(file, good.substr(0, good.size() - 5)); }},
      {"garbage", [&] { writeBytes(file, garbage); }},
      {"empty", [&] { writeBytes(file, ""); }},
      {"over the cap",
       [&] {
         writeBytes(file, good);
         fs::resize_file(file, kMaxPipelineCacheFileBytes + 1);  // sparse: no disk used
       }},
  };
  for (const auto& [name, spoil] : cases) {
    spoil();
    TinyPipeline run(folder);
    PipelineCache& cache = run.context.pipelineCache();
    EXPECT_EQ(cache.loadedBytes(), 0u) << name;
    EXPECT_EQ(cache.counts().created, 1u) << name;
    EXPECT_TRUE(cache.save()) << name;
    EXPECT_EQ(readBytes(file), good) << name;
  }
  EXPECT_EQ(folderNames(folder), std::vector<std::string>{file.filename().string()});
  fs::remove_all(folder);
}

// The file is replaced by a rename of a complete temporary, never rewritten in place: a
// second name for the old file (a hard link) still reads the old bytes afterwards. With
// threads saving while others keep spoiling the file (each save then has something to
// write), a reader never sees anything but a whole file of one writer, and no temporary is
// left behind.
TEST(PipelineCache, IsWrittenAtomicallyLeavingNoTemporaries) {
  const fs::path folder = freshFolder("pipeline-cache-atomic");
  TinyPipeline tiny(folder);
  const fs::path file = tiny.file();
  const std::string spoiled = "spoiled: not a pipeline cache";
  writeBytes(file, spoiled);
  const fs::path oldName = folder / "old-name";
  fs::create_hard_link(file, oldName);
  ASSERT_TRUE(tiny.context.pipelineCache().save());
  EXPECT_EQ(readBytes(oldName), spoiled);
  const std::string good = readBytes(file);
  EXPECT_NE(good, spoiled);
  fs::remove(oldName);

  // Each saver is a PipelineCache of its own on the device, as a process of its own would
  // have. Before each save it spoils the file (atomically too, so a torn file can only come
  // from a save), so that most saves have something to write.
  const VkPhysicalDeviceProperties properties = tiny.properties();
  std::atomic<bool> stop{false};
  std::atomic<int> torn{0}, reads{0}, saves{0};
  std::thread reader([&] {
    while (!stop) {
      const std::string bytes = readBytes(file);
      ++reads;
      if (bytes != good && bytes != spoiled)
        ++torn;
    }
  });
  std::vector<std::thread> savers;
  for (int t = 0; t < 3; ++t)
    savers.emplace_back([&] {
      PipelineCache cache(tiny.context.device(), properties, file);
      std::string error;
      for (int i = 0; i < 30; ++i) {
        EXPECT_TRUE(files::writeFileAtomically(file, spoiled, error)) << error;
        saves += cache.save() ? 1 : 0;
      }
    });
  for (auto& saver : savers)
    saver.join();
  stop = true;
  reader.join();
  EXPECT_EQ(torn, 0) << "of " << reads << " reads";
  EXPECT_GT(saves, 0);
  EXPECT_EQ(folderNames(folder), std::vector<std::string>{file.filename().string()});
  fs::remove_all(folder);
}

// A cold start's threads each create through a cache of their own, merged into the device's
// afterwards, so the file keeps their pipelines; once the device's cache holds something (a
// pipeline created, or data from the file) every thread shares it, to find what it holds.
TEST(PipelineCache, ThreadCachesSplitOnlyAColdStartAndMergeBack) {
  const fs::path folder = freshFolder("pipeline-cache-threads");
  {
    VulkanContext context(TinyPipeline::options(folder));
    PipelineCache& cache = context.pipelineCache();
    EXPECT_FALSE(ThreadPipelineCaches(cache, 1).split());  // one thread: nothing to contend
    ThreadPipelineCaches caches(cache, 2);
    ASSERT_TRUE(caches.split());
    EXPECT_NE(caches.forThread(0), caches.forThread(1));
    EXPECT_NE(caches.forThread(1), cache.handle());
    ShaderCompiler compiler(
        {{"tiny.comp", "#version 460\nlayout(local_size_x = 1) in;\nvoid main() {}\n"}}, {});
    auto module = createShaderModule(context.device(),
                                     compiler.compile({"tiny.comp", ShaderStage::Compute, {}}));
    auto layout = createPipelineLayout(context.device(), VK_NULL_HANDLE);
    auto pipeline =
        createComputePipeline(context, module.get(), layout.get(), "tiny", caches.forThread(1));
    EXPECT_EQ(cache.counts().created, 1u);  // counted on the device's cache all the same
    caches.merge();
    EXPECT_FALSE(caches.split());
    EXPECT_EQ(caches.forThread(1), cache.handle());
    EXPECT_FALSE(ThreadPipelineCaches(cache, 2).split());  // it holds a pipeline now
    EXPECT_TRUE(cache.save());
  }
  VulkanContext warm(TinyPipeline::options(folder));
  ASSERT_GT(warm.pipelineCache().loadedBytes(), 0u);
  EXPECT_FALSE(ThreadPipelineCaches(warm.pipelineCache(), 2).split());
  fs::remove_all(folder);
}

// The renderer: its pipelines are counted and the file is written once, beside the SPIR-V
// cache; a second renderer (a second start) loads it and writes nothing new. The render's
// summary figures come from the same counts.
TEST(PipelineCache, TheRendererKeepsItBesideTheShaderCache) {
  const fs::path folder = freshFolder("pipeline-cache-render");
  RendererOptions options = testing::testOptions();
  options.shaderCacheDirectory = folder;
  const Scene scene = testing::greyQuadScene("A");
  RenderSettings settings;
  settings.width = settings.height = 4;
  RenderStats first, second;
  {
    Renderer renderer(options);
    first = renderer.render(scene, settings).stats;
  }
  {
    Renderer renderer(options);
    second = renderer.render(scene, settings).stats;
  }
  // The megakernel on the query backend: the path tracer's one compute pipeline.
  EXPECT_EQ(first.pipelinesCreated, 1u);
  EXPECT_EQ(second.pipelinesCreated, 1u);
  EXPECT_EQ(first.pipelineCacheLoadedBytes, 0u);
  EXPECT_TRUE(first.pipelineCacheWritten);
  EXPECT_GT(second.pipelineCacheLoadedBytes, 0u);
  EXPECT_FALSE(second.pipelineCacheWritten);
  EXPECT_GT(first.firstFrameMilliseconds, first.pipelineCreateMilliseconds);
  std::size_t pipelineFiles = 0;
  for (const auto& name : folderNames(folder)) {
    EXPECT_EQ(name.find(".partial-"), std::string::npos) << name;
    pipelineFiles += name.rfind("pipeline-cache-", 0) == 0;
  }
  EXPECT_EQ(pipelineFiles, 1u);
  fs::remove_all(folder);
}

}  // namespace
}  // namespace memograph::runtime
