// The one table of `render`'s and `bench`'s options, and what reads it: the scanner that
// parses each value by its declared type, the help, and the notes for unused options.
#ifdef MEMOGRAPH_HAVE_RUNTIME

#include "option_table.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <stdexcept>

#include "cli_common.h"

namespace memograph::cli {

namespace {

// How a value is read. Choice: one of the words in the metavar ("none|texel|tile").
enum class ValueType { Flag, Choice, Whole, Real, Path, Text, ImageSize, SizeList, TileSize };

// Where an option's help stands.
enum class Section { InputOutput, Image, Memoization, Culling, Device };
constexpr std::string_view kSectionTitles[] = {"Input and output", "Image and frames",
                                               "Material memoization (thesis §5.3, §5.4)",
                                               "Culling (seeds/001 §3.3)", "Device and shading"};

// The mode an option needs; given without it, the option is named as ignored.
enum class Needs { Nothing, Cache, TileCache, Frustum, Lipac, Megakernel, AmbientOcclusion };

constexpr unsigned kRender = 1, kBench = 2, kBoth = kRender | kBench;

// A value read from the command line, as its type gives it.
struct Value {
  bool flag = false;
  std::string text;
  std::uint32_t whole = 0;
  double real = 0.0;
  std::vector<ImageSize> sizes;  // ImageSize and TileSize: one
};

using Apply = void (*)(TraceCommandOptions&, const Value&);

struct Option {
  std::string_view name;
  ValueType type;
  std::string_view metavar;  // Choice: the choices, '|' between them
  std::string_view help;     // wrapped with the default to at most two lines (a test checks)
  // Shown as "(default X)". `tableDefault`: the CLI's own default, applied (parsed as a
  // given value would be) before the arguments; otherwise the runtime's, shown only.
  std::string_view defaultText;
  bool tableDefault;
  Section section;
  bool advanced;  // listed by --help-all only
  Needs needs;
  unsigned commands;
  Apply apply;
  // What the value must be, for errors: "--x takes <takes>, not 'v'"; empty: by its type.
  std::string_view takes = {};
  double min = -std::numeric_limits<double>::infinity();  // Whole and Real: the range
  double max = std::numeric_limits<double>::infinity();
  std::string_view alias = {};         // another name for it ("-o")
  std::string_view benchDefault = {};  // bench's default, where it differs
  std::string_view benchHelp = {};     // bench's help, where it differs
};

constexpr std::uint32_t kMaxFramesInRange = 1000000;

// "A:B" with A <= B, both whole numbers. Throws std::invalid_argument for the user.
FrameRange parseFrameRange(std::string_view text) {
  const auto refuse = [&](std::string_view why) -> FrameRange {
    throw std::invalid_argument(
        "--frame-range takes A:B, the first and last frame (whole "
        "numbers, A <= B), not '" +
        std::string(text) + "'" + std::string(why));
  };
  const std::size_t colon = text.find(':');
  FrameRange range;
  if (colon == std::string_view::npos || !parseNumber(text.substr(0, colon), range.first) ||
      !parseNumber(text.substr(colon + 1), range.last))
    return refuse("");
  if (range.first > range.last)
    return refuse(": the last frame comes before the first");
  // One run's frames are planned as a list (which to write, which are done): a bound keeps a
  // mistyped range from asking for gigabytes of it. A farm splits a longer path into ranges.
  if (range.last - range.first >= kMaxFramesInRange)
    return refuse(": at most " + std::to_string(kMaxFramesInRange) + " frames in one range");
  return range;
}

using O = TraceCommandOptions;
using S = Section;
using N = Needs;
constexpr bool kAdvanced = true, kCommon = false, kApplied = true, kShown = false;

// The options. Those the thesis's tables vary (eviction, clock, thresholds, budgets, ...)
// are advanced: --help-all lists them.
const Option kOptions[] = {
    // Input and output.
    {"--out", ValueType::Path, "FILE",
     "the image: .pfm, or .png or .exr in builds with OpenImageIO; with\n"
     "--frame-range, a run of '#' in the name is the frame's index, zero-padded",
     "", kShown, S::InputOutput, kCommon, N::Nothing, kRender,
     [](O& o, const Value& v) { o.out = v.text; }, {}, 0, 0, "-o"},
    {"--materials", ValueType::Path, "DIR", "folder of .mgraph graphs for a scene file's materials",
     "", kShown, S::InputOutput, kCommon, N::Nothing, kRender,
     [](O& o, const Value& v) { o.materials = v.text; }},
    {"--nodes", ValueType::Path, "DIR", "node library folder instead of the built-in one", "",
     kShown, S::InputOutput, kCommon, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.renderer.nodeLibraryDirectory = v.text; }},
    {"--camera-path", ValueType::Path, "FILE",
     "one camera per frame: lines 'px py pz  tx ty tz  fov'", "", kShown, S::InputOutput,
     kCommon, N::Nothing, kRender, [](O& o, const Value& v) { o.cameraPath = v.text; }},
    {"--environment", ValueType::Path, "FILE",
     "equirectangular environment image (linear radiance, e.g. .exr, .hdr)\n"
     "replacing the scene's sky or its own image",
     "", kShown, S::InputOutput, kCommon, N::Nothing, kRender,
     [](O& o, const Value& v) { o.environment = v.text; }},
    {"--stats", ValueType::Path, "FILE",
     "per-frame statistics as CSV (GPU ms, rays, AS memory, cache)", "", kShown,
     S::InputOutput, kCommon, N::Nothing, kRender,
     [](O& o, const Value& v) { o.stats = v.text; }},
    {"--debug-misses", ValueType::Flag, "",
     "cache debug view (thesis Fig. 6.9): each frame alone, red where a path\n"
     "of the pixel missed the cache; needs --cache",
     "", kShown, S::InputOutput, kCommon, N::Nothing, kRender,
     [](O& o, const Value&) { o.debugMisses = true; }},
    {"--debug-culling", ValueType::Path, "FILE",
     "also write a 512x512 top view of the last frame's instances (orange active,\n"
     "yellow omitted, grey inactive, blue: inactive hitboxes, red: the camera)",
     "", kShown, S::InputOutput, kCommon, N::Nothing, kRender,
     [](O& o, const Value& v) { o.debugCulling = v.text; }},
    {"--csv", ValueType::Path, "FILE", "one line per scene and size", "", kShown, S::InputOutput,
     kCommon, N::Nothing, kBench, [](O& o, const Value& v) { o.csv = v.text; }},
    {"--frames-csv", ValueType::Path, "PREFIX",
     "per-frame statistics to PREFIX<scene>[_<label>]_<W>x<H>.csv", "", kShown, S::InputOutput,
     kCommon, N::Nothing, kBench, [](O& o, const Value& v) { o.framesCsv = v.text; }},
    {"--pipeline-statistics", ValueType::Path, "FILE",
     "the driver's statistics of each pipeline it compiled (registers,\n"
     "spills, ...), one CSV line per statistic",
     "", kShown, S::InputOutput, kAdvanced, N::Nothing, kBench,
     [](O& o, const Value& v) {
       o.pipelineStatistics = v.text;
       o.renderer.context.pipelineStatistics = true;
     }},
    {"--label", ValueType::Text, "NAME",
     "names the run in the output, the CSV and the per-frame file names\n"
     "(letters, digits, '.', '_', '-')",
     "", kShown, S::InputOutput, kCommon, N::Nothing, kBench,
     [](O& o, const Value& v) {
       if (!std::all_of(v.text.begin(), v.text.end(), [](char c) {
             return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' ||
                    c == '-';
           }))
         throw std::invalid_argument("--label takes letters, digits, '.', '_' and '-' only, not '" +
                                     v.text + "'");
       o.label = v.text;
     }},

    // Image and frames.
    {"--size", ValueType::ImageSize, "WxH", "image size", "640x360", kApplied, S::Image, kCommon,
     N::Nothing, kRender,
     [](O& o, const Value& v) {
       o.settings.width = v.sizes[0].width;
       o.settings.height = v.sizes[0].height;
     }},
    {"--sizes", ValueType::SizeList, "WxH,...", "image sizes, each run in turn", "1920x1080",
     kApplied, S::Image, kCommon, N::Nothing, kBench, [](O& o, const Value& v) { o.sizes = v.sizes; },
     {}, 0, 0, "--size"},
    {"--paths", ValueType::Whole, "P", "paths per pixel per frame", "1", kApplied, S::Image,
     kCommon, N::Nothing, kBoth, [](O& o, const Value& v) { o.settings.pathsPerPixel = v.whole; },
     "a whole number > 0", 1, std::numeric_limits<std::uint32_t>::max(), {}, "6"},
    {"--bounces", ValueType::Whole, "L", "rays per path; 1: the primary hit with direct light",
     "4", kApplied, S::Image, kCommon, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.settings.raysPerPath = v.whole; }, "a whole number > 0", 1},
    {"--filter-glossy", ValueType::Real, "F",
     "Cycles' Filter Glossy: after bounces of pdf p < F, glossy lobes get\n"
     "alpha >= sqrt(1 - p/F)/2; 0: off",
     "a Blender export's, else 0", kShown, S::Image, kCommon, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.renderer.filterGlossy = float(v.real); },
     "a number >= 0", 0, 3.0e38},
    {"--frames", ValueType::Whole, "F",
     "frames; a static camera accumulates them", "1", kApplied, S::Image, kCommon, N::Nothing,
     kBoth, [](O& o, const Value& v) { o.settings.frames = v.whole; }, "a whole number > 0", 1,
     std::numeric_limits<std::uint32_t>::max(), {}, "20", "timed frames"},
    {"--frame-range", ValueType::Text, "A:B",
     "frames A..B of the camera path, one image each (--out frame_####.pfm);\n"
     "a frame's random numbers depend on its index and --seed alone",
     "", kShown, S::Image, kCommon, N::Nothing, kRender,
     [](O& o, const Value& v) { o.frameRange = parseFrameRange(v.text); }},
    {"--warmup-frames", ValueType::Whole, "N",
     "with --cache or --culling lipac, a range first renders the N frames\n"
     "before it, unwritten, to warm them",
     "8", kApplied, S::Image, kCommon, N::Nothing, kRender,
     [](O& o, const Value& v) { o.warmupFrames = v.whole; }},
    {"--resume", ValueType::Flag, "",
     "with --frame-range, skip the frames whose files are complete (a requeued job)", "",
     kShown, S::Image, kCommon, N::Nothing, kRender, [](O& o, const Value&) { o.resume = true; }},
    {"--seed", ValueType::Whole, "S", "random seed", "0", kApplied, S::Image, kCommon,
     N::Nothing, kRender, [](O& o, const Value& v) { o.settings.seed = v.whole; }},
    {"--warmup", ValueType::Whole, "W",
     "untimed frames first, along the camera path up to its first camera\n"
     "(the path is a closed loop)",
     "3", kApplied, S::Image, kCommon, N::Nothing, kBench,
     [](O& o, const Value& v) { o.warmup = v.whole; }},
    {"--camera-frames", ValueType::Whole, "N", "cameras on the camera path: its length in frames",
     "F x K", kShown, S::Image, kCommon, N::Nothing, kBench,
     [](O& o, const Value& v) { o.cameraFrames = v.whole; }, "a whole number > 0", 1},
    {"--frame-stride", ValueType::Whole, "K",
     "time every K-th camera of the path only; needs --cache none (a cached\n"
     "frame depends on the frames before it)",
     "1", kApplied, S::Image, kCommon, N::Nothing, kBench,
     [](O& o, const Value& v) { o.frameStride = v.whole; }, "a whole number > 0", 1},
    {"--static-camera", ValueType::Flag, "", "keep the scene's camera still (no camera path)", "",
     kShown, S::Image, kCommon, N::Nothing, kBench,
     [](O& o, const Value&) { o.staticCamera = true; }},
    {"--time-limit", ValueType::Real, "S",
     "stop once the bench has run S seconds (wall time, set-up included) after\n"
     "the current frame; the summary and CSV say it stopped early",
     "none", kShown, S::Image, kCommon, N::Nothing, kBench,
     [](O& o, const Value& v) { o.timeLimitSeconds = v.real; }, "seconds (a number >= 0)", 0},
    {"--integrator", ValueType::Choice, "path|ao",
     "path-traced radiance, or ao: the unoccluded fraction of --ao-samples\n"
     "cosine-weighted rays from the primary hit (seeds/004 §3)",
     "path", kShown, S::Image, kCommon, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.renderer.integrator = runtime::parseIntegrator(v.text); }},
    {"--ao-distance", ValueType::Real, "D",
     "--integrator ao: an AO ray's length (world units); 0: a tenth of the\n"
     "diagonal of the scene's bounds",
     "0", kShown, S::Image, kCommon, N::AmbientOcclusion, kBoth,
     [](O& o, const Value& v) { o.renderer.ambientOcclusion.distance = float(v.real); },
     "a distance (a number >= 0)", 0, 3.0e38},
    {"--ao-samples", ValueType::Whole, "N",
     "--integrator ao: AO rays from each path's primary hit", "16", kShown, S::Image, kCommon,
     N::AmbientOcclusion, kBoth,
     [](O& o, const Value& v) { o.renderer.ambientOcclusion.samples = v.whole; },
     "a number of rays (1..4096)", 1, 4096},
    {"--shared-primary", ValueType::Flag, "",
     "one primary ray through the pixel centre for all P paths of a pixel (§5.1)", "", kShown,
     S::Image, kCommon, N::Nothing, kBoth,
     [](O& o, const Value&) { o.settings.sharedPrimaryRay = true; }},
    {"--no-emissive-nee", ValueType::Flag, "",
     "no light sampling of emissive triangles (BSDF rays only)", "", kShown, S::Image, kCommon,
     N::Nothing, kBoth, [](O& o, const Value&) { o.noEmissiveNee = true; }},

    // Material memoization.
    {"--cache", ValueType::Choice, "none|texel|tile",
     "memoize material graphs: texel (§5.3, a hash table of texels) or\n"
     "tile (§5.4, tiles of texels, each computed by a subgroup)",
     "none", kShown, S::Memoization, kCommon, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.renderer.cache.mode = runtime::parseCacheMode(v.text); }},
    {"--cache-entries", ValueType::Whole, "N",
     "cache entries: texels, or tiles with --cache tile; the default\n"
     "halves until it fits a storage buffer and 1/4 of device memory",
     "2^24 or 2^21", kShown, S::Memoization, kCommon, N::Cache, kBoth,
     [](O& o, const Value& v) { o.renderer.cache.entries = v.whole; }},
    {"--snap-uv", ValueType::Flag, "",
     "evaluate a miss at its texel's centre with a texel's footprint (§6.1,\n"
     "eq. 5.16-5.17): a texel-cached render becomes repeatable",
     "", kShown, S::Memoization, kCommon, N::Cache, kBoth,
     [](O& o, const Value&) { o.renderer.cache.snapUv = true; }},
    {"--cache-filter", ValueType::Choice, "nearest|trilinear|stochastic",
     "the nearest entry; the 8 texels (16 voxels) of 2 levels, blended;\n"
     "or one of them by weight",
     "nearest", kShown, S::Memoization, kAdvanced, N::Cache, kBoth,
     [](O& o, const Value& v) { o.renderer.cache.filter = runtime::parseCacheFilter(v.text); }},
    {"--cache-keys", ValueType::Text, "all|uv,object,world",
     "the key domains the cache takes; a material keyed in another runs\n"
     "uncached (uv also holds the whole uv-only materials)",
     "all", kShown, S::Memoization, kAdvanced, N::Cache, kBoth,
     [](O& o, const Value& v) {
       o.renderer.cache.keyDomains = runtime::parseCacheKeyDomains(v.text);
     }},
    {"--floor-materials", ValueType::Flag, "",
     "every material replaced by constants (the cost of a free material); with\n"
     "--cache, the cache's own cost: the same lookups, misses that cost nothing",
     "", kShown, S::Memoization, kCommon, N::Nothing, kBoth,
     [](O& o, const Value&) { o.renderer.floorMaterials = true; }},
    {"--probe", ValueType::Whole, "D", "linear probing distance, 1..16", "8", kShown,
     S::Memoization, kAdvanced, N::Cache, kBoth,
     [](O& o, const Value& v) { o.renderer.cache.probe = v.whole; }},
    {"--eviction", ValueType::Choice, "lru|lrw|random|none",
     "what a miss replaces in a full probe range (§4.5): the\n"
     "least recently used or written (by --clock), random, or none",
     "lru", kShown, S::Memoization, kAdvanced, N::Cache, kBoth,
     [](O& o, const Value& v) { o.renderer.cache.eviction = runtime::parseCacheEviction(v.text); }},
    {"--clock", ValueType::Choice, "counter|frame",
     "lru and lrw time (§5.3.3): a GPU atomic counter bumped per access, or the\n"
     "frame number",
     "frame for texel lru, else counter", kShown, S::Memoization, kAdvanced, N::Cache, kBoth,
     [](O& o, const Value& v) { o.renderer.cache.clock = runtime::parseCacheClock(v.text); }},
    {"--mip-bias", ValueType::Real, "B", "added to the cache's mip level (eq. 5.5); positive: finer",
     "0", kShown, S::Memoization, kAdvanced, N::Cache, kBoth,
     [](O& o, const Value& v) { o.renderer.cache.mipBias = float(v.real); }, "a number (-64..64)",
     -64, 64},
    {"--value-format", ValueType::Choice, "fp32|fp16",
     "entry values as 32-bit floats or two 16-bit halves a word (§5.3.1)", "fp32", kShown,
     S::Memoization, kAdvanced, N::Cache, kBoth,
     [](O& o, const Value& v) {
       o.renderer.cache.valueFormat = runtime::parseCacheValueFormat(v.text);
     }},
    {"--cache-refresh", ValueType::Whole, "N",
     "texel cache, nearest: refill each key at another point of its cell\n"
     "every N frames; 0: never",
     "16 for object/world keys, 0 for uv", kShown, S::Memoization, kAdvanced, N::Cache, kBoth,
     [](O& o, const Value& v) { o.renderer.cache.refreshFrames = v.whole; },
     "a number of frames (0..65536)", 0, 65536},
    {"--cache-secondary-only", ValueType::Flag, "",
     "only bounces >= 1 use the cache; camera hits evaluate their graph\n"
     "(§6.1, Fig. 6.6)",
     "", kShown, S::Memoization, kAdvanced, N::Cache, kBoth,
     [](O& o, const Value&) { o.renderer.cache.secondaryOnly = true; }},
    {"--tile", ValueType::TileSize, "WxH",
     "texels per tile; W*H at most the subgroup size with the subgroup fill", "4x4", kShown,
     S::Memoization, kAdvanced, N::TileCache, kBoth,
     [](O& o, const Value& v) {
       o.renderer.cache.tileWidth = v.sizes[0].width;
       o.renderer.cache.tileHeight = v.sizes[0].height;
     }},
    {"--filter", ValueType::Choice, "nearest|bilinear",
     "tile sampling; bilinear tiles overlap by one texel (eq. 5.12-5.15)", "nearest", kShown,
     S::Memoization, kAdvanced, N::TileCache, kBoth,
     [](O& o, const Value& v) { o.renderer.cache.tileFilter = runtime::parseTileFilter(v.text); }},
    {"--tile-storage", ValueType::Choice, "entry|buffer|texture2d|texture3d",
     "where a tile's texels live (§5.4.1)", "entry", kShown, S::Memoization, kAdvanced,
     N::TileCache, kBoth,
     [](O& o, const Value& v) {
       o.renderer.cache.tileStorage = runtime::parseTileStorage(v.text);
     }},
    {"--group-by-material", ValueType::Flag, "",
     "compute the missing tiles of one material together (§5.4.4)", "", kShown, S::Memoization,
     kAdvanced, N::TileCache, kBoth,
     [](O& o, const Value&) { o.renderer.cache.groupByMaterial = true; }},
    {"--tile-fill", ValueType::Choice, "subgroup|deferred",
     "who computes a missing tile: its subgroup at once (§5.4.3),\n"
     "or a pass after the frame, from a queue (as the wavefront)",
     "subgroup", kShown, S::Memoization, kAdvanced, N::TileCache, kBoth,
     [](O& o, const Value& v) { o.renderer.cache.tileFill = runtime::parseTileFill(v.text); }},
    {"--tile-queue", ValueType::Whole, "N", "deferred fill: tiles queued per frame at most",
     "65536", kShown, S::Memoization, kAdvanced, N::TileCache, kBoth,
     [](O& o, const Value& v) { o.renderer.cache.tileQueue = v.whole; }},

    // Culling.
    {"--culling", ValueType::Choice, "none|frustum|lipac",
     "which instances the TLAS holds a frame: all, those in the\n"
     "camera's frustum, or light-path-guided culling's (LiPaC)",
     "none", kShown, S::Culling, kCommon, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.mode = runtime::parseCullingMode(v.text); }},
    {"--culling-radius", ValueType::Real, "R", "frustum: also keep instances within R of the camera",
     "30", kShown, S::Culling, kCommon, N::Frustum, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.radius = float(v.real); }},
    {"--hitbox-size", ValueType::Real, "S", "lipac: hitbox grid cell edge in x and z", "50",
     kShown, S::Culling, kAdvanced, N::Lipac, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.hitboxSize = float(v.real); }},
    {"--hitbox-activate", ValueType::Real, "A",
     "lipac: an inactive hitbox activates at A hits per million rays", "20", kShown, S::Culling,
     kAdvanced, N::Lipac, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.hitboxActivate = v.real; }},
    {"--hitbox-deactivate", ValueType::Real, "D",
     "lipac: an active hitbox deactivates below D hits per million rays", "2", kShown,
     S::Culling, kAdvanced, N::Lipac, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.hitboxDeactivate = v.real; }},
    {"--instance-activate", ValueType::Real, "A",
     "lipac: an omitted instance with its own BLAS activates at A hits per\n"
     "million rays",
     "16", kShown, S::Culling, kAdvanced, N::Lipac, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.instanceActivate = v.real; }},
    {"--instance-deactivate", ValueType::Real, "D", "lipac: and is omitted again below D", "1.6",
     kShown, S::Culling, kAdvanced, N::Lipac, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.instanceDeactivate = v.real; }},
    {"--low-frames", ValueType::Whole, "K",
     "lipac: counting frames below a deactivation threshold before it acts\n"
     "(doubled each time it deactivates, at most 16 K; decays back)",
     "2", kShown, S::Culling, kAdvanced, N::Lipac, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.lowFrames = v.whole; }},
    {"--feedback-every", ValueType::Whole, "K",
     "lipac: the trace counts rays every K-th frame (1..64)", "4", kShown, S::Culling, kAdvanced,
     N::Lipac, kBoth, [](O& o, const Value& v) { o.renderer.culling.feedbackEvery = v.whole; }},
    {"--feedback-paths", ValueType::Whole, "N",
     "lipac: N of a pixel's P paths count their rays, weighted P / N (N divides\n"
     "P; 0: every path)",
     "1", kShown, S::Culling, kAdvanced, N::Lipac, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.feedbackPaths = v.whole; }},
    {"--feedback-stride", ValueType::Whole, "N",
     "lipac: 1 in N 8x8-pixel blocks counts its rays, weighted N (1..64)", "1", kShown,
     S::Culling, kAdvanced, N::Lipac, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.feedbackStride = v.whole; }},
    {"--look-appearing", ValueType::Whole, "N",
     "lipac: this many instances coming into view at once make the frame first\n"
     "trace its camera with the hitboxes it faces active",
     "8", kShown, S::Culling, kAdvanced, N::Lipac, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.lookAppearing = v.whole; }},
    {"--mesh-lods", ValueType::Choice, "on|off",
     "culled: each instance takes its mesh's coarsest LOD within\n"
     "--lod-pixel-error footprints of its ray cones (or pixels at its distance)",
     "off", kShown, S::Culling, kAdvanced, N::Nothing, kBoth,
     [](O& o, const Value& v) {
       if (v.text != "on" && v.text != "off")
         throw std::invalid_argument("--mesh-lods takes on or off, not '" + v.text + "'");
       o.renderer.culling.meshLods = v.text == "on";
     }},
    {"--lod-pixel-error", ValueType::Real, "E",
     "culled: a LOD's error may reach E footprints of the narrowest ray cone at\n"
     "its instance",
     "1", kShown, S::Culling, kAdvanced, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.lodPixelError = float(v.real); }},
    {"--blas-budget", ValueType::Whole, "MB",
     "culled: evict unused BLASes, least recently used first, past MB mebibytes", "no limit",
     kShown, S::Culling, kAdvanced, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.blasBudgetBytes = std::uint64_t(v.whole) << 20; }},
    {"--blas-build-budget", ValueType::Whole, "T",
     "culled: build at most T triangles of BLASes a frame (at least one BLAS)", "no limit",
     kShown, S::Culling, kAdvanced, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.blasBuildTriangles = v.whole; }},
    {"--blas-build-ms", ValueType::Real, "MS",
     "culled: build at most MS GPU milliseconds of BLASes a frame, at the rate\n"
     "of the builds so far (at least one BLAS)",
     "no limit", kShown, S::Culling, kAdvanced, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.blasBuildMilliseconds = v.real; }},
    {"--blas-keep-frames", ValueType::Whole, "K",
     "evict a BLAS no instance in the TLAS has used for K frames (0: only\n"
     "--blas-budget evicts)",
     "2", kShown, S::Culling, kAdvanced, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.blasKeepFrames = v.whole; }},
    {"--blas-rebuild-every", ValueType::Whole, "N",
     "animated meshes: BLASes updated in place every frame, rebuilt every N", "16", kShown,
     S::Culling, kAdvanced, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.renderer.culling.blasRebuildEvery = v.whole; }},

    // Device and shading.
    {"--device", ValueType::Whole, "N", "Vulkan device index", "the first suited", kShown,
     S::Device, kCommon, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.renderer.context.deviceIndex = int(v.whole); },
     "a device index (memograph render --list-devices lists them)", 0,
     std::numeric_limits<int>::max()},
    {"--list-devices", ValueType::Flag, "",
     "print the Vulkan devices and their ray-tracing support", "", kShown, S::Device, kCommon,
     N::Nothing, kRender, [](O& o, const Value&) { o.listDevices = true; }},
    {"--backend", ValueType::Choice, "auto|query|pipeline",
     "ray queries in compute, or the ray-tracing pipeline; auto:\n"
     "the pipeline for scenes of more than 8 materials, else query",
     "auto", kShown, S::Device, kCommon, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.renderer.context.backend = runtime::parseBackend(v.text); }},
    {"--shading", ValueType::Choice, "auto|megakernel|wavefront",
     "one kernel per path, or passes over path queues with\n"
     "materials in sorted batches; auto: wavefront on a GPU if able",
     "auto", kShown, S::Device, kCommon, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.renderer.shading = runtime::parseShading(v.text); }},
    {"--shader-cache", ValueType::Path, "DIR",
     "SPIR-V cache folder, and the device's pipeline cache file",
     "$XDG_CACHE_HOME/memograph/shaders", kShown, S::Device, kCommon, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.renderer.shaderCacheDirectory = v.text; }},
    {"--no-shader-cache", ValueType::Flag, "", "compile every shader and pipeline, keeping none",
     "", kShown, S::Device,
     kCommon, N::Nothing, kRender, [](O& o, const Value&) { o.renderer.shaderCache = false; }},
    {"--validation", ValueType::Flag, "", "enable the Vulkan validation layer", "", kShown,
     S::Device, kCommon, N::Nothing, kRender,
     [](O& o, const Value&) { o.renderer.context.validation = true; }},
    {"--material-dispatch", ValueType::Choice, "auto|switch|callable",
     "all materials in one shader, or a callable\n"
     "each (pipeline only); auto: callable on the pipeline",
     "auto", kShown, S::Device, kAdvanced, N::Nothing, kBoth,
     [](O& o, const Value& v) {
       o.renderer.materialDispatch = runtime::parseMaterialDispatch(v.text);
     }},
    {"--wavefront-paths", ValueType::Whole, "N",
     "the wavefront's paths in flight (0: every pixel, or what one storage\n"
     "buffer holds); a round over more pixels runs in chunks of N",
     "0", kShown, S::Device, kAdvanced, N::Nothing, kBoth,
     [](O& o, const Value& v) { o.renderer.wavefrontPaths = v.whole; },
     "a number of paths (0: the default)"},
    {"--dispatch-paths", ValueType::Whole, "N",
     "the megakernel traces a frame's P paths in dispatches of at most N paths,\n"
     "each adding its share of the pixel's mean (0: all P in one)",
     "5", kShown, S::Device, kAdvanced, N::Megakernel, kBoth,
     [](O& o, const Value& v) { o.renderer.pathsPerDispatch = v.whole; },
     "a number of paths per trace dispatch (0: all in one)"},
};

unsigned commandBit(TraceCommand command) {
  return command == TraceCommand::Render ? kRender : kBench;
}

std::vector<std::string_view> choicesOf(const Option& option) {
  std::vector<std::string_view> choices;
  std::string_view rest = option.metavar;
  for (std::size_t bar; (bar = rest.find('|')) != std::string_view::npos;
       rest.remove_prefix(bar + 1))
    choices.push_back(rest.substr(0, bar));
  choices.push_back(rest);
  return choices;
}

// "a, b or c".
std::string listChoices(const std::vector<std::string_view>& choices) {
  std::string text;
  for (std::size_t i = 0; i < choices.size(); ++i) {
    if (i > 0)
      text += i + 1 == choices.size() ? " or " : ", ";
    text += choices[i];
  }
  return text;
}

std::string takesText(const Option& option) {
  if (!option.takes.empty())
    return std::string(option.takes);
  switch (option.type) {
    case ValueType::Choice:
      return listChoices(choicesOf(option));
    case ValueType::Whole:
      return "a whole number";
    case ValueType::Real:
      return "a number";
    case ValueType::TileSize:
      return "WxH (e.g. 4x4)";
    default:
      return "a value";
  }
}

// Reads `text` as `option`'s value. Throws std::invalid_argument naming the option, what
// it takes and what was given.
Value readValue(const Option& option, std::string_view text) {
  const std::string name(option.name);
  const auto refuse = [&]() -> Value {
    throw std::invalid_argument(name + " takes " + takesText(option) + ", not '" +
                                std::string(text) + "'");
  };
  Value value;
  switch (option.type) {
    case ValueType::Flag:
      value.flag = true;
      break;
    case ValueType::Choice: {
      const auto choices = choicesOf(option);
      if (std::find(choices.begin(), choices.end(), text) == choices.end())
        return refuse();
      value.text = text;
      break;
    }
    case ValueType::Whole:
      if (!parseNumber(text, value.whole) || value.whole < option.min || value.whole > option.max)
        return refuse();
      break;
    case ValueType::Real:
      if (!parseReal(text, value.real) || value.real < option.min || value.real > option.max)
        return refuse();
      break;
    case ValueType::Path:
    case ValueType::Text:
      value.text = text;
      break;
    case ValueType::ImageSize: {
      ImageSize& size = value.sizes.emplace_back();
      if (std::string error; !parseImageSize(text, size.width, size.height, error))
        throw std::invalid_argument(name + ": " + error);
      break;
    }
    case ValueType::SizeList: {
      // Every item between commas is a size: an empty one ("16x9," or "16x9,,8x8") is
      // refused, not skipped, as a list cut short is likely a mistake.
      for (std::size_t start = 0;;) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        if (comma == start)
          throw std::invalid_argument(name + " takes WxH[,WxH...], not '" + std::string(text) +
                                      "': a size is missing before or after a comma");
        ImageSize& size = value.sizes.emplace_back();
        if (std::string error;
            !parseImageSize(text.substr(start, comma - start), size.width, size.height, error))
          throw std::invalid_argument(name + " takes WxH[,WxH...]: " + error);
        if (comma == text.size())
          break;
        start = comma + 1;
      }
      break;
    }
    case ValueType::TileSize: {
      ImageSize& size = value.sizes.emplace_back();
      const auto x = text.find('x');
      if (x == std::string_view::npos || !parseNumber(text.substr(0, x), size.width) ||
          !parseNumber(text.substr(x + 1), size.height))
        return refuse();
      break;
    }
  }
  return value;
}

const Option* findOption(TraceCommand command, std::string_view name) {
  for (const Option& option : kOptions) {
    if ((option.commands & commandBit(command)) && (option.name == name || option.alias == name))
      return &option;
  }
  return nullptr;
}

std::string_view defaultFor(const Option& option, TraceCommand command) {
  return command == TraceCommand::Bench && !option.benchDefault.empty() ? option.benchDefault
                                                                        : option.defaultText;
}

void applyTableDefaults(TraceCommand command, TraceCommandOptions& options) {
  for (const Option& option : kOptions) {
    if ((option.commands & commandBit(command)) && option.tableDefault)
      option.apply(options, readValue(option, defaultFor(option, command)));
  }
}

std::string_view commandName(TraceCommand command) {
  return command == TraceCommand::Render ? "render" : "bench";
}

// The options' help: "  --name METAVAR", then the help from this column (or two spaces
// after a longer name), words wrapped at kHelpWidth, continued at this column.
constexpr std::size_t kHelpColumn = 24, kHelpWidth = 100;

void appendOptionHelp(std::string& text, const Option& option, TraceCommand command) {
  std::string line = "  " + std::string(option.name);
  if (!option.alias.empty())
    line.append(", ").append(option.alias);
  if (!option.metavar.empty())
    line.append(" ").append(option.metavar);
  line.append(line.size() + 2 <= kHelpColumn ? kHelpColumn - line.size() : 2, ' ');
  std::string help(command == TraceCommand::Bench && !option.benchHelp.empty() ? option.benchHelp
                                                                               : option.help);
  std::replace(help.begin(), help.end(), '\n', ' ');
  if (const std::string_view byDefault = defaultFor(option, command); !byDefault.empty())
    help.append(" (default ").append(byDefault).append(")");
  bool lineHasWord = false;
  for (std::size_t at = 0; at < help.size();) {
    const std::size_t end = std::min(help.find(' ', at), help.size());
    const std::string_view word = std::string_view(help).substr(at, end - at);
    if (lineHasWord && line.size() + 1 + word.size() > kHelpWidth) {
      text.append(line).append("\n");
      line.assign(kHelpColumn, ' ');
      lineHasWord = false;
    }
    if (lineHasWord)
      line += ' ';
    line.append(word);
    lineHasWord = true;
    at = end + 1;
  }
  text.append(line).append("\n");
}

}  // namespace

bool TraceCommandOptions::wasGiven(std::string_view name) const {
  return std::find(given.begin(), given.end(), name) != given.end();
}

std::optional<int> scanTraceOptions(TraceCommand command, std::span<const std::string_view> args,
                                    std::string_view intro, TraceCommandOptions& options,
                                    std::vector<std::string>& positional) {
  const std::string_view name = commandName(command);
  applyTableDefaults(command, options);
  bool onlyPositional = false;
  std::optional<bool> helpAll;  // set: help asked for
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string_view arg = args[i];
    if (onlyPositional || arg.size() < 2 || arg[0] != '-') {
      positional.emplace_back(arg);
      continue;
    }
    if (arg == "--") {
      onlyPositional = true;
      continue;
    }
    if (arg == "--help" || arg == "-h" || arg == "--help-all") {
      helpAll = helpAll.value_or(false) || arg == "--help-all";
      continue;
    }
    const auto equals = arg.find('=');
    const std::string_view optionName = arg.substr(0, equals);
    const Option* option = findOption(command, optionName);
    if (!option)
      return usageError(name, "unknown option '" + std::string(optionName) + "'");
    options.given.push_back(option->name);
    std::string_view text;
    if (option->type == ValueType::Flag) {
      if (equals != std::string_view::npos)
        return usageError(name, "option '" + std::string(optionName) + "' takes no value");
    } else {
      if (equals != std::string_view::npos)
        text = arg.substr(equals + 1);
      else if (i + 1 < args.size())
        text = args[++i];
      if (text.empty())
        return usageError(name, "option '" + std::string(optionName) + "' needs a value");
    }
    try {
      option->apply(options, readValue(*option, text));
    } catch (const std::invalid_argument& e) {
      return usageError(name, e.what());
    }
  }
  if (helpAll) {
    std::cout << intro << traceOptionHelp(command, *helpAll);
    return kExitOk;
  }
  return std::nullopt;
}

void validateTraceOptions(TraceCommandOptions& options) {
  runtime::RendererOptions& renderer = options.renderer;
  // A test hook, not an option: the tile cache's subgroup fill gives up this share of its
  // tile computations before storing a texel, as after a callable repack (runtime.md).
  if (const char* giveUp = std::getenv("MEMOGRAPH_TEST_TILE_GIVE_UP"); giveUp && *giveUp) {
    std::uint32_t percent = 0;
    if (!parseNumber(giveUp, percent) || percent > 100)
      throw std::invalid_argument(
          "MEMOGRAPH_TEST_TILE_GIVE_UP takes a whole number of percent, 0..100, not '" +
          std::string(giveUp) + "'");
    renderer.cache.testRepacks = percent > 0;
    renderer.cache.testRepackPercent = percent > 0 ? percent : 100;
  }
  runtime::validateCacheOptions(renderer.cache);  // the renderer's own ranges and messages
  runtime::validateCullingOptions(renderer.culling);
  runtime::validateWavefrontOptions(renderer);
  runtime::validateIntegratorOptions(renderer);
  if (renderer.shading == runtime::Shading::Wavefront &&
      renderer.cache.tileFill == runtime::TileFill::Subgroup)
    throw std::invalid_argument(
        "--tile-fill subgroup is the megakernel's: --shading wavefront computes missing "
        "tiles in its material passes, from the deferred fill's queue");
}

std::vector<std::string> ignoredOptionNotes(const TraceCommandOptions& options) {
  const runtime::CacheMode cache = options.renderer.cache.mode;
  const runtime::CullingMode culling = options.renderer.culling.mode;
  std::vector<std::string> notes;
  for (const Option& option : kOptions) {
    if (!options.wasGiven(option.name))
      continue;
    switch (option.needs) {
      case Needs::Nothing:
        break;
      case Needs::Cache:
        if (cache == runtime::CacheMode::None)
          notes.push_back(ignoredOptionNote(option.name, "--cache texel or --cache tile"));
        break;
      case Needs::TileCache:
        if (cache != runtime::CacheMode::Tile)
          notes.push_back(ignoredOptionNote(option.name, "--cache tile"));
        break;
      case Needs::Frustum:
        if (culling != runtime::CullingMode::Frustum)
          notes.push_back(ignoredOptionNote(option.name, "--culling frustum"));
        break;
      case Needs::Lipac:
        if (culling != runtime::CullingMode::Lipac)
          notes.push_back(ignoredOptionNote(option.name, "--culling lipac"));
        break;
      case Needs::Megakernel:
        if (options.renderer.shading == runtime::Shading::Wavefront)
          notes.push_back(ignoredOptionNote(option.name, "the megakernel"));
        break;
      case Needs::AmbientOcclusion:
        if (options.renderer.integrator != runtime::Integrator::AmbientOcclusion)
          notes.push_back(ignoredOptionNote(option.name, "--integrator ao"));
        break;
    }
  }
  return notes;
}

std::string traceOptionHelp(TraceCommand command, bool all) {
  std::string text;
  bool anyAdvanced = false;
  for (std::size_t section = 0; section < std::size(kSectionTitles); ++section) {
    std::string lines;
    for (const Option& option : kOptions) {
      if (!(option.commands & commandBit(command)) || std::size_t(option.section) != section)
        continue;
      anyAdvanced |= option.advanced;
      if (all || !option.advanced)
        appendOptionHelp(lines, option, command);
    }
    if (!lines.empty())
      text.append("\n").append(kSectionTitles[section]).append(":\n").append(lines);
  }
  if (!all && anyAdvanced)
    text.append("\nmemograph ")
        .append(commandName(command))
        .append(
            " --help-all also lists the advanced options (cache, LiPaC, BLAS and\n"
            "dispatch parameters).\n");
  return text;
}

}  // namespace memograph::cli

#endif  // MEMOGRAPH_HAVE_RUNTIME
