// The file names of a frame range's images (`render --frame-range A:B --out frame_####.exr`)
// and what makes one complete, for --resume.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace memograph::cli {

// Where `pattern` numbers its frames: the one run of '#' in its file name (not its folder).
struct FramePattern {
  std::string pattern;
  std::size_t hashesAt = std::string::npos;  // npos: no run, every frame the same name
  std::size_t hashes = 0;
};

// The pattern of an --out; nullopt with `error` set when its file name holds more than one
// run of '#' (which run counts would be a guess).
std::optional<FramePattern> parseFramePattern(const std::string& out, std::string& error);

// Frame `frame`'s file: the run of '#' replaced by the index, zero-padded to the run's
// width (frame_####.pfm, 7: frame_0007.pfm; more digits where the index needs them).
std::string framePath(const FramePattern& pattern, std::uint32_t frame);

// Whether `path` holds a whole image a reader accepts: a PFM whose header parses and whose
// size is the header's plus width x height pixels exactly; an .exr or .png that decodes
// (builds with the io module). A file cut short (a copy that stopped, a full disk that the
// atomic write did not see) is not complete; a torn write never has the final name.
bool imageFileComplete(const std::string& path);

}  // namespace memograph::cli
