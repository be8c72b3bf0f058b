#include "tools/io/base64.h"

#include <string_view>

#include <OpenImageIO/strutil.h>

namespace memograph::io {

std::string base64Encode(const std::vector<unsigned char>& bytes) {
  return OIIO::Strutil::base64_encode(
      std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace memograph::io
