// The culled acceleration structures' command-line options (seeds/001 §3.3), shared by
// `render` and `bench`.
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "cli_common.h"
#include "runtime/accel/scene_culling.h"

namespace memograph::cli {

inline constexpr const char* kCullingHelp =
    "  --culling C           which instances the TLAS holds each frame: none (default: all),\n"
    "                        frustum (those in the camera's frustum or within\n"
    "                        --culling-radius of it) or lipac (light-path-guided culling:\n"
    "                        hit counters from the last frame's rays activate hitboxes of\n"
    "                        a grid, so what is seen in a mirror or lights the view stays)\n"
    "  --culling-radius R    frustum: also keep instances within R of the camera (default 30)\n"
    "  --hitbox-size S       lipac: hitbox grid cell edge in x and z (default 50)\n"
    "  --hitbox-activate A   lipac: an inactive hitbox activates at A hits per million rays\n"
    "                        of the frame (default 20)\n"
    "  --hitbox-deactivate D lipac: an active hitbox deactivates after --low-frames\n"
    "                        counting frames below D hits per million rays (default 2)\n"
    "  --instance-activate A lipac: an instance with its own BLAS, omitted (a box counts its\n"
    "                        rays), activates at A hits per million rays (default 16)\n"
    "  --instance-deactivate D  lipac: and is omitted again below D (default 1.6)\n"
    "  --low-frames K        lipac: counting frames below a deactivation threshold before it\n"
    "                        acts (default 2; doubled each time it deactivates)\n"
    "  --feedback-every K    lipac: the trace counts every K-th frame; the frames between\n"
    "                        trace without the feedback's code and probes (default 4; 1:\n"
    "                        every frame; 1..64)\n"
    "  --feedback-paths N    lipac: N of each pixel's P paths count their rays in a counting\n"
    "                        frame, weighted P / N (N divides P; default 1; 0: every path)\n"
    "  --feedback-stride N   lipac: 1 in N 8x8-pixel blocks counts its rays in a counting\n"
    "                        frame, weighted N (default 1: every block; 1..64)\n"
    "  --feedback-dispatch split|single  lipac, with --feedback-paths below P: a counting\n"
    "                        frame traces the paths that do not count without the\n"
    "                        feedback's code, then those that do with it, in dispatches of\n"
    "                        their own (default split: on an H200 and an H100 its counting\n"
    "                        frames took 0.94x the unculled frame's time, in one dispatch\n"
    "                        1.12-1.13x), or all of them with it (single)\n"
    "  --hit-counters after-trace|closest-hit  lipac: the path rays' hit counters bumped\n"
    "                        after each trace, a run of rays that count the same instance\n"
    "                        written at once (default after-trace), or by the closest-hit\n"
    "                        shader, one atomic a ray (the pipeline backend only; --backend\n"
    "                        auto picks it). The same counts either way\n"
    "  --looks on|off        lipac: before the first frame, and before one that brings\n"
    "                        --look-appearing instances with their own BLAS into view at\n"
    "                        once, trace its camera once with the hitboxes it faces active\n"
    "                        and those instances as counting boxes, so the frame holds what\n"
    "                        its rays reach (default on); off: it holds every instance that\n"
    "                        appears large in its frustum, hidden ones too\n"
    "  --look-appearing N    lipac: instances appearing at once that call for a look\n"
    "                        (default 8)\n"
    "  --instance-fill host|gpu  culled or animated: the TLAS's instance records written by\n"
    "                        the host, or assembled by a compute pass from the instance\n"
    "                        states (the same records; default host)\n"
    "  --blas-budget MB      culled: evict BLASes no instance in the TLAS uses, least\n"
    "                        recently used first, past MB mebibytes (default: no limit)\n"
    "  --blas-build-budget T culled: build at most T triangles of BLASes a frame (at least\n"
    "                        one BLAS; default: no limit)\n"
    "  --blas-build-ms MS    culled: build at most MS GPU milliseconds of BLASes a frame, at\n"
    "                        the rate the builds so far took (at least one BLAS; the first\n"
    "                        frame times its first alone; the builds alone: not their\n"
    "                        compaction, nor the animated meshes' updates; default: no\n"
    "                        limit); what is built when then depends on the GPU's speed\n"
    "  --blas-keep-frames K  evict a BLAS no instance in the TLAS has used for K frames\n"
    "                        (default 2; 0: only --blas-budget evicts)\n"
    "  --blas-rebuild-every N  animated meshes (the city's flags): their BLASes are updated\n"
    "                        in place every frame and rebuilt every N frames (default 16)\n";

// The options stay empty unless given: parse() then keeps CullingOptions' own defaults (the
// measured ones, scene_culling.h), so that there is one place to change them.
struct CullingArguments {
  std::string mode = "none", radius, hitboxSize, hitboxActivate, hitboxDeactivate, instanceActivate,
              instanceDeactivate, lowFrames, blasBudget, blasBuildBudget, blasBuildMilliseconds,
              blasRebuildEvery, blasKeepFrames, feedbackStride, feedbackPaths, feedbackEvery,
              instanceFill, looks, lookAppearing, feedbackDispatch, hitCounters;

  // Each option, and the mode that uses it (the others leave it unused).
  enum class Uses { Any, Frustum, Lipac };
  struct Option {
    const char* name;
    std::string CullingArguments::*value;
    Uses uses;
  };
  static constexpr std::array<Option, 21> options() {
    using A = CullingArguments;
    return {{{"--culling", &A::mode, Uses::Any},
             {"--culling-radius", &A::radius, Uses::Frustum},
             {"--hitbox-size", &A::hitboxSize, Uses::Lipac},
             {"--hitbox-activate", &A::hitboxActivate, Uses::Lipac},
             {"--hitbox-deactivate", &A::hitboxDeactivate, Uses::Lipac},
             {"--instance-activate", &A::instanceActivate, Uses::Lipac},
             {"--instance-deactivate", &A::instanceDeactivate, Uses::Lipac},
             {"--low-frames", &A::lowFrames, Uses::Lipac},
             {"--blas-budget", &A::blasBudget, Uses::Any},
             {"--blas-build-budget", &A::blasBuildBudget, Uses::Any},
             {"--blas-build-ms", &A::blasBuildMilliseconds, Uses::Any},
             {"--blas-rebuild-every", &A::blasRebuildEvery, Uses::Any},
             {"--blas-keep-frames", &A::blasKeepFrames, Uses::Any},
             {"--feedback-stride", &A::feedbackStride, Uses::Lipac},
             {"--feedback-every", &A::feedbackEvery, Uses::Lipac},
             {"--feedback-paths", &A::feedbackPaths, Uses::Lipac},
             {"--feedback-dispatch", &A::feedbackDispatch, Uses::Lipac},
             {"--hit-counters", &A::hitCounters, Uses::Lipac},
             {"--instance-fill", &A::instanceFill, Uses::Any},
             {"--looks", &A::looks, Uses::Lipac},
             {"--look-appearing", &A::lookAppearing, Uses::Lipac}}};
  }

  void registerWith(ArgumentScanner& scanner) {
    for (const Option& o : options())
      scanner.option(o.name, &(this->*o.value));
  }

  // A note (ignoredOptionNote) for each option given that `mode` leaves unused.
  static std::vector<std::string> ignored(const ArgumentScanner& scanner,
                                          runtime::CullingMode mode) {
    std::vector<std::string> notes;
    for (const Option& o : options()) {
      if (!scanner.given(o.name))
        continue;
      if (o.uses == Uses::Frustum && mode != runtime::CullingMode::Frustum)
        notes.push_back(ignoredOptionNote(o.name, "--culling frustum"));
      if (o.uses == Uses::Lipac && mode != runtime::CullingMode::Lipac)
        notes.push_back(ignoredOptionNote(o.name, "--culling lipac"));
    }
    return notes;
  }

  // Throws std::invalid_argument with a message for the user.
  runtime::CullingOptions parse() const {
    runtime::CullingOptions o;
    o.mode = runtime::parseCullingMode(mode);
    auto real = [](const std::string& text, const char* flag) {
      double value = 0.0;
      if (!parseReal(text, value))
        throw std::invalid_argument(std::string(flag) + " takes a number, not '" + text + "'");
      return value;
    };
    auto whole = [](const std::string& text, const char* flag) {
      std::uint32_t value = 0;
      if (!parseNumber(text, value))
        throw std::invalid_argument(std::string(flag) + " takes a whole number, not '" + text +
                                    "'");
      return value;
    };
    // Each number given replaces its default.
    const auto setReal = [&](const std::string& text, const char* flag, auto& field) {
      if (!text.empty())
        field = static_cast<std::remove_reference_t<decltype(field)>>(real(text, flag));
    };
    const auto setWhole = [&](const std::string& text, const char* flag, std::uint32_t& field) {
      if (!text.empty())
        field = whole(text, flag);
    };
    setReal(radius, "--culling-radius", o.radius);
    setReal(hitboxSize, "--hitbox-size", o.hitboxSize);
    setReal(hitboxActivate, "--hitbox-activate", o.hitboxActivate);
    setReal(hitboxDeactivate, "--hitbox-deactivate", o.hitboxDeactivate);
    setReal(instanceActivate, "--instance-activate", o.instanceActivate);
    setReal(instanceDeactivate, "--instance-deactivate", o.instanceDeactivate);
    setWhole(lowFrames, "--low-frames", o.lowFrames);
    if (!blasBudget.empty())
      o.blasBudgetBytes = std::uint64_t(whole(blasBudget, "--blas-budget")) << 20;
    if (!blasBuildBudget.empty())
      o.blasBuildTriangles = whole(blasBuildBudget, "--blas-build-budget");
    setReal(blasBuildMilliseconds, "--blas-build-ms", o.blasBuildMilliseconds);
    setWhole(blasRebuildEvery, "--blas-rebuild-every", o.blasRebuildEvery);
    setWhole(blasKeepFrames, "--blas-keep-frames", o.blasKeepFrames);
    setWhole(feedbackStride, "--feedback-stride", o.feedbackStride);
    setWhole(feedbackEvery, "--feedback-every", o.feedbackEvery);
    setWhole(feedbackPaths, "--feedback-paths", o.feedbackPaths);
    setWhole(lookAppearing, "--look-appearing", o.lookAppearing);
    runtime::validateCullingOptions(o);
    return o;
  }
};

}  // namespace memograph::cli
