// The node library sources (nodes/**/*.inc), embedded at build time.
#pragma once

#include <span>
#include <string_view>

namespace memograph::nodes {

struct EmbeddedFile {
  std::string_view path;  // relative to nodes/, e.g. "prelude/common.inc"
  std::string_view text;
};

std::span<const EmbeddedFile> embeddedNodeLibrary();

}  // namespace memograph::nodes
