// libFuzzer entry point: any bytes as a camera-path file (runtime/scene/builtin/camera_path.h).
// Crashes, hangs, leaks and sanitizer reports are findings; so is a rejected file without
// an error, or an accepted one with a frame the renderer cannot use. docs/design/testing.md.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "runtime/scene/builtin/camera_path.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace memograph;
  const compiler::SourceFile file{"fuzz.campath",
                                  std::string(reinterpret_cast<const char*>(data), size)};
  compiler::Diagnostics diagnostics;
  const auto path = runtime::parseCameraPath(file, diagnostics);
  if (!path) {
    if (!diagnostics.hasErrors())
      std::abort();  // rejected without saying why
    return 0;
  }
  for (const auto& camera : path->frames) {
    const float fov = camera.verticalFovDegrees;
    if (!(fov > 0.0f && fov < 180.0f) || !std::isfinite(camera.position.x) ||
        !std::isfinite(camera.target.x))
      std::abort();  // accepted a frame that validation should have refused
  }
  return 0;
}
