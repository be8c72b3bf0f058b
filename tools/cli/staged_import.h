// The check `import-blender` makes on what the exporter left in its staging folder before
// any of it reaches the output folder: Blender runs arbitrary scripts and add-ons, so its
// output is untrusted input like any other (docs/guide/limits.md). Standard library, the
// compiler's parser and the JSON reader (tools/io/json_reader.h) only, so the fuzz target
// (tests/fuzz/staged_import_fuzzer.cpp) can drive it without Blender.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "compiler/input_file.h"

namespace memograph::cli {

struct StagedExportLimits {
  std::uint64_t maxGraphBytes = files::kMaxTextFileBytes;  // each .mgraph and index.json
  std::uint64_t maxFileBytes = files::kMaxImageFileBytes;  // any other file (textures, glTF)
  std::uint64_t maxTotalBytes = 4 * files::kMaxImageFileBytes;
  std::size_t maxEntries = 100000;  // files and folders
  int maxDepth = 4;                 // folders below the staging folder (textures/ is 1)
};

// What the exporter said it wrote: the count from its summary line ("memograph: wrote N
// material(s) to ..."), and whether the scene files were asked for (--scene).
struct StagedExportExpectation {
  std::optional<std::size_t> reportedMaterials;  // nullopt: no summary line was printed
  bool scene = false;
};

// Reads "memograph: wrote N material(s) to ..." (the exporter's summary); nullopt for any
// other line.
std::optional<std::size_t> parseExportSummary(std::string_view line);

// Checks the staged export in `staging`: still a real folder; only regular files and
// folders (no links, FIFOs, sockets or devices), each within the limits; index.json valid
// ({"materials": {name: {"file": "X.mgraph", "material": "X"}}}) and naming exactly the
// .mgraph files present; every graph parses and declares the material the index gives it;
// at least as many materials as the exporter reported; scene.gltf and scene.memograph with
// --scene. Returns an empty string when the export may be committed, else one message that
// names the offending file as `displayRoot`/<its path in the export> (a parse error as
// file:line:col).
std::string validateStagedExport(const std::filesystem::path& staging,
                                 const std::filesystem::path& displayRoot,
                                 const StagedExportExpectation& expected,
                                 const StagedExportLimits& limits = {});

}  // namespace memograph::cli
