// base64Encode (OpenImageIO's encoder behind it) against the test vectors of RFC 4648 §10, and
// bytes above 0x7f: the glTF data URIs need standard base64 with padding.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tools/io/base64.h"

namespace memograph::io {
namespace {

std::string encode(const std::string& text) {
  return base64Encode(std::vector<unsigned char>(text.begin(), text.end()));
}

TEST(Base64, EncodesTheRfc4648Vectors) {
  EXPECT_EQ(encode(""), "");
  EXPECT_EQ(encode("f"), "Zg==");
  EXPECT_EQ(encode("fo"), "Zm8=");
  EXPECT_EQ(encode("foo"), "Zm9v");
  EXPECT_EQ(encode("foob"), "Zm9vYg==");
  EXPECT_EQ(encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(encode("foobar"), "Zm9vYmFy");
}

TEST(Base64, EncodesHighBytes) {
  EXPECT_EQ(base64Encode({0xff, 0xfe, 0xfd}), "//79");
  EXPECT_EQ(base64Encode({0x00, 0x80}), "AIA=");
}

}  // namespace
}  // namespace memograph::io
