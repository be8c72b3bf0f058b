// How many pipelines a wavefront frame creates: a cold start's first frame waits for every
// one of them (docs/results.md, "First frame"), so a pipeline more is a regression to see
// here, counted, never timed. A render
// counts the pipelines it created (RenderStats::pipelinesCreated); the classroom's render is
// pinned in wavefront_test.cpp (TheClassroomsGraphsGiveTheMegakernelsPictureAtOneSeed).
#include <unistd.h>

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "render_test_support.h"
#include "runtime/materials/scene_materials.h"
#include "runtime/renderer.h"
#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/shaders/shared_types.h"
#include "runtime/trace/wavefront/wavefront_passes.h"

namespace memograph::runtime {
namespace {

// The classroom on the GPU (the pipeline backend, no cache): its 88 distinct graphs come from
// 11 recipes, which differ only in float constants (colours, offsets, scales), so they are 11
// instance groups, each a material pass; then the generate, shade, queue, finish and three
// binning passes, and one ray-tracing pipeline for the trace and shadow raygens. No lookup
// pass without a cache; no trace or shadow compute pass where raygens trace.
TEST(WavefrontPipelineCount, TheClassroomCreates19PipelinesOnThePipelineBackend) {
  const Scene scene = makeBuiltinScene("classroom", {});
  const SceneMaterials materials = linkSceneMaterials(scene, {});
  EXPECT_EQ(materials.linked.distinct.size(), 88u);
  WavefrontPipelineChoice choice;
  choice.rayQuery = false;
  choice.materialPasses = static_cast<std::uint32_t>(materials.linked.instanceGroups.size());
  EXPECT_EQ(choice.materialPasses, 11u);
  EXPECT_EQ(wavefrontComputePasses(choice),
            (std::vector<std::uint32_t>{gpu::kWavefrontGenerate, gpu::kWavefrontShade,
                                        gpu::kWavefrontQueue, gpu::kWavefrontFinish,
                                        gpu::kWavefrontBinCount, gpu::kWavefrontBinOffsets,
                                        gpu::kWavefrontBinScatter}));
  EXPECT_EQ(wavefrontPipelineCount(choice), 19u);
  choice.cacheLookups = true;  // --cache texel or tile: the lookup pass
  EXPECT_EQ(wavefrontPipelineCount(choice), 20u);
}

// The free-material floor has no bins to sort: generate, shade, queue, finish, plus trace and
// shadow as compute passes on the query backend or one ray-tracing pipeline.
TEST(WavefrontPipelineCount, TheFloorBuildsNoBinningOrMaterialPasses) {
  WavefrontPipelineChoice choice;
  EXPECT_EQ(wavefrontPipelineCount(choice), 6u);
  choice.rayQuery = false;
  EXPECT_EQ(wavefrontPipelineCount(choice), 5u);
}

// What a render creates is what wavefrontPipelineCount says: the landscape's graphs on both
// backends, counted by the pipeline cache as the driver creates them. Each a cold start with
// a cache folder, so its threads create through caches of their own (ThreadPipelineCaches),
// under the validation layer where it is installed.
TEST(WavefrontPipelineCount, ARenderCreatesExactlyThePipelinesItsFrameUses) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() /
      ("memograph-wavefront-pipelines-" + std::to_string(::getpid()));
  const Scene scene = makeBuiltinScene("landscape", {});
  const SceneMaterials materials = linkSceneMaterials(scene, {});
  RenderSettings settings;
  settings.width = 8;
  settings.height = 4;
  settings.pathsPerPixel = 1;
  settings.raysPerPath = 2;
  for (Backend backend : {Backend::RayQuery, Backend::RayTracingPipeline}) {
    RendererOptions options = testing::testOptions(backend);
    options.nodeLibraryDirectory.clear();  // built-in scenes: the real node library
    options.shading = Shading::Wavefront;
    std::filesystem::remove_all(folder);
    options.shaderCacheDirectory = folder;
    Renderer renderer(options);
    const RenderStats stats = renderer.render(scene, settings).stats;
    EXPECT_TRUE(stats.pipelineCacheWritten);
    EXPECT_TRUE(renderer.context().validationErrors().empty());
    WavefrontPipelineChoice choice;
    choice.rayQuery = backend == Backend::RayQuery;
    choice.materialPasses = static_cast<std::uint32_t>(materials.linked.instanceGroups.size());
    EXPECT_EQ(stats.pipelinesCreated, wavefrontPipelineCount(choice)) << stats.backend;
  }
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace memograph::runtime
