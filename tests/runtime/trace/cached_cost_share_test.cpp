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
// of its graph's cost (marble) and a uv cut holding 0.984 of it (car_paint).
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
  // Each instance weighs by its graph's estimated cost: the share is of the scene's cost.
  const auto& m = materials_.linked.materials;
  const double checker = m.at(0).estimatedCost;
  const double marble = m.at(1).estimatedCost;
  const double carPaint = m.at(2).estimatedCost;
  ASSERT_GT(checker, 0.0);
  ASSERT_NE(marble, checker);  // else the weighting would not show
  const double total = checker + marble + carPaint;
  EXPECT_NEAR(m.at(1).cutCostShare, 1.0, 1e-3);
  EXPECT_NEAR(m.at(2).cutCostShare, 0.984, 1e-3);
  EXPECT_NEAR(s.whole, checker / total, 1e-9);
  EXPECT_NEAR(s.world, marble / total, 1e-3);
  EXPECT_NEAR(s.uv, 0.984 * carPaint / total, 1e-3);
  EXPECT_EQ(s.object, 0.0);
  EXPECT_NEAR(s.total(), (checker + marble + 0.984 * carPaint) / total, 1e-3);
  const auto megakernelSwitch = share(CacheMode::Texel, false, MaterialDispatch::Switch);
  EXPECT_NEAR(megakernelSwitch.total(), s.total(), 1e-12);
}

TEST_F(CachedCostShare, CallablesAndTheTileCacheServeWholeGraphsOnly) {
  for (const auto& s : {share(CacheMode::Texel, false, MaterialDispatch::Callable),
                        share(CacheMode::Tile, true, MaterialDispatch::Callable)}) {
    const auto& m = materials_.linked.materials;
    EXPECT_NEAR(s.whole,
                m.at(0).estimatedCost /
                    (m.at(0).estimatedCost + m.at(1).estimatedCost + m.at(2).estimatedCost),
                1e-9);
    EXPECT_EQ(s.uv + s.object + s.world, 0.0);
  }
  EXPECT_EQ(share(CacheMode::None, true, MaterialDispatch::Callable).total(), 0.0);
}

}  // namespace
}  // namespace memograph::runtime
