// RenderStats::cachedCostShare (render_setup.h): what share of a scene's estimated material
// cost a render's cache can serve, by what it caches: whole uv-only graphs everywhere, cuts by
// key domain only where the texel cache keys cuts (wavefront, or the megakernel's switch).
// No device: the materials are linked on the CPU.
#include <gtest/gtest.h>

#include <filesystem>

#include "runtime/materials/scene_materials.h"
#include "runtime/trace/render_setup.h"

namespace memograph::runtime {
namespace {

// Three instances: a whole cacheable graph (textured_checker), a world-space cut holding all
// of its graph's cost (marble) and a uv cut holding 0.849 of it (car_paint).
class CachedCostShare : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::filesystem::path graphs = MEMOGRAPH_EXAMPLES_DIR;
    for (const char* name : {"textured_checker", "marble", "car_paint"})
      scene_.materials.push_back(
          {.name = name, .graphPath = (graphs / (std::string(name) + ".mgraph")).string()});
    scene_.instances = {
        {.mesh = 0, .material = 0}, {.mesh = 0, .material = 1}, {.mesh = 0, .material = 2}};
    materials_ = linkSceneMaterials(scene_, {});
  }
  RenderStats::CachedCostShare share(CacheMode mode, bool wavefront, MaterialDispatch dispatch) {
    RendererOptions options;
    options.cache.mode = mode;
    RenderPlan plan;
    plan.wavefront = wavefront;
    plan.dispatch = dispatch;
    return cachedCostShare(options, scene_, materials_, plan);
  }
  Scene scene_;
  SceneMaterials materials_;
};

TEST_F(CachedCostShare, TheWavefrontTexelCacheServesWholeGraphsAndCutsByDomain) {
  const auto s = share(CacheMode::Texel, true, MaterialDispatch::Callable);
  EXPECT_NEAR(s.whole, 1.0 / 3.0, 1e-9);
  EXPECT_NEAR(s.world, 1.0 / 3.0, 1e-3);
  EXPECT_NEAR(s.uv, 0.849 / 3.0, 1e-3);
  EXPECT_EQ(s.object, 0.0);
  EXPECT_NEAR(s.total(), (2.0 + 0.849) / 3.0, 1e-3);
  const auto megakernelSwitch = share(CacheMode::Texel, false, MaterialDispatch::Switch);
  EXPECT_NEAR(megakernelSwitch.total(), s.total(), 1e-12);
}

TEST_F(CachedCostShare, CallablesAndTheTileCacheServeWholeGraphsOnly) {
  for (const auto& s : {share(CacheMode::Texel, false, MaterialDispatch::Callable),
                        share(CacheMode::Tile, true, MaterialDispatch::Callable)}) {
    EXPECT_NEAR(s.whole, 1.0 / 3.0, 1e-9);
    EXPECT_EQ(s.uv + s.object + s.world, 0.0);
  }
  EXPECT_EQ(share(CacheMode::None, true, MaterialDispatch::Callable).total(), 0.0);
}

}  // namespace
}  // namespace memograph::runtime
