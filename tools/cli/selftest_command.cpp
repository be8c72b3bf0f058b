// memograph selftest: the cache's concurrency stress test (thesis §5.3.4) on this machine's
// GPU, in every read-check and storage mode, with the torn reads of each, then the tile
// cache's subgroup fill (§5.4.3: tiles published by their last texel's count). Runs from the
// device bundle, so the GPU machine can check the memory ordering lavapipe cannot show.
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_common.h"
#include "commands.h"
#include "runtime/vk/vulkan_context.h"
#include "tools/selftest/cache_selftest.h"

namespace memograph::cli {

namespace {

// The tile configurations with given-up tiles (tileFillStressConfigurations) give an
// iteration's tiles up from pass 0, 1, ... of a tile, then two iterations not at all; a
// tile takes at most 4 passes (a quarter of the lanes computing), so iterations 0 to 3 may
// publish nothing, the 5th publishes and the 6th reads. Fewer, and the run checks nothing
// (it failed with "nothing published or read").
constexpr std::uint32_t kMinIterations = 6;

}  // namespace

int runSelftest(std::span<const std::string_view> args) {
  std::string iterationsText = "256", invocationsText = "4096", roundsText = "1";
  ArgumentScanner scanner("selftest", args);
  scanner.option("--iterations", &iterationsText);
  scanner.option("--invocations", &invocationsText);
  scanner.option("--rounds", &roundsText);
  scanner.help(
      "usage: memograph selftest [--invocations N] [--iterations N] [--rounds N]\n\n"
      "The material cache's concurrency stress test on this GPU: N invocations\n"
      "(default 4096, a multiple of 64) of N lookups each (default 256, at least 6)\n"
      "on 32 entries, in the key, counter, image-key, image-counter and unprotected\n"
      "modes, --rounds times each (default 1). Prints the torn reads per mode; exits 1\n"
      "when the update counter (the renderer's protocol) tore. The key check and no\n"
      "protection are demonstrations of the tears the counter prevents: reported, not\n"
      "failed. Then the tile cache's subgroup fill, the same way, in every tile\n"
      "storage, with several tiles an iteration, several passes a tile and given-up\n"
      "tiles: exits 1 when a tile read tore or a tile was not published exactly once\n"
      "with all its texels (or given back empty). The log goes to stdout, each\n"
      "failure also to stderr; exits 2 on a usage error.\n");
  std::vector<std::string> positional;
  if (const auto exitCode = scanner.scan(positional))
    return *exitCode;
  if (!positional.empty())
    return usageError("selftest", "takes no positional arguments");
  std::uint32_t iterations = 0, invocations = 0, rounds = 0;
  if (!parseNumber(iterationsText, iterations) || iterations > 65536)
    return usageError("selftest", "--iterations takes " + std::to_string(kMinIterations) +
                                      "..65536, not '" + iterationsText + "'");
  if (iterations < kMinIterations)
    return usageError("selftest",
                      "--iterations " + iterationsText +
                          " is too few: the tile fill's given-up "
                          "tiles publish nothing before the 5th iteration, so give --iterations " +
                          std::to_string(kMinIterations) + " or more (default 256)");
  if (!parseNumber(invocationsText, invocations) || invocations == 0 || invocations % 64 != 0 ||
      invocations > (1u << 24))
    return usageError(
        "selftest",
        "--invocations takes a multiple of 64 from 64 to 16777216, not '" + invocationsText + "'");
  if (!parseNumber(roundsText, rounds) || rounds == 0 || rounds > 1000)
    return usageError("selftest", "--rounds takes 1..1000, not '" + roundsText + "'");
  try {
    runtime::VulkanContext context(runtime::ContextOptions{});
    std::printf("device: %s\n", context.info().name.c_str());
    std::printf("mode,round,invocations,iterations,hits,misses,torn,occupancy\n");
    bool protectedTore = false;
    // Each failure, for stderr at the end: stdout is the log a sweep keeps, with the same
    // lines marked "FAILED" in place.
    std::vector<std::string> failures;
    for (runtime::CacheStressMode mode :
         {runtime::CacheStressMode::Key, runtime::CacheStressMode::Counter,
          runtime::CacheStressMode::ImageKey, runtime::CacheStressMode::ImageCounter,
          runtime::CacheStressMode::Unprotected}) {
      std::uint64_t hits = 0, torn = 0;
      for (std::uint32_t round = 0; round < rounds; ++round) {
        runtime::CacheStressResult r =
            runtime::runCacheStress(context, mode, invocations, iterations);
        std::printf("%s,%u,%u,%u,%u,%u,%u,%u\n", runtime::cacheStressModeName(mode), round,
                    r.invocations, r.iterations, r.hits, r.misses, r.torn, r.occupancy);
        hits += r.hits;
        torn += r.torn;
      }
      const bool mustNotTear = runtime::cacheStressModeMustNotTear(mode);
      std::printf("# %s: %llu torn reads of %llu hits%s\n", runtime::cacheStressModeName(mode),
                  (unsigned long long)torn, (unsigned long long)hits,
                  mustNotTear ? "" : " (a demonstration: this check is not the renderer's)");
      if (mustNotTear && torn > 0) {
        protectedTore = true;
        failures.push_back(std::string(runtime::cacheStressModeName(mode)) + ": " +
                           std::to_string(torn) + " torn reads of " + std::to_string(hits) +
                           " hits (a protected mode must tear none)");
      }
    }
    // The tile cache's subgroup fill (§5.4.3): each tile published by its last texel.
    bool tileFailed = false, nothingExercised = false;
    std::printf(
        "mode,round,invocations,iterations,tile,lanes,passes,hits,misses,torn,served,wrong_served,"
        "tiles_computed,published,given_up,duplicates,left_locked,left_counts,occupancy,"
        "entries_in_use\n");
    for (const runtime::TileFillStressOptions& options : runtime::tileFillStressConfigurations()) {
      const std::string name = runtime::tileFillStressName(options);
      std::uint64_t hits = 0, torn = 0, published = 0;
      std::string roundFailures;
      for (std::uint32_t round = 0; round < rounds; ++round) {
        runtime::TileFillStressResult r;
        try {
          r = runtime::runTileFillStress(context, options, invocations, iterations);
        } catch (const std::invalid_argument& e) {
          std::printf("# %s: skipped, %s\n", name.c_str(), e.what());
          break;
        }
        std::printf("%s,%u,%u,%u,%ux%u,%u,%u,%u,%u,%u,%u,%u,%u,%u,%u,%u,%u,%u,%u,%u\n",
                    name.c_str(), round, r.invocations, r.iterations, r.tileWidth, r.tileHeight,
                    r.computingLanes, r.passes, r.hits, r.misses, r.torn, r.served, r.wrongServed,
                    r.tilesComputed, r.tilesPublished, r.tilesGivenUp, r.duplicateTiles,
                    r.entriesLocked, r.countsLeft, r.occupancy, r.entriesFilled);
        hits += r.hits;
        torn += r.torn;
        published += r.tilesPublished;
        if (r.tilesPublished == 0 || r.hits == 0)
          nothingExercised = true;
        if (const std::string why = r.failure(); !why.empty())
          roundFailures += (roundFailures.empty() ? "" : " | ") +
                           ("round " + std::to_string(round) + ": " + why);
      }
      std::printf("# %s: %llu torn reads of %llu hits, %llu tiles published%s%s\n", name.c_str(),
                  (unsigned long long)torn, (unsigned long long)hits, (unsigned long long)published,
                  roundFailures.empty() ? "" : "; FAILED: ", roundFailures.c_str());
      if (!roundFailures.empty()) {
        tileFailed = true;
        failures.push_back(name + ": " + roundFailures);
      }
    }
    std::fflush(stdout);
    for (const std::string& failure : failures)
      std::cerr << "memograph selftest: FAILED: " << failure << "\n";
    if (nothingExercised)
      std::cerr << "memograph selftest: a configuration published or read no tile: the run "
                   "was too small to check it; raise --invocations or --iterations (defaults "
                   "4096 and 256)\n";
    return protectedTore || tileFailed ? kExitFailure : kExitOk;
  } catch (const std::exception& e) {
    std::cerr << "memograph selftest: " << e.what() << "\n";
    return kExitFailure;
  }
}

}  // namespace memograph::cli
