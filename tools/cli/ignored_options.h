// Options that the chosen modes leave unused: LiPaC's settings under --culling none or
// frustum, the frustum's radius under the others, the cache's without --cache, the tile
// cache's with --cache texel. They are accepted (a script may pass one set of flags to every
// mode it measures), but `render` and `bench` name each on stderr, so that a forgotten
// --culling lipac or --cache tile does not silently measure something else.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "cli_common.h"
#include "runtime/renderer.h"

namespace memograph::cli {

// LiPaC's options (culling_arguments.h).
inline constexpr std::array<std::string_view, 13> kLipacOptions = {
    "--hitbox-size",         "--hitbox-activate",   "--hitbox-deactivate", "--instance-activate",
    "--instance-deactivate", "--low-frames",        "--feedback-every",    "--feedback-paths",
    "--feedback-stride",     "--feedback-dispatch", "--hit-counters",      "--looks",
    "--look-appearing"};
// The tile cache's options (cache_arguments.h), and those of both caches.
inline constexpr std::array<std::string_view, 7> kTileCacheOptions = {
    "--tile",      "--filter",     "--tile-storage", "--group-by-material",
    "--tile-fill", "--tile-queue", "--test-give-up"};
inline constexpr std::array<std::string_view, 10> kCacheOptions = {
    "--cache-entries", "--probe", "--eviction",    "--cache-read-check", "--mip-bias",
    "--value-format",  "--clock", "--clock-shift", "--snap-uv",          "--cache-secondary-only"};

// One line per option given that `options` leave unused: "--x is ignored: it needs ...".
inline std::vector<std::string> ignoredOptions(const ArgumentScanner& scanner,
                                               const runtime::RendererOptions& options) {
  std::vector<std::string> lines;
  const auto note = [&](const auto& names, std::string_view needs) {
    for (std::string_view name : names)
      if (scanner.given(name))
        lines.push_back(std::string(name) + " is ignored: it needs " + std::string(needs));
  };
  if (options.culling.mode != runtime::CullingMode::Lipac)
    note(kLipacOptions, "--culling lipac");
  if (options.culling.mode != runtime::CullingMode::Frustum)
    note(std::array<std::string_view, 1>{"--culling-radius"}, "--culling frustum");
  if (options.cache.mode == runtime::CacheMode::None) {
    note(kCacheOptions, "--cache texel or --cache tile");
    note(kTileCacheOptions, "--cache tile");
  } else if (options.cache.mode == runtime::CacheMode::Texel) {
    note(kTileCacheOptions, "--cache tile");
  }
  return lines;
}

}  // namespace memograph::cli
