// The pipeline stage of Renderer::render: the material cache (thesis §5.3, §5.4) and the
// shaders of the architecture the plan chose, compiled with the defines the scene, the cache
// and LiPaC ask for: the megakernel's trace pipelines (with callable material shaders on the
// pipeline backend) or the wavefront's passes.
#pragma once

#include <filesystem>
#include <memory>

#include "runtime/materials/scene_materials.h"
#include "runtime/memo/material_cache.h"
#include "runtime/renderer.h"
#include "runtime/scene/scene_resources.h"
#include "runtime/trace/frame_tracer.h"
#include "runtime/trace/render_setup.h"

namespace memograph::runtime {

struct RenderPipelines {
  std::unique_ptr<MaterialCache> cache;
  std::unique_ptr<FrameTracer> tracer;
};

// What the pipelines are built for besides the options and the plan.
struct PipelineInputs {
  const SceneMaterials* materials = nullptr;
  const SceneResources* scene = nullptr;
  bool hitFeedback = false;  // LiPaC counts: the feedback's pipeline (MG_HIT_FEEDBACK)
  std::filesystem::path shaderCacheDirectory;  // empty: compiled shaders are not kept
  // Integrator::AmbientOcclusion: its rays' length, resolved for the scene.
  float ambientOcclusionDistance = 0.0f;
  // Cycles' Filter Glossy the path tracer applies (RendererOptions::filterGlossy, else the
  // scene's); 0: off, and its code is not compiled in (MG_FILTER_GLOSSY_INVERSE).
  float filterGlossy = 0.0f;
};

// Compiles and creates everything; fills `stats`'s shader, cache and architecture figures.
RenderPipelines buildPipelines(const VulkanContext& context, const RendererOptions& options,
                               const RenderSettings& settings, const RenderPlan& plan,
                               const PipelineInputs& inputs, RenderStats& stats);

}  // namespace memograph::runtime
