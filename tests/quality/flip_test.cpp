// LDR-FLIP (tools/quality/flip.h): exact zero on identical images, monotone growth with a
// growing perturbation, and the simple cases the paper describes.
#include "tools/quality/flip.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <vector>

namespace memograph::runtime {
namespace {

constexpr int kSize = 48;

struct Image {
  int width = kSize, height = kSize;
  std::vector<float> rgb = std::vector<float>(static_cast<std::size_t>(kSize) * kSize * 3);

  float* at(int x, int y) { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
  FlipImageView view() const { return {rgb, width, height, 3}; }
};

Image filled(float r, float g, float b) {
  Image image;
  for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
    image.rgb[i] = r;
    image.rgb[i + 1] = g;
    image.rgb[i + 2] = b;
  }
  return image;
}

// A deterministic pattern in [-1, 1] (a 32-bit integer hash per pixel and channel).
float noise(int x, int y, int c) {
  std::uint32_t h = static_cast<std::uint32_t>(x) * 73856093u ^
                    static_cast<std::uint32_t>(y) * 19349663u ^
                    static_cast<std::uint32_t>(c) * 83492791u;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return static_cast<float>(h) / 4294967295.0f * 2.0f - 1.0f;
}

// A colourful, structured reference: gradients and a few edges.
Image reference() {
  Image image;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      float* p = image.at(x, y);
      p[0] = 0.2f + 0.6f * x / kSize;
      p[1] = 0.2f + 0.6f * y / kSize;
      p[2] = (x / 12 + y / 12) % 2 ? 0.7f : 0.3f;
    }
  }
  return image;
}

Image withNoise(const Image& base, float amplitude) {
  Image image = base;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      for (int c = 0; c < 3; ++c) {
        float& v = image.at(x, y)[c];
        v = std::clamp(v + amplitude * noise(x, y, c), 0.0f, 1.0f);
      }
  return image;
}

double meanFlip(const Image& a, const Image& b, FlipOptions options = {}) {
  return computeFlip(a.view(), b.view(), options).mean;
}

TEST(Flip, PixelsPerDegreeOfThePapersMonitor) {
  EXPECT_NEAR(defaultPixelsPerDegree(), 67.0206, 1e-3);
  EXPECT_NEAR(pixelsPerDegree(0.7, 0.7, 3840.0), defaultPixelsPerDegree(), 1e-12);
  EXPECT_NEAR(pixelsPerDegree(1.4, 0.7, 3840.0), 2.0 * defaultPixelsPerDegree(), 1e-9);
}

TEST(Flip, IdenticalImagesGiveExactlyZero) {
  const Image a = reference();
  const FlipResult result = computeFlip(a.view(), a.view());
  EXPECT_EQ(result.mean, 0.0);
  EXPECT_EQ(result.max, 0.0f);
  for (const float e : result.error)
    ASSERT_EQ(e, 0.0f);
  // A separate copy (not the same buffer) too, and linear input.
  const Image b = a;
  EXPECT_EQ(meanFlip(a, b, {.encoding = FlipEncoding::Linear}), 0.0);
}

TEST(Flip, ErrorsLieInTheUnitInterval) {
  const FlipResult result = computeFlip(reference().view(), withNoise(reference(), 0.8f).view());
  for (std::size_t i = 0; i < result.error.size(); ++i) {
    ASSERT_GE(result.error[i], 0.0f);
    ASSERT_LE(result.error[i], 1.0f);
    ASSERT_GE(result.featureError[i], 0.0f);
    ASSERT_LE(result.featureError[i], 1.0f);
  }
}

TEST(Flip, MeanGrowsWithTheNoiseAmplitude) {
  const Image a = reference();
  double previous = 0.0;
  for (const float amplitude : {0.01f, 0.03f, 0.06f, 0.1f, 0.2f, 0.35f, 0.5f}) {
    const double mean = meanFlip(a, withNoise(a, amplitude));
    EXPECT_GT(mean, previous) << "amplitude " << amplitude;
    previous = mean;
  }
}

TEST(Flip, MeanGrowsWithAColourShift) {
  const Image a = filled(0.3f, 0.4f, 0.5f);
  double previous = 0.0;
  for (const float shift : {0.01f, 0.02f, 0.05f, 0.1f, 0.2f, 0.4f}) {
    const double mean = meanFlip(a, filled(0.3f + shift, 0.4f, 0.5f - shift));
    EXPECT_GT(mean, previous) << "shift " << shift;
    previous = mean;
  }
}

TEST(Flip, BlackAgainstWhiteIsNearOne) {
  const FlipResult result = computeFlip(filled(0, 0, 0).view(), filled(1, 1, 1).view());
  // HyAB = 100 (lightness only), 100^0.7 ≈ 25.1 > pc·cmax: remapped into [pt, 1].
  EXPECT_GT(result.mean, 0.95);
  EXPECT_LE(result.max, 1.0f);
}

TEST(Flip, GreenAgainstBlueIsTheMaximum) {
  // cmax is defined by this pair, so the remapped colour difference is exactly 1.
  const FlipResult result = computeFlip(filled(0, 1, 0).view(), filled(0, 0, 1).view());
  EXPECT_NEAR(result.mean, 1.0, 1e-4);
}

TEST(Flip, FlatDifferencesHaveNoFeatureTerm) {
  const FlipResult result =
      computeFlip(filled(0.5f, 0.5f, 0.5f).view(), filled(0.6f, 0.6f, 0.6f).view());
  for (std::size_t i = 0; i < result.error.size(); ++i) {
    ASSERT_LT(result.featureError[i], 1e-3f);
    ASSERT_NEAR(result.error[i], result.colorError[i], 1e-3f);
  }
}

TEST(Flip, AOnePixelLineIsAmplifiedByTheFeatureTerm) {
  const Image grey = filled(0.5f, 0.5f, 0.5f);
  Image line = grey;
  for (int y = 0; y < kSize; ++y)
    for (int c = 0; c < 3; ++c)
      line.at(kSize / 2, y)[c] = 0.7f;
  const FlipResult lineResult = computeFlip(grey.view(), line.view());
  const FlipResult flatResult = computeFlip(grey.view(), filled(0.7f, 0.7f, 0.7f).view());
  const std::size_t centre = static_cast<std::size_t>(kSize / 2) * kSize + kSize / 2;
  // The CSF blurs the thin line, so its colour difference is smaller than the flat one's...
  EXPECT_LT(lineResult.colorError[centre], flatResult.colorError[centre]);
  // ...but the edge/point detectors see it, and ΔEc^(1 − ΔEf) raises it above ΔEc.
  EXPECT_GT(lineResult.featureError[centre], 0.1f);
  EXPECT_GT(lineResult.error[centre], 1.2f * lineResult.colorError[centre]);
  EXPECT_NEAR(flatResult.error[centre], flatResult.colorError[centre], 1e-4f);
  std::printf("line: colour %.4f feature %.4f FLIP %.4f; flat: colour %.4f FLIP %.4f\n",
              lineResult.colorError[centre], lineResult.featureError[centre],
              lineResult.error[centre], flatResult.colorError[centre], flatResult.error[centre]);
}

TEST(Flip, FartherViewingLowersTheErrorOfFineNoise) {
  const Image grey = filled(0.5f, 0.5f, 0.5f);
  const Image noisy = withNoise(grey, 0.15f);
  double previous = 2.0;
  for (const double ppd : {15.0, 30.0, 67.0, 120.0}) {
    const double mean = meanFlip(grey, noisy, {.pixelsPerDegree = ppd});
    EXPECT_LT(mean, previous) << "ppd " << ppd;
    previous = mean;
  }
}

TEST(Flip, IsSymmetric) {
  const Image a = reference();
  const Image b = withNoise(a, 0.2f);
  const FlipResult ab = computeFlip(a.view(), b.view());
  const FlipResult ba = computeFlip(b.view(), a.view());
  EXPECT_NEAR(ab.mean, ba.mean, 1e-5);
  for (std::size_t i = 0; i < ab.error.size(); ++i)
    ASSERT_NEAR(ab.error[i], ba.error[i], 1e-4f) << "pixel " << i;
}

TEST(Flip, SrgbAndLinearEncodingsAgree) {
  // The same colours, given once sRGB-encoded and once linear.
  auto encode = [](float linear) {
    return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
  };
  const Image a = reference();
  const Image b = withNoise(a, 0.1f);
  Image aSrgb = a, bSrgb = b;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) {
    aSrgb.rgb[i] = encode(a.rgb[i]);
    bSrgb.rgb[i] = encode(b.rgb[i]);
  }
  EXPECT_NEAR(meanFlip(a, b, {.encoding = FlipEncoding::Linear}), meanFlip(aSrgb, bSrgb), 1e-4);
}

TEST(Flip, RejectsMismatchedOrMalformedInput) {
  const Image a = reference();
  Image small;
  small.width = 8;
  small.height = 8;
  small.rgb.assign(8 * 8 * 3, 0.5f);
  EXPECT_THROW(computeFlip(a.view(), small.view()), std::invalid_argument);
  EXPECT_THROW(computeFlip(a.view(), {a.rgb, kSize, kSize, 2}), std::invalid_argument);
  EXPECT_THROW(computeFlip(a.view(), {std::span(a.rgb).first(10), kSize, kSize, 3}),
               std::invalid_argument);
  EXPECT_THROW(computeFlip(a.view(), a.view(), {.pixelsPerDegree = -1.0}), std::invalid_argument);
  EXPECT_THROW(computeFlip({a.rgb, 0, 0, 3}, {a.rgb, 0, 0, 3}), std::invalid_argument);
}

TEST(Flip, AcceptsRgbaAndIgnoresAlpha) {
  const Image a = reference();
  const Image b = withNoise(a, 0.1f);
  std::vector<float> aRgba, bRgba;
  for (std::size_t i = 0; i < a.rgb.size(); i += 3) {
    aRgba.insert(aRgba.end(), {a.rgb[i], a.rgb[i + 1], a.rgb[i + 2], 1.0f});
    bRgba.insert(bRgba.end(), {b.rgb[i], b.rgb[i + 1], b.rgb[i + 2], 0.0f});
  }
  EXPECT_EQ(computeFlip({aRgba, kSize, kSize, 4}, {bRgba, kSize, kSize, 4}).mean, meanFlip(a, b));
}

TEST(Flip, Percentiles) {
  const std::vector<float> values = {0.5f, 0.1f, 0.4f, 0.2f, 0.3f};
  EXPECT_EQ(flipPercentile(values, 0.0), 0.1f);
  EXPECT_EQ(flipPercentile(values, 0.5), 0.3f);
  EXPECT_EQ(flipPercentile(values, 0.95), 0.5f);
  EXPECT_EQ(flipPercentile(values, 1.0), 0.5f);
  EXPECT_EQ(flipPercentile({}, 0.5), 0.0f);
  const double fractions[] = {0.0, 0.5, 1.0};
  EXPECT_EQ(flipPercentiles(values, fractions), (std::vector<float>{0.1f, 0.3f, 0.5f}));
}

TEST(Flip, MagmaRunsFromBlackToPaleYellow) {
  const auto low = magmaSrgb(0.0f), high = magmaSrgb(1.0f), mid = magmaSrgb(0.5f);
  EXPECT_LT(low[0] + low[1] + low[2], 0.05f);
  EXPECT_GT(high[0], 0.95f);
  EXPECT_GT(high[1], 0.95f);
  EXPECT_GT(mid[0], mid[1]);  // purple-red in the middle
  EXPECT_EQ(magmaSrgb(-1.0f), low);
  EXPECT_EQ(magmaSrgb(2.0f), high);
}

}  // namespace
}  // namespace memograph::runtime
