// The texel cache's command-line options (thesis §5.3), shared by `render` and `bench`.
#pragma once

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_common.h"
#include "runtime/renderer.h"

namespace memograph::cli {

inline constexpr const char* kCacheHelp =
    "  --cache C             material graph memoization: none (default), texel (thesis\n"
    "                        §5.3: one hash table of texels of cacheable materials) or tile\n"
    "                        (§5.4: entries are tiles, computed by a whole subgroup)\n"
    "  --cache-entries N     cache entries S: texels, or tiles with --cache tile\n"
    "                        (default 16777216 texels or 2097152 tiles, the best rows\n"
    "                        measured on an H200; halved until the cache fits one storage\n"
    "                        buffer and a quarter of the device's memory: 128 MiB on\n"
    "                        lavapipe; output says so)\n"
    "  --probe D             linear probing distance, 1..16 (default 8)\n"
    "  --eviction E          when a probe range is full: lru (default), lrw (least recently\n"
    "                        written; both by --clock), random, or none\n"
    "  --cache-read-check C  counter (default: an update counter per entry also catches a\n"
    "                        key restored meanwhile, §5.3.4) or key (read key, values, key);\n"
    "                        the wavefront's lookups need neither (no writer runs beside)\n"
    "  --mip-bias B          added to the cache's mip level (eq. 5.5); positive: finer\n"
    "  --tile WxH            texels per tile (default 4x4; W*H at most the subgroup size:\n"
    "                        32 on NVIDIA, 8 on lavapipe, with --tile-fill subgroup)\n"
    "  --filter F            tile sampling: nearest (default) or bilinear (tiles overlap by\n"
    "                        one texel, eq. 5.12-5.15)\n"
    "  --tile-storage S      where texels live (§5.4.1): entry (default), buffer,\n"
    "                        texture2d or texture3d\n"
    "  --group-by-material   compute missing tiles of one material together (§5.4.4)\n"
    "  --tile-fill F         who computes a missing tile: subgroup (the megakernel's\n"
    "                        default; §5.4.3, at once, one texel per lane) or deferred (queued; a "
    "second pass\n"
    "                        after the frame computes it for the next frame, and the\n"
    "                        requester evaluates its own hit; faster when the cache holds\n"
    "                        a frame's tiles, much slower when it does not). When the\n"
    "                        wavefront runs (--shading wavefront, or auto on a GPU) tiles\n"
    "                        are always queued and computed by the material passes of the\n"
    "                        bounce that missed them; an explicit subgroup makes auto pick\n"
    "                        the megakernel, and --shading wavefront refuse it\n"
    "  --tile-queue N        deferred fill: tiles queued per frame at most (default 65536)\n"
    "  --value-format F      fp32 (default) or fp16: entry values as 32-bit floats or two\n"
    "                        16-bit halves per word (§5.3.1; half the value memory)\n"
    "  --clock C             lru/lrw time: counter (a GPU atomic counter bumped per\n"
    "                        access, §5.3.3; the tile cache's default where the device\n"
    "                        has 64-bit buffer atomics) or frame (the frame number; the\n"
    "                        texel cache's default under lru: as good a hit rate, and\n"
    "                        faster)\n"
    "  --clock-shift S       counter clock: the entry keeps counter bits S..S+31 (default:\n"
    "                        lru about 2^10 ages a frame, 16 at 1080p P=6 L=4, §5.3.3;\n"
    "                        lrw 0, where only writes tick)\n"
    "  --snap-uv             evaluate a miss at its texel's centre with a texel's\n"
    "                        footprint (§6.1, eq. 5.16-5.17); makes a texel-cached render\n"
    "                        repeatable (otherwise the hit that stores a texel first, which\n"
    "                        thread order decides, sets its value; tiles are always\n"
    "                        computed so)\n"
    "  --cache-secondary-only  only bounces >= 1 use the cache; camera hits evaluate\n"
    "                        their graph directly (§6.1, Fig. 6.6)\n"
    "  --floor-materials     floor run: every material replaced by constants, no graph\n"
    "                        evaluated (the cost of a free material); with --cache, the\n"
    "                        cache's own cost: the same lookups, misses that cost nothing\n"
    "  --test-give-up PCT    test hook, tile cache with the subgroup fill: that share of the\n"
    "                        subgroup's tile computations is given up before any texel is\n"
    "                        stored, as after a callable repack on NVIDIA's raygen (about\n"
    "                        60 % of the tiles started on the classroom at 1080p); 0: off\n";

struct CacheArguments {
  std::string cache = "none", entries = "", probe = "8", eviction = "lru", mipBias = "0",
              readCheck = "counter", valueFormat = "fp32", clock = "", clockShift = "",
              tile = "4x4", filter = "nearest", tileStorage = "entry", tileFill = "",
              tileQueue = "65536", testGiveUp = "0";
  bool snapUv = false, secondaryOnly = false, floorMaterials = false, groupByMaterial = false;

  // Each option (a value, or a flag), and the caches that use it (without them it is unused).
  enum class Uses { Any, Cache, Tile };
  struct Option {
    const char* name;
    std::string CacheArguments::*value;
    bool CacheArguments::*flag;
    Uses uses;
  };
  static constexpr std::array<Option, 19> options() {
    using A = CacheArguments;
    return {{{"--cache", &A::cache, nullptr, Uses::Any},
             {"--cache-entries", &A::entries, nullptr, Uses::Cache},
             {"--probe", &A::probe, nullptr, Uses::Cache},
             {"--eviction", &A::eviction, nullptr, Uses::Cache},
             {"--mip-bias", &A::mipBias, nullptr, Uses::Cache},
             {"--cache-read-check", &A::readCheck, nullptr, Uses::Cache},
             {"--tile", &A::tile, nullptr, Uses::Tile},
             {"--filter", &A::filter, nullptr, Uses::Tile},
             {"--tile-storage", &A::tileStorage, nullptr, Uses::Tile},
             {"--group-by-material", nullptr, &A::groupByMaterial, Uses::Tile},
             {"--tile-fill", &A::tileFill, nullptr, Uses::Tile},
             {"--tile-queue", &A::tileQueue, nullptr, Uses::Tile},
             {"--value-format", &A::valueFormat, nullptr, Uses::Cache},
             {"--clock", &A::clock, nullptr, Uses::Cache},
             {"--clock-shift", &A::clockShift, nullptr, Uses::Cache},
             {"--snap-uv", nullptr, &A::snapUv, Uses::Cache},
             {"--cache-secondary-only", nullptr, &A::secondaryOnly, Uses::Cache},
             {"--floor-materials", nullptr, &A::floorMaterials, Uses::Any},
             {"--test-give-up", &A::testGiveUp, nullptr, Uses::Tile}}};
  }

  void registerWith(ArgumentScanner& scanner) {
    for (const Option& o : options()) {
      if (o.flag)
        scanner.flag(o.name, &(this->*o.flag));
      else
        scanner.option(o.name, &(this->*o.value));
    }
  }

  // A note (ignoredOptionNote) for each option given that `mode` leaves unused.
  static std::vector<std::string> ignored(const ArgumentScanner& scanner, runtime::CacheMode mode) {
    std::vector<std::string> notes;
    for (const Option& o : options()) {
      if (!scanner.given(o.name))
        continue;
      if (o.uses == Uses::Cache && mode == runtime::CacheMode::None)
        notes.push_back(ignoredOptionNote(o.name, "--cache texel or --cache tile"));
      if (o.uses == Uses::Tile && mode != runtime::CacheMode::Tile)
        notes.push_back(ignoredOptionNote(o.name, "--cache tile"));
    }
    return notes;
  }

  // Throws std::invalid_argument with a message for the user.
  runtime::CacheOptions parse() const {
    runtime::CacheOptions options;
    options.mode = runtime::parseCacheMode(cache);
    options.eviction = runtime::parseCacheEviction(eviction);
    options.valueFormat = runtime::parseCacheValueFormat(valueFormat);
    if (!clock.empty())
      options.clock = runtime::parseCacheClock(clock);
    options.snapUv = snapUv;
    options.secondaryOnly = secondaryOnly;
    if (readCheck != "key" && readCheck != "counter")
      throw std::invalid_argument("unknown --cache-read-check '" + readCheck +
                                  "' (choose key or counter)");
    options.updateCounter = readCheck == "counter";
    options.tileFilter = runtime::parseTileFilter(filter);
    options.tileStorage = runtime::parseTileStorage(tileStorage);
    options.groupByMaterial = groupByMaterial;
    if (!tileFill.empty())  // unset: subgroup, or the wavefront's queue (renderer.cpp)
      options.tileFill = runtime::parseTileFill(tileFill);
    auto whole = [](const std::string& text, const char* name) {
      std::uint32_t value = 0;
      if (!parseNumber(text, value))
        throw std::invalid_argument(std::string(name) + " takes a whole number, not '" + text +
                                    "'");
      return value;
    };
    if (!entries.empty())
      options.entries = whole(entries, "--cache-entries");
    options.probe = whole(probe, "--probe");
    if (!clockShift.empty())
      options.clockShift = whole(clockShift, "--clock-shift");
    options.tileQueue = whole(tileQueue, "--tile-queue");
    const std::uint32_t giveUp = whole(testGiveUp, "--test-give-up");
    if (giveUp > 100)
      throw std::invalid_argument("--test-give-up must be 0..100 %, not " + testGiveUp);
    options.testRepacks = giveUp > 0;
    options.testRepackPercent = giveUp > 0 ? giveUp : 100;
    const auto x = tile.find('x');
    if (x == std::string::npos)
      throw std::invalid_argument("--tile takes WxH (e.g. 4x4), not '" + tile + "'");
    options.tileWidth = whole(tile.substr(0, x), "--tile's width");
    options.tileHeight = whole(tile.substr(x + 1), "--tile's height");
    double bias = 0.0;
    if (!parseReal(mipBias, bias) || std::abs(bias) > 64.0)
      throw std::invalid_argument("--mip-bias takes a number (-64..64), not '" + mipBias + "'");
    options.mipBias = float(bias);
    runtime::validateCacheOptions(options);  // the renderer's own ranges and messages
    return options;
  }
};

}  // namespace memograph::cli
