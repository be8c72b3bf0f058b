// Base64 (RFC 4648, with '=' padding) for glTF's embedded buffers (data URIs): OpenImageIO's
// encoder (Strutil::base64_encode; assimp has one too, but its shared library does not
// export it), taking bytes, so that callers need not see OpenImageIO.
#pragma once

#include <string>
#include <vector>

namespace memograph::io {

std::string base64Encode(const std::vector<unsigned char>& bytes);

}  // namespace memograph::io
