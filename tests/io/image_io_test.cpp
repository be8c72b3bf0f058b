// Image files: PNG/EXR output, texture input, PFM conversion, and clean failures.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "tools/io/image_io.h"
#include "tools/io/pfm.h"

namespace memograph::io {
namespace {

namespace fs = std::filesystem;
using compiler::Diagnostics;
using runtime::HdrImage;

class ImageIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("memograph_image_io_" +
           std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }
  std::string file(const std::string& name) const { return (dir / name).string(); }
  fs::path dir;
};

// A 5×3 image with distinct values per pixel and channel, some above 1.
HdrImage gradient() {
  HdrImage image{5, 3, {}};
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 5; ++x) {
      image.rgba.insert(image.rgba.end(), {0.1f * x, 0.3f * y, 1.5f * x * y, 0.25f * (x % 4)});
    }
  }
  return image;
}

TEST(ToSrgb8, EncodesTheSrgbCurveAfterExposureAndTonemap) {
  EXPECT_EQ(toSrgb8(0.0f, {}), 0);
  EXPECT_EQ(toSrgb8(1.0f, {}), 255);
  EXPECT_EQ(toSrgb8(7.0f, {}), 255);
  EXPECT_EQ(toSrgb8(0.5f, {}), 188);                         // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354
  EXPECT_EQ(toSrgb8(0.25f, {1.0f, Tonemap::Clamp}), 188);    // one stop up
  EXPECT_EQ(toSrgb8(1.0f, {0.0f, Tonemap::Reinhard}), 188);  // 1 / (1 + 1)
  EXPECT_LT(toSrgb8(4.0f, {0.0f, Tonemap::Aces}), 255);
  EXPECT_LT(toSrgb8(1.0f, {0.0f, Tonemap::Aces}), toSrgb8(4.0f, {0.0f, Tonemap::Aces}));
}

TEST_F(ImageIoTest, PngStoresSrgb8AndReadsBackAsRgba8) {
  const HdrImage image = gradient();
  Diagnostics diagnostics;
  ASSERT_TRUE(writeImage(file("out.png"), image, {}, diagnostics))
      << compiler::formatDiagnostics(diagnostics);
  const auto back = readImageRgba8(file("out.png"), diagnostics);
  ASSERT_TRUE(back.has_value()) << compiler::formatDiagnostics(diagnostics);
  ASSERT_EQ(back->width, 5);
  ASSERT_EQ(back->height, 3);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 5; ++x) {
      const float* p = image.pixel(x, y);
      const std::uint8_t* q = &back->rgba[(y * 5 + x) * 4];
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(q[c], toSrgb8(p[c], {})) << x << ',' << y;
      EXPECT_EQ(q[3], static_cast<std::uint8_t>(std::lround(p[3] * 255)));
    }
  }
  // Nothing but the image is left in the folder (the temporary was renamed).
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST_F(ImageIoTest, ExrRoundTripsFloatsExactly) {
  const HdrImage image = gradient();
  Diagnostics diagnostics;
  ASSERT_TRUE(writeImage(file("out.exr"), image, {}, diagnostics))
      << compiler::formatDiagnostics(diagnostics);
  const auto back = readImageFloat(file("out.exr"), diagnostics);
  ASSERT_TRUE(back.has_value()) << compiler::formatDiagnostics(diagnostics);
  EXPECT_EQ(back->width, 5);
  EXPECT_EQ(back->rgba, image.rgba);
}

TEST_F(ImageIoTest, PfmRoundTripsAndConvertsToPng) {
  HdrImage image = gradient();
  Diagnostics diagnostics;
  ASSERT_TRUE(writePfm(file("frame.pfm"), image, diagnostics));
  const auto back = readPfm(file("frame.pfm"), diagnostics);
  ASSERT_TRUE(back.has_value()) << compiler::formatDiagnostics(diagnostics);
  // PFM has no alpha: it reads back as 1.
  for (std::size_t i = 0; i < image.rgba.size(); ++i) {
    EXPECT_EQ(back->rgba[i], i % 4 == 3 ? 1.0f : image.rgba[i]) << i;
  }
  ASSERT_TRUE(convertPfm(file("frame.pfm"), file("frame.png"), {}, diagnostics))
      << compiler::formatDiagnostics(diagnostics);
  const auto png = readImageRgba8(file("frame.png"), diagnostics);
  ASSERT_TRUE(png.has_value());
  EXPECT_EQ(png->rgba[(2 * 5 + 1) * 4 + 1], toSrgb8(image.pixel(1, 2)[1], {}));
  ASSERT_TRUE(convertPfm(file("frame.pfm"), file("frame.exr"), {}, diagnostics));
  EXPECT_EQ(readImageFloat(file("frame.exr"), diagnostics)->rgba, back->rgba);
}

TEST_F(ImageIoTest, PfmReadsBigEndianAndGreyFiles) {
  {
    std::ofstream out(file("grey.pfm"), std::ios::binary);
    out << "Pf\n2 1\n1.0\n";                                           // positive scale: big-endian
    const unsigned char pixels[] = {0x3f, 0x80, 0, 0, 0x40, 0, 0, 0};  // 1.0, 2.0
    out.write(reinterpret_cast<const char*>(pixels), sizeof pixels);
  }
  Diagnostics diagnostics;
  const auto image = readPfm(file("grey.pfm"), diagnostics);
  ASSERT_TRUE(image.has_value()) << compiler::formatDiagnostics(diagnostics);
  EXPECT_EQ(image->rgba, (std::vector<float>{1, 1, 1, 1, 2, 2, 2, 1}));
}

TEST_F(ImageIoTest, BadPfmFilesGiveClearErrors) {
  std::ofstream(file("text.pfm")) << "hello";
  std::ofstream(file("short.pfm"), std::ios::binary) << "PF\n4 4\n-1.0\n" << std::string(10, '\0');
  const auto error = [&](const std::string& name) {
    Diagnostics diagnostics;
    EXPECT_FALSE(readPfm(file(name), diagnostics).has_value());
    return diagnostics.all().empty() ? "" : diagnostics.all()[0].message;
  };
  EXPECT_NE(error("text.pfm").find("not a PFM file"), std::string::npos);
  EXPECT_NE(error("short.pfm").find("truncated"), std::string::npos);
  EXPECT_NE(error("absent.pfm").find("no such file"), std::string::npos);
}

TEST_F(ImageIoTest, GreyImagesExpandToRgbaWithOpaqueAlpha) {
  std::ofstream(file("grey.pgm"), std::ios::binary) << "P5\n2 1\n255\n" << '\x00' << '\xc8';
  Diagnostics diagnostics;
  const auto image = readImageRgba8(file("grey.pgm"), diagnostics);
  ASSERT_TRUE(image.has_value()) << compiler::formatDiagnostics(diagnostics);
  EXPECT_EQ(image->rgba, (std::vector<std::uint8_t>{0, 0, 0, 255, 200, 200, 200, 255}));
  const auto floats = readImageFloat(file("grey.pgm"), diagnostics);
  ASSERT_TRUE(floats.has_value());
  EXPECT_FLOAT_EQ(floats->rgba[4], 200.0f / 255.0f);
  EXPECT_EQ(floats->rgba[7], 1.0f);
}

TEST_F(ImageIoTest, UnreadableImagesAreErrorsNotCrashes) {
  std::ofstream(file("fake.png")) << "this is not a png";
  Diagnostics diagnostics;
  EXPECT_FALSE(readImageRgba8(file("fake.png"), diagnostics).has_value());
  EXPECT_FALSE(readImageFloat(file("missing.exr"), diagnostics).has_value());
  EXPECT_FALSE(readImageRgba8(dir.string(), diagnostics).has_value());
  ASSERT_EQ(diagnostics.errorCount(), 3u);
  EXPECT_EQ(diagnostics.all()[0].file, file("fake.png"));
  EXPECT_NE(diagnostics.all()[1].message.find("no such file"), std::string::npos);
  EXPECT_NE(diagnostics.all()[2].message.find("is a folder"), std::string::npos);
}

TEST_F(ImageIoTest, WriteRefusesUnknownExtensionsAndBadImagesLeavingNoFile) {
  Diagnostics diagnostics;
  EXPECT_FALSE(writeImage(file("out.bmp"), gradient(), {}, diagnostics));
  HdrImage wrong = gradient();
  wrong.rgba.pop_back();
  EXPECT_FALSE(writeImage(file("out.png"), wrong, {}, diagnostics));
  EXPECT_FALSE(writeImage((dir / "no" / "such" / "dir.png").string(), gradient(), {}, diagnostics));
  EXPECT_EQ(diagnostics.errorCount(), 3u);
  EXPECT_TRUE(fs::is_empty(dir));
}

}  // namespace
}  // namespace memograph::io
