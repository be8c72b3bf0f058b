// LDR-FLIP: the perceptual image-difference metric of Andersson, Nilsson, Akenine-Möller,
// Oskarsson, Åström and Fairchild, "FLIP: A Difference Evaluator for Alternating Images",
// Proc. ACM Comput. Graph. Interact. Tech. 3(2) (HPG 2020). Written from the paper; plain
// C++ without dependencies, so the renderer's tests and the CLI can both use it.
//
// The metric compares a reference and a test image as seen by an observer at a given number
// of pixels per degree of visual angle, and gives every pixel an error in [0, 1]: 0 where the
// two are indistinguishable, 1 for the largest difference (e.g. green against blue). The mean
// over the image is the headline figure.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace memograph::runtime {

// The paper's constants, named as in the paper. Exposed for tests and docs.
namespace flip_constants {
constexpr double kQc = 0.7;   // colour pipeline: exponent of the HyAB difference
constexpr double kPc = 0.4;   // colour pipeline: fraction of cmax where the remapping bends
constexpr double kPt = 0.95;  // colour pipeline: error assigned to pc·cmax
constexpr double kW = 0.082;  // feature pipeline: detector width in degrees (σ = w/2 · ppd)
constexpr double kQf = 0.5;   // feature pipeline: exponent of the feature difference
}  // namespace flip_constants

// Pixels per degree of an observer `distance` metres from a monitor `width` metres wide with
// `resolution` pixels across (the paper's viewing conditions): ppd = d · (r / w) · π / 180.
double pixelsPerDegree(double distance, double width, double resolution);

// The paper's default observer: 0.7 m from a 0.7 m wide 3840-pixel monitor, ≈ 67.02 ppd.
double defaultPixelsPerDegree();

// The observers computeFlip accepts. The CSF filter's radius, and with it the cost (radius x
// pixels), grows with ppd: 1000 covers a 3840-pixel, 0.7 m monitor seen from 10 m.
inline constexpr double kMinPixelsPerDegree = 1.0;
inline constexpr double kMaxPixelsPerDegree = 1000.0;

enum class FlipEncoding {
  Srgb,    // channel values are sRGB-encoded (8-bit files, displayed images)
  Linear,  // channel values are linear RGB; clamped to [0, 1] (LDR-FLIP)
};

struct FlipOptions {
  double pixelsPerDegree = 0.0;  // 0: defaultPixelsPerDegree()
  FlipEncoding encoding = FlipEncoding::Srgb;
};

// An RGB(A) float image: `channels` (3 or 4) floats per pixel, row-major. Alpha is ignored.
struct FlipImageView {
  std::span<const float> pixels;
  int width = 0;
  int height = 0;
  int channels = 3;
};

struct FlipResult {
  int width = 0;
  int height = 0;
  std::vector<float> error;         // ΔE = ΔEc^(1 − ΔEf) per pixel, in [0, 1]
  std::vector<float> colorError;    // ΔEc per pixel: the remapped colour difference
  std::vector<float> featureError;  // ΔEf per pixel: the feature difference
  double mean = 0.0;                // mean of `error`
  float max = 0.0f;
};

// LDR-FLIP of `test` against `reference` (the paper's pipeline, Fig. 2). Throws
// std::invalid_argument when the sizes differ, an image is empty, the channel count is not 3
// or 4, a buffer is too small, or the ppd is not positive.
FlipResult computeFlip(const FlipImageView& reference, const FlipImageView& test,
                       const FlipOptions& options = {});

// The value below which `fraction` (0..1) of `values` lie (nearest rank on a sorted copy);
// the plural sorts once for all `fractions`. Empty `values` give 0.
float flipPercentile(std::span<const float> values, double fraction);
std::vector<float> flipPercentiles(std::span<const float> values,
                                   std::span<const double> fractions);

// The magma colour map the paper shows its error maps in, as sRGB-encoded RGB for t in
// [0, 1] (clamped): piecewise linear between 11 samples of matplotlib's magma.
std::array<float, 3> magmaSrgb(float t);

}  // namespace memograph::runtime
