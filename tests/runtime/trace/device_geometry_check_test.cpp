// deviceGeometryCheck (render_setup.h): a built-in scene's geometry is checked against the
// device while it is built, and the device is asked only once the geometry passes what every
// Vulkan device holds, so a render of a smaller scene creates no second Vulkan instance.
#include <cstdint>
#include <optional>

#include <gtest/gtest.h>

#include "runtime/scene/scene_limits.h"
#include "runtime/trace/render_setup.h"

namespace memograph::runtime {
namespace {

DeviceInfo deviceWithRange(std::uint32_t storageRangeBytes) {
  DeviceInfo info;
  info.name = "Small GPU";
  info.limits.maxStorageBufferRange = storageRangeBytes;
  info.maxMemoryAllocationSize = std::uint64_t(1) << 32;
  return info;
}

TEST(DeviceGeometryCheck, AsksTheDeviceOnlyPastWhatEveryDeviceHolds) {
  int asked = 0;
  const auto check = deviceGeometryCheck([&]() -> std::optional<DeviceInfo> {
    ++asked;
    return deviceWithRange(std::uint32_t(1) << 28);
  });
  // 2^21 vertices of 64 bytes and 2^23 triangles of 12 bytes: within 2^27 bytes each.
  check(std::uint64_t(1) << 21, std::uint64_t(1) << 23);
  EXPECT_EQ(asked, 0);
  // Twice that many vertices pass 2^27 bytes: the device is asked, once, and holds them.
  check(std::uint64_t(1) << 22, 0);
  check(std::uint64_t(1) << 22, 0);
  EXPECT_EQ(asked, 1);
  // Past its 2^28-byte range: refused.
  EXPECT_THROW(check(std::uint64_t(1) << 23, 0), SceneLimitError);
  EXPECT_EQ(asked, 1);
}

TEST(DeviceGeometryCheck, NoDeviceMeansNoCheck) {
  int asked = 0;
  const auto check = deviceGeometryCheck([&]() -> std::optional<DeviceInfo> {
    ++asked;
    return std::nullopt;
  });
  EXPECT_NO_THROW(check(std::uint64_t(1) << 30, std::uint64_t(1) << 30));
  EXPECT_NO_THROW(check(std::uint64_t(1) << 31, 0));
  EXPECT_EQ(asked, 1);  // asked once; the renderer then says that no device qualifies
}

}  // namespace
}  // namespace memograph::runtime
