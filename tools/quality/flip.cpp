// LDR-FLIP (Andersson et al., HPG 2020), following the paper's pipeline (its Fig. 2):
//
//   colour pipeline:  sRGB → linear RGB → YyCxCz → CSF filtering per channel → linear RGB,
//                     clamped → CIELAB → Hunt adjustment → HyAB → ^qc → remap to [0, 1]
//   feature pipeline: achromatic channel → edge and point detectors → ΔEf
//   combination:      ΔE = ΔEc^(1 − ΔEf)
//
// Comments name the paper's step. Every filter is applied separably with clamp-to-edge
// borders (as the authors' published implementation); the 2D kernels the paper defines are
// products of 1D Gaussians (or sums of such products), so the separable form is the same
// kernel.
#include "tools/quality/flip.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace memograph::runtime {

namespace {

using std::numbers::pi;

// Linear sRGB (Rec. 709 primaries, D65) to CIE XYZ and back.
constexpr double kRgbToXyz[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                                    {0.2126729, 0.7151522, 0.0721750},
                                    {0.0193339, 0.1191920, 0.9503041}};
constexpr double kXyzToRgb[3][3] = {{3.2404542, -1.5371385, -0.4985314},
                                    {-0.9692660, 1.8760108, 0.0415560},
                                    {0.0556434, -0.2040259, 1.0572252}};

struct Vec3 {
  double x, y, z;
};

Vec3 multiply(const double (&m)[3][3], Vec3 v) {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
          m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

// The reference white: XYZ of linear RGB (1, 1, 1), i.e. D65 with Yn = 1. White then has
// Cx = Cz = 0 and a* = b* = 0 exactly (up to rounding).
const Vec3 kWhite = multiply(kRgbToXyz, {1.0, 1.0, 1.0});

double srgbToLinear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// YyCxCz (the paper's colour pipeline, after Zhang & Wandell / Johnson & Fairchild): the
// linearised CIELAB, an opponent space in which filtering is meaningful because it is linear
// in XYZ.
Vec3 xyzToYcxcz(Vec3 xyz) {
  const double x = xyz.x / kWhite.x, y = xyz.y / kWhite.y, z = xyz.z / kWhite.z;
  return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}

Vec3 ycxczToXyz(Vec3 c) {
  const double y = (c.x + 16.0) / 116.0;
  return {kWhite.x * (c.y / 500.0 + y), kWhite.y * y, kWhite.z * (y - c.z / 200.0)};
}

// CIELAB (CIE 1976) with the same white.
double labF(double t) {
  constexpr double delta = 6.0 / 29.0;
  return t > delta * delta * delta ? std::cbrt(t) : t / (3.0 * delta * delta) + 4.0 / 29.0;
}

Vec3 xyzToLab(Vec3 xyz) {
  const double fx = labF(xyz.x / kWhite.x), fy = labF(xyz.y / kWhite.y),
               fz = labF(xyz.z / kWhite.z);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

// Hunt adjustment (colour pipeline): chroma grows with lightness, a*_H = 0.01 L* a*,
// b*_H = 0.01 L* b*.
Vec3 huntAdjust(Vec3 lab) {
  return {lab.x, 0.01 * lab.x * lab.y, 0.01 * lab.x * lab.z};
}

Vec3 linearRgbToHuntLab(Vec3 rgb) {
  return huntAdjust(xyzToLab(multiply(kRgbToXyz, rgb)));
}

// HyAB (Abasi et al. 2020; colour pipeline): city-block distance in lightness plus Euclidean
// distance in the chromatic plane.
double hyab(Vec3 a, Vec3 b) {
  return std::abs(a.x - b.x) + std::hypot(a.y - b.y, a.z - b.z);
}

// cmax: the largest difference in the gamut, that of green against blue after the Hunt
// adjustment, raised to qc (colour pipeline).
double maxColorDifference() {
  static const double cmax =
      std::pow(hyab(linearRgbToHuntLab({0.0, 1.0, 0.0}), linearRgbToHuntLab({0.0, 0.0, 1.0})),
               flip_constants::kQc);
  return cmax;
}

// The remapping of the colour pipeline: differences below pc·cmax are spread linearly over
// [0, pt], the rest compressed into [pt, 1].
double remapColorDifference(double difference, double cmax) {
  using namespace flip_constants;
  const double knee = kPc * cmax;
  const double remapped = difference < knee
                              ? kPt / knee * difference
                              : kPt + (difference - knee) / (cmax - knee) * (1.0 - kPt);
  return std::clamp(remapped, 0.0, 1.0);
}

// A planar single-channel float image.
struct Plane {
  int width = 0, height = 0;
  std::vector<float> values;
  Plane(int w, int h) : width(w), height(h), values(static_cast<std::size_t>(w) * h) {}
  float& at(int x, int y) { return values[static_cast<std::size_t>(y) * width + x]; }
  float at(int x, int y) const { return values[static_cast<std::size_t>(y) * width + x]; }
};

// One separable pass: `kernel` has 2r+1 taps centred on tap r; horizontal or vertical;
// samples outside the image repeat the border pixel. Rows are processed whole (a padded copy
// horizontally, row-by-row accumulation vertically) so the inner loops vectorise.
Plane convolve1d(const Plane& in, const std::vector<double>& kernel, bool horizontal) {
  const int radius = static_cast<int>(kernel.size() / 2);
  const std::vector<float> taps(kernel.begin(), kernel.end());
  const int width = in.width, height = in.height;
  Plane out(width, height);
  if (horizontal) {
    std::vector<float> padded(static_cast<std::size_t>(width) + 2 * radius);
    for (int y = 0; y < height; ++y) {
      const float* row = &in.values[static_cast<std::size_t>(y) * width];
      for (int i = 0; i < width + 2 * radius; ++i)
        padded[i] = row[std::clamp(i - radius, 0, width - 1)];
      float* target = &out.values[static_cast<std::size_t>(y) * width];
      for (int x = 0; x < width; ++x) {
        float sum = 0.0f;
        for (int t = 0; t <= 2 * radius; ++t)
          sum += taps[t] * padded[x + t];
        target[x] = sum;
      }
    }
  } else {
    for (int y = 0; y < height; ++y) {
      float* target = &out.values[static_cast<std::size_t>(y) * width];
      for (int t = 0; t <= 2 * radius; ++t) {
        const int source = std::clamp(y + t - radius, 0, height - 1);
        const float* row = &in.values[static_cast<std::size_t>(source) * width];
        const float tap = taps[t];
        for (int x = 0; x < width; ++x)
          target[x] += tap * row[x];
      }
    }
  }
  return out;
}

Plane convolveSeparable(const Plane& in, const std::vector<double>& horizontal,
                        const std::vector<double>& vertical) {
  return convolve1d(convolve1d(in, horizontal, true), vertical, false);
}

// The contrast sensitivity functions of the colour pipeline's spatial filtering, one per
// YyCxCz channel, as sums of Gaussians in the frequency domain, Ŝ(f) = Σ a_k exp(−b_k f²),
// whose spatial form is S(x) = Σ a_k √(π/b_k) exp(−π² x² / b_k), x in degrees.
struct Csf {
  double a1, b1, a2, b2;
};
constexpr Csf kCsf[3] = {
    {1.0, 0.0047, 0.0, 1e-5},   // achromatic (Yy)
    {1.0, 0.0053, 0.0, 1e-5},   // red-green (Cx)
    {34.1, 0.04, 13.5, 0.025},  // blue-yellow (Cz)
};

// The filter radius in pixels: three standard deviations of the widest Gaussian of all
// channels (σ = √(b / (2π²)) degrees), at ppd pixels per degree.
int csfRadius(double ppd) {
  double bMax = 0.0;
  for (const auto& csf : kCsf)
    bMax = std::max({bMax, csf.b1, csf.b2});
  return static_cast<int>(std::ceil(3.0 * std::sqrt(bMax / (2.0 * pi * pi)) * ppd));
}

// Filters one channel with its CSF: the 2D kernel Σ_k a_k √(π/b_k) exp(−π²(x²+y²)/b_k),
// sampled at pixel centres (x, y in degrees) and normalised to sum 1. Each term is a product
// of 1D Gaussians g_k(x) g_k(y), so the result is Σ_k w_k (ĝ_k ⊗ ĝ_k) * I with ĝ_k = g_k /
// Σ g_k and w_k = a_k √(π/b_k) (Σ g_k)² / N.
Plane filterCsf(const Plane& channel, const Csf& csf, double ppd, int radius) {
  struct Term {
    std::vector<double> kernel;
    double weight;
  };
  std::vector<Term> terms;
  double total = 0.0;
  for (const auto& [a, b] : {std::pair{csf.a1, csf.b1}, std::pair{csf.a2, csf.b2}}) {
    if (a == 0.0)
      continue;
    std::vector<double> kernel(2 * radius + 1);
    double sum = 0.0;
    for (int i = -radius; i <= radius; ++i) {
      const double x = i / ppd;
      kernel[i + radius] = std::exp(-pi * pi * x * x / b);
      sum += kernel[i + radius];
    }
    for (auto& k : kernel)
      k /= sum;
    const double weight = a * std::sqrt(pi / b) * sum * sum;
    terms.push_back({std::move(kernel), weight});
    total += weight;
  }
  Plane out(channel.width, channel.height);
  for (const auto& term : terms) {
    const Plane filtered = convolveSeparable(channel, term.kernel, term.kernel);
    const double w = term.weight / total;
    for (std::size_t i = 0; i < out.values.size(); ++i)
      out.values[i] += static_cast<float>(w * filtered.values[i]);
  }
  return out;
}

// The feature pipeline's detectors: first (edges) and second (points) derivatives of a
// Gaussian with σ = ½ w ppd pixels (w = 0.082°), radius ⌈3σ⌉. Each derivative kernel is
// normalised so that its positive weights sum to 1 and its negative weights to −1; the
// across-direction Gaussian is normalised to sum 1 (so the 2D kernels are normalised the
// same way, and a unit step gives an edge response of 1).
struct FeatureKernels {
  std::vector<double> gaussian, first, second;
};

void normaliseSigned(std::vector<double>& kernel) {
  double positive = 0.0, negative = 0.0;
  for (const double k : kernel)
    (k > 0.0 ? positive : negative) += k;
  for (auto& k : kernel) {
    if (k > 0.0 && positive > 0.0)
      k /= positive;
    else if (k < 0.0 && negative < 0.0)
      k /= -negative;
  }
}

FeatureKernels featureKernels(double ppd) {
  const double sigma = 0.5 * flip_constants::kW * ppd;
  const int radius = static_cast<int>(std::ceil(3.0 * sigma));
  FeatureKernels kernels;
  double sum = 0.0;
  for (int i = -radius; i <= radius; ++i) {
    const double x = i, g = std::exp(-x * x / (2.0 * sigma * sigma));
    kernels.gaussian.push_back(g);
    kernels.first.push_back(-x * g);
    kernels.second.push_back((x * x / (sigma * sigma) - 1.0) * g);
    sum += g;
  }
  for (auto& g : kernels.gaussian)
    g /= sum;
  normaliseSigned(kernels.first);
  normaliseSigned(kernels.second);
  return kernels;
}

struct Features {
  Plane edges, points;  // ‖∇‖ and the magnitude of the second-derivative responses
};

Features detectFeatures(const Plane& achromatic, const FeatureKernels& k) {
  const Plane dx = convolveSeparable(achromatic, k.first, k.gaussian);
  const Plane dy = convolveSeparable(achromatic, k.gaussian, k.first);
  const Plane dxx = convolveSeparable(achromatic, k.second, k.gaussian);
  const Plane dyy = convolveSeparable(achromatic, k.gaussian, k.second);
  Features features{Plane(achromatic.width, achromatic.height),
                    Plane(achromatic.width, achromatic.height)};
  for (std::size_t i = 0; i < achromatic.values.size(); ++i) {
    features.edges.values[i] = std::hypot(dx.values[i], dy.values[i]);
    features.points.values[i] = std::hypot(dxx.values[i], dyy.values[i]);
  }
  return features;
}

// One input image in YyCxCz, planar, plus the normalised achromatic channel Y/Yn ∈ [0, 1]
// that the feature pipeline reads.
struct Opponent {
  Plane yy, cx, cz, achromatic;
};

Opponent toOpponent(const FlipImageView& image, FlipEncoding encoding) {
  Opponent out{Plane(image.width, image.height), Plane(image.width, image.height),
               Plane(image.width, image.height), Plane(image.width, image.height)};
  const std::size_t count = static_cast<std::size_t>(image.width) * image.height;
  for (std::size_t i = 0; i < count; ++i) {
    const float* p = &image.pixels[i * image.channels];
    Vec3 rgb{std::clamp<double>(p[0], 0.0, 1.0), std::clamp<double>(p[1], 0.0, 1.0),
             std::clamp<double>(p[2], 0.0, 1.0)};
    if (encoding == FlipEncoding::Srgb)
      rgb = {srgbToLinear(rgb.x), srgbToLinear(rgb.y), srgbToLinear(rgb.z)};
    const Vec3 c = xyzToYcxcz(multiply(kRgbToXyz, rgb));
    out.yy.values[i] = static_cast<float>(c.x);
    out.cx.values[i] = static_cast<float>(c.y);
    out.cz.values[i] = static_cast<float>(c.z);
    out.achromatic.values[i] = static_cast<float>((c.x + 16.0) / 116.0);
  }
  return out;
}

// Colour pipeline up to the perceptual space: CSF filtering of each opponent channel, back
// to linear RGB clamped to [0, 1], then Hunt-adjusted CIELAB.
std::vector<Vec3> filteredHuntLab(const Opponent& image, double ppd) {
  const int radius = csfRadius(ppd);
  const Plane yy = filterCsf(image.yy, kCsf[0], ppd, radius);
  const Plane cx = filterCsf(image.cx, kCsf[1], ppd, radius);
  const Plane cz = filterCsf(image.cz, kCsf[2], ppd, radius);
  std::vector<Vec3> lab(yy.values.size());
  for (std::size_t i = 0; i < lab.size(); ++i) {
    Vec3 rgb = multiply(kXyzToRgb, ycxczToXyz({yy.values[i], cx.values[i], cz.values[i]}));
    rgb = {std::clamp(rgb.x, 0.0, 1.0), std::clamp(rgb.y, 0.0, 1.0), std::clamp(rgb.z, 0.0, 1.0)};
    lab[i] = linearRgbToHuntLab(rgb);
  }
  return lab;
}

void validate(const FlipImageView& image, const char* name) {
  if (image.width <= 0 || image.height <= 0)
    throw std::invalid_argument(std::string("FLIP: the ") + name + " image is empty");
  if (image.channels != 3 && image.channels != 4)
    throw std::invalid_argument(std::string("FLIP: the ") + name +
                                " image needs 3 or 4 channels, not " +
                                std::to_string(image.channels));
  const std::size_t needed = static_cast<std::size_t>(image.width) * image.height * image.channels;
  if (image.pixels.size() < needed)
    throw std::invalid_argument(std::string("FLIP: the ") + name + " image has " +
                                std::to_string(image.pixels.size()) + " values, " +
                                std::to_string(needed) + " needed");
}

}  // namespace

double pixelsPerDegree(double distance, double width, double resolution) {
  return distance * (resolution / width) * (pi / 180.0);
}

double defaultPixelsPerDegree() {
  return pixelsPerDegree(0.7, 0.7, 3840.0);
}

FlipResult computeFlip(const FlipImageView& reference, const FlipImageView& test,
                       const FlipOptions& options) {
  validate(reference, "reference");
  validate(test, "test");
  if (reference.width != test.width || reference.height != test.height) {
    throw std::invalid_argument(
        "FLIP: the images differ in size (" + std::to_string(reference.width) + "x" +
        std::to_string(reference.height) + " against " + std::to_string(test.width) + "x" +
        std::to_string(test.height) + ")");
  }
  const double ppd =
      options.pixelsPerDegree == 0.0 ? defaultPixelsPerDegree() : options.pixelsPerDegree;
  if (!(ppd >= kMinPixelsPerDegree && ppd <= kMaxPixelsPerDegree))
    throw std::invalid_argument("FLIP: pixels per degree must be from 1 to 1000");

  const Opponent ref = toOpponent(reference, options.encoding);
  const Opponent tst = toOpponent(test, options.encoding);

  // Colour pipeline.
  const std::vector<Vec3> refLab = filteredHuntLab(ref, ppd);
  const std::vector<Vec3> tstLab = filteredHuntLab(tst, ppd);
  const double cmax = maxColorDifference();

  // Feature pipeline.
  const FeatureKernels kernels = featureKernels(ppd);
  const Features refFeatures = detectFeatures(ref.achromatic, kernels);
  const Features tstFeatures = detectFeatures(tst.achromatic, kernels);

  FlipResult result;
  result.width = reference.width;
  result.height = reference.height;
  const std::size_t count = refLab.size();
  result.error.resize(count);
  result.colorError.resize(count);
  result.featureError.resize(count);
  double sum = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const double color =
        remapColorDifference(std::pow(hyab(refLab[i], tstLab[i]), flip_constants::kQc), cmax);
    // ΔEf = (max(|‖edge_r‖ − ‖edge_t‖|, |‖point_r‖ − ‖point_t‖|) / √2)^qf.
    const double edge = std::abs(refFeatures.edges.values[i] - tstFeatures.edges.values[i]);
    const double point = std::abs(refFeatures.points.values[i] - tstFeatures.points.values[i]);
    const double feature = std::clamp(
        std::pow(std::max(edge, point) / std::numbers::sqrt2, flip_constants::kQf), 0.0, 1.0);
    // The combination: features amplify the colour difference.
    const double error = std::pow(color, 1.0 - feature);
    result.colorError[i] = static_cast<float>(color);
    result.featureError[i] = static_cast<float>(feature);
    result.error[i] = static_cast<float>(error);
    sum += error;
    result.max = std::max(result.max, result.error[i]);
  }
  result.mean = sum / static_cast<double>(count);
  return result;
}

std::vector<float> flipPercentiles(std::span<const float> values,
                                   std::span<const double> fractions) {
  std::vector<float> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  std::vector<float> result;
  for (const double fraction : fractions) {
    if (sorted.empty()) {
      result.push_back(0.0f);
      continue;
    }
    const double rank = std::ceil(std::clamp(fraction, 0.0, 1.0) * sorted.size());
    const std::size_t index = rank < 1.0 ? 0 : static_cast<std::size_t>(rank) - 1;
    result.push_back(sorted[std::min(index, sorted.size() - 1)]);
  }
  return result;
}

float flipPercentile(std::span<const float> values, double fraction) {
  return flipPercentiles(values, std::span(&fraction, 1)).front();
}

std::array<float, 3> magmaSrgb(float t) {
  // matplotlib's magma (van der Walt & Smith), sampled at t = 0, 0.1, …, 1 (sRGB-encoded).
  static constexpr float kSamples[11][3] = {
      {0.001462f, 0.000466f, 0.013866f}, {0.078815f, 0.054184f, 0.211667f},
      {0.232077f, 0.059889f, 0.437695f}, {0.390384f, 0.100379f, 0.501864f},
      {0.550287f, 0.161158f, 0.505719f}, {0.716387f, 0.214982f, 0.475290f},
      {0.868793f, 0.287728f, 0.409303f}, {0.967671f, 0.439703f, 0.359810f},
      {0.994738f, 0.624350f, 0.427397f}, {0.995680f, 0.812706f, 0.572645f},
      {0.987053f, 0.991438f, 0.749504f}};
  const float s = std::clamp(std::isnan(t) ? 0.0f : t, 0.0f, 1.0f) * 10.0f;
  const int i = std::min(static_cast<int>(s), 9);
  const float f = s - static_cast<float>(i);
  return {kSamples[i][0] + f * (kSamples[i + 1][0] - kSamples[i][0]),
          kSamples[i][1] + f * (kSamples[i + 1][1] - kSamples[i][1]),
          kSamples[i][2] + f * (kSamples[i + 1][2] - kSamples[i][2])};
}

}  // namespace memograph::runtime
