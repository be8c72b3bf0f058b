// memograph diff REFERENCE TEST [--out MAP] [--ppd N | --monitor-*]: the LDR-FLIP difference
// (tools/quality/flip.h; Andersson et al. 2020) of two images: prints the mean, the
// maximum and a few percentiles, and writes the per-pixel error map (magma colour map).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>

#include "cli_common.h"
#include "commands.h"
#include "tools/io/pfm.h"
#include "tools/quality/flip.h"
#include "tools/quality/image_bias.h"

#ifdef MEMOGRAPH_HAVE_IO
#include "tools/io/image_io.h"
#endif

namespace memograph::cli {

namespace {

constexpr std::string_view kHelp =
    "usage: memograph diff REFERENCE TEST [--out MAP] [options]\n"
    "\n"
    "Compares TEST against REFERENCE with LDR-FLIP (Andersson et al., HPG 2020), a perceptual\n"
    "difference: 0 where a viewer flipping between the two sees no change, 1 for the largest\n"
    "(green against blue). Prints the mean (the headline figure), the maximum and the 50th,\n"
    "90th, 95th and 99th percentiles of the per-pixel error. See docs/design/flip.md.\n"
    "\n"
    "options:\n"
    "  --out MAP                 write the error map: .png colour-mapped (magma), .exr or\n"
    "                            .pfm the raw error in [0, 1] as grey\n"
    "  --ppd N                   observer's pixels per degree, 1 to 1000 (default 67.02:\n"
    "                            0.7 m from a 0.7 m wide 3840-pixel monitor)\n"
    "  --monitor-distance M      or compute it: viewing distance in metres (default 0.7)\n"
    "  --monitor-width M         monitor width in metres (default 0.7)\n"
    "  --monitor-resolution PX   monitor width in pixels (default 3840)\n"
    "  --encoding E              auto (default: .exr/.hdr/.pfm linear, others sRGB), srgb\n"
    "                            or linear, for both images; linear values are clamped to\n"
    "                            [0, 1] (LDR-FLIP: tonemap HDR renders first)\n"
    "  --bias-block N            also print both images' means and their mean absolute\n"
    "                            difference after averaging NxN pixel blocks (linear\n"
    "                            values, unclamped): noise shrinks with N, a bias stays\n"
    "                            (default: not printed)\n"
    "\n"
    "PFM files (the renderer's --out) are read and written by every build; other formats\n"
    "need the io module (OpenImageIO), which the GPU bundle is built without.\n"
    "\n"
    "Exit codes: 0 compared, 1 an image is unreadable or the sizes differ, 2 usage error.\n";

}  // namespace

namespace {

bool parsePositive(const std::string& text, double& out) {
  return parseReal(text, out) && out > 0.0;
}

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

bool linearByExtension(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".exr" || ext == ".hdr" || ext == ".pfm";
}

constexpr const char* kNeedsIo =
    "this build reads and writes only .pfm images (configured without the io module, so "
    "without OpenImageIO)";

std::optional<runtime::HdrImage> readImage(const std::string& path,
                                           compiler::Diagnostics& diagnostics) {
  // The renderer's own PFM files go through the project's reader (row order, byte order),
  // which every build has: the GPU bundle compares its renders without OpenImageIO.
  if (lowerExtension(path) == ".pfm")
    return io::readPfm(path, diagnostics);
#ifdef MEMOGRAPH_HAVE_IO
  return io::readImageFloat(path, diagnostics);
#else
  diagnostics.error(path, kNeedsIo);
  return std::nullopt;
#endif
}

bool writeImage(const std::string& path, const runtime::HdrImage& image,
                compiler::Diagnostics& diagnostics) {
  if (lowerExtension(path) == ".pfm")
    return io::writePfm(path, image, diagnostics);
#ifdef MEMOGRAPH_HAVE_IO
  return io::writeImage(path, image, io::LdrOptions{}, diagnostics);
#else
  diagnostics.error(path, kNeedsIo);
  return false;
#endif
}

float srgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

int runDiff(std::span<const std::string_view> args) {
  std::string out, ppdText, distanceText, widthText, resolutionText, encoding = "auto";
  std::string biasBlockText;
  ArgumentScanner scanner("diff", args);
  scanner.option("--out", &out);
  scanner.option("-o", &out);
  scanner.option("--ppd", &ppdText);
  scanner.option("--monitor-distance", &distanceText);
  scanner.option("--monitor-width", &widthText);
  scanner.option("--monitor-resolution", &resolutionText);
  scanner.option("--encoding", &encoding);
  scanner.option("--bias-block", &biasBlockText);
  scanner.help(kHelp);
  std::vector<std::string> positional;
  if (const auto exitCode = scanner.scan(positional))
    return *exitCode;
  if (positional.size() != 2)
    return usageError("diff", "expected two images, REFERENCE and TEST");
  std::uint32_t biasBlock = 0;
  if (!biasBlockText.empty() &&
      (!parseNumber(biasBlockText, biasBlock) || biasBlock == 0 || biasBlock > kMaxImageSide))
    return usageError("diff", "--bias-block must be a whole number of pixels from 1 to " +
                                  std::to_string(kMaxImageSide) + ", not '" + biasBlockText + "'");

  double ppd = runtime::defaultPixelsPerDegree();
  const bool monitor = !distanceText.empty() || !widthText.empty() || !resolutionText.empty();
  if (!ppdText.empty() && monitor)
    return usageError("diff", "give --ppd or the --monitor-* options, not both");
  if (!ppdText.empty() && !parsePositive(ppdText, ppd))
    return usageError("diff", "--ppd must be a positive number, not '" + ppdText + "'");
  if (monitor) {
    double distance = 0.7, width = 0.7, resolution = 3840.0;
    if (!distanceText.empty() && !parsePositive(distanceText, distance))
      return usageError("diff", "--monitor-distance must be a positive number of metres");
    if (!widthText.empty() && !parsePositive(widthText, width))
      return usageError("diff", "--monitor-width must be a positive number of metres");
    if (!resolutionText.empty() && !parsePositive(resolutionText, resolution))
      return usageError("diff", "--monitor-resolution must be a positive number of pixels");
    ppd = runtime::pixelsPerDegree(distance, width, resolution);
  }
  // Checked here, before any image is read, so a mistyped value is a usage error at once.
  if (!(ppd >= runtime::kMinPixelsPerDegree && ppd <= runtime::kMaxPixelsPerDegree)) {
    char range[96];
    std::snprintf(range, sizeof range, "%.3g pixels per degree, outside %g to %g", ppd,
                  runtime::kMinPixelsPerDegree, runtime::kMaxPixelsPerDegree);
    return usageError("diff",
                      std::string(monitor ? "the --monitor-* options give " : "--ppd is ") + range);
  }
  if (encoding != "auto" && encoding != "srgb" && encoding != "linear")
    return usageError("diff", "--encoding must be auto, srgb or linear, not '" + encoding + "'");
  if (!out.empty()) {
    const std::string ext = lowerExtension(out);
    if (ext != ".png" && ext != ".exr" && ext != ".pfm")
      return usageError("diff", "--out must name a .png, .exr or .pfm file, not '" + out + "'");
  }
  if (const int code = refuseOutputOverInput(
          "diff", {{"--out", out}}, {{"REFERENCE", positional[0]}, {"TEST", positional[1]}});
      code != kExitOk)
    return code;
  if (!out.empty()) {
    if (const int code = checkOutputFile("diff", out); code != kExitOk)
      return code;
  }

  const std::string& referencePath = positional[0];
  const std::string& testPath = positional[1];
  compiler::Diagnostics diagnostics;
  auto reference = readImage(referencePath, diagnostics);
  auto test = readImage(testPath, diagnostics);
  if (!reference || !test) {
    printDiagnostics(diagnostics);
    return kExitFailure;
  }
  // FLIP of a NaN is NaN, and it would print `mean nan`: say where the bad pixel is instead.
  for (const auto& [path, image] : {std::pair{&referencePath, &*reference}, {&testPath, &*test}}) {
    for (std::size_t i = 0; i < image->rgba.size(); ++i) {
      if (i % 4 != 3 && !std::isfinite(image->rgba[i])) {
        const std::size_t pixel = i / 4;
        std::cerr << *path << ": error: pixel (" << pixel % image->width << ", "
                  << pixel / image->width << ") is not a finite number ("
                  << (std::isnan(image->rgba[i]) ? "NaN" : "infinite")
                  << "); FLIP compares finite colours\n";
        return kExitFailure;
      }
    }
  }
  if (reference->width != test->width || reference->height != test->height) {
    std::cerr << "memograph diff: the images differ in size: " << referencePath << " is "
              << reference->width << "x" << reference->height << ", " << testPath << " is "
              << test->width << "x" << test->height << "\n";
    return kExitFailure;
  }
  const auto encodingOf = [&](const std::string& path) {
    if (encoding == "auto")
      return linearByExtension(path) ? runtime::FlipEncoding::Linear : runtime::FlipEncoding::Srgb;
    return encoding == "linear" ? runtime::FlipEncoding::Linear : runtime::FlipEncoding::Srgb;
  };
  // An sRGB file against a linear one (a PNG against an EXR render): decode the sRGB one.
  runtime::FlipEncoding flipEncoding = encodingOf(testPath);
  if (encodingOf(referencePath) != flipEncoding) {
    auto& encoded = flipEncoding == runtime::FlipEncoding::Srgb ? *test : *reference;
    for (std::size_t i = 0; i < encoded.rgba.size(); ++i) {
      if (i % 4 != 3)
        encoded.rgba[i] = srgbToLinear(std::clamp(encoded.rgba[i], 0.0f, 1.0f));
    }
    flipEncoding = runtime::FlipEncoding::Linear;
  }

  const runtime::FlipResult result =
      runtime::computeFlip({reference->rgba, int(reference->width), int(reference->height), 4},
                           {test->rgba, int(test->width), int(test->height), 4},
                           {.pixelsPerDegree = ppd, .encoding = flipEncoding});

  std::printf("LDR-FLIP of %s against %s (%dx%d, %.2f pixels per degree)\n", testPath.c_str(),
              referencePath.c_str(), result.width, result.height, ppd);
  std::printf("mean  %.6f\n", result.mean);
  std::printf("max   %.6f\n", result.max);
  static constexpr double kFractions[] = {0.5, 0.9, 0.95, 0.99};
  static constexpr const char* kLabels[] = {"p50", "p90", "p95", "p99"};
  const std::vector<float> percentiles = runtime::flipPercentiles(result.error, kFractions);
  for (std::size_t i = 0; i < percentiles.size(); ++i)
    std::printf("%-5s %.6f\n", kLabels[i], percentiles[i]);
  if (biasBlock > 0) {
    const runtime::BiasResult bias =
        runtime::measureBias({reference->rgba, reference->width, reference->height},
                             {test->rgba, test->width, test->height}, biasBlock);
    std::printf("image mean  reference %.6f  test %.6f\n", bias.referenceMean, bias.testMean);
    std::printf("block MAE   %.6f (%ux%u blocks)\n", bias.blockMeanAbsoluteError, biasBlock,
                biasBlock);
  }
  std::fflush(stdout);

  if (!out.empty()) {
    runtime::HdrImage map{std::uint32_t(result.width), std::uint32_t(result.height),
                          std::vector<float>(result.error.size() * 4, 1.0f)};
    const bool png = lowerExtension(out) == ".png";
    for (std::size_t i = 0; i < result.error.size(); ++i) {
      float* p = &map.rgba[i * 4];
      if (png) {
        // writeImage sRGB-encodes linear values: hand it magma's colours decoded.
        const auto colour = runtime::magmaSrgb(result.error[i]);
        for (int c = 0; c < 3; ++c)
          p[c] = srgbToLinear(colour[c]);
      } else {
        p[0] = p[1] = p[2] = result.error[i];
      }
    }
    if (!writeImage(out, map, diagnostics)) {
      printDiagnostics(diagnostics);
      return kExitFailure;
    }
  }
  return kExitOk;
}

}  // namespace memograph::cli
