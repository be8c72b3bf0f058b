// Base64 (RFC 4648, with '=' padding) for glTF's embedded buffers (data URIs). Assimp has an
// encoder, but its shared library does not export it.
#pragma once

#include <string>
#include <vector>

namespace memograph::io {

std::string base64Encode(const std::vector<unsigned char>& bytes);

}  // namespace memograph::io
