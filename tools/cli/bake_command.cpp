// memograph bake GRAPH|DIR... --size WxH --out DIR: evaluates every output a material
// writes over its UV square and writes one image per output (docs/guide/bake.md).
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>

#include "cli_common.h"
#include "commands.h"
#include "compiler/compiler.h"
#include "runtime/host/atomic_file.h"
#include "runtime/host/image.h"

#ifdef MEMOGRAPH_HAVE_RUNTIME
#include "runtime/materials/material_baker.h"
#include "runtime/renderer.h"
#include "runtime/vk/shader_compiler.h"
#endif
#ifdef MEMOGRAPH_HAVE_IO
#include "tools/io/image_io.h"
#endif

namespace memograph::cli {

namespace {

namespace fs = std::filesystem;

constexpr std::string_view kHelp =
    "usage: memograph bake GRAPH|DIR... --size WxH --out DIR [options]\n"
    "       memograph bake GRAPH|DIR... --size WxH --time R [options]\n"
    "\n"
    "Evaluates each material graph (a DIR means every .mgraph in it) at the pixel centres\n"
    "of its UV square and writes one image per output the material writes:\n"
    "DIR/<Material>_<output>.<ext>, output one of baseColor, metallic, roughness, specular,\n"
    "specularTint, cyclesPrincipled, normal, emission, opacity. Pixel (i, j) is uv\n"
    "((i + 0.5) / W, (j + 0.5) / H); j = 0 is v near 0 (Blender's img.pixels row 0).\n"
    "\n"
    "The material sits on a plane spanning the bounds in x and y at their centre in z\n"
    "(default: Blender's default plane, position = object = (2u-1, 2v-1, 0)), normal\n"
    "+Z (or --normal), geometric normal and view +Z, tangent +X, Generated coordinates\n"
    "from Blender's automatic texture space of the bounds, vertex colour 1, time 0.\n"
    "\n"
    "Files: every image is RGB; scalars are grey (R = G = B).\n"
    "  exr  32-bit float, exact values; the first stored row is the top (v near 1)\n"
    "  pfm  32-bit float, exact values; PFM stores the bottom row first, so the file's\n"
    "       first row is j = 0 (v near 0), Blender's img.pixels order\n"
    "  png  8-bit, top row first: baseColor and emission sRGB-encoded, scalars linear,\n"
    "       normal encoded as 0.5 * n + 0.5; values clamped to [0, 1]\n"
    "A material's files are written together or not at all; a graph that fails writes\n"
    "nothing while the others still bake (exit status 1 if any failed).\n"
    "\n"
    "options:\n"
    "  --size WxH        image size in pixels (required)\n"
    "  --out DIR         output directory, created if missing (required without --time)\n"
    "  --format F        exr, png or pfm (default exr; pfm in builds without OpenImageIO)\n"
    "  --bounds X0,Y0,Z0,X1,Y1,Z1\n"
    "                    the object's bounding box (default -1,-1,0,1,1,0)\n"
    "  --normal X,Y,Z    the shading normal over the whole plane, normalized (default\n"
    "                    0,0,1): a plane with custom normals, for nodes that read it\n"
    "  --nodes DIR       use the node library in DIR instead of the built-in one\n"
    "  --device N        Vulkan device index (render --list-devices lists them)\n"
    "  --shard I/N       bake only shard I of N (0 <= I < N): the graphs whose index in the\n"
    "                    list above (folders in name order) is I modulo N, so that N jobs\n"
    "                    with the same arguments bake each graph once (docs/guide/slurm.md)\n"
    "  --time R          write no image: evaluate each material R times on the device and\n"
    "                    print the median GPU time of one evaluation, in ns per pixel\n"
    "                    (timestamp queries around each dispatch; a pixel stores one float,\n"
    "                    the sum of its outputs; default: off)\n"
    "  --quiet           print only errors\n";

// Reads --bounds; false with `error` saying which number is wrong and why.
bool parseBounds(const std::string& text, std::array<float, 3>& lo, std::array<float, 3>& hi,
                 std::string& error) {
  constexpr double kMaxBound = 1e30;  // finite as floats with room: the shader computes in float
  constexpr std::array<const char*, 6> kNames = {"xmin", "ymin", "zmin", "xmax", "ymax", "zmax"};
  std::array<double, 6> values{};
  std::size_t start = 0;
  for (int k = 0; k < 6; ++k) {
    const std::size_t comma = text.find(',', start);
    if ((k < 5) != (comma != std::string::npos)) {
      error = "takes six numbers xmin,ymin,zmin,xmax,ymax,zmax";
      return false;
    }
    const std::string_view item = std::string_view(text).substr(
        start, comma == std::string::npos ? std::string::npos : comma - start);
    if (!parseReal(item, values[k]) || !std::isfinite(values[k])) {
      error = std::string(kNames[k]) + " '" + std::string(item) + "' is not a number";
      return false;
    }
    if (std::abs(values[k]) > kMaxBound) {
      error = std::string(kNames[k]) + " " + std::string(item) +
              " is out of range: each bound must lie within -1e30..1e30";
      return false;
    }
    start = comma + 1;
  }
  for (int k = 0; k < 3; ++k) {
    if (values[k] > values[k + 3]) {
      error = std::string(kNames[k]) + " is greater than " + kNames[k + 3];
      return false;
    }
    lo[k] = float(values[k]);
    hi[k] = float(values[k + 3]);
  }
  return true;
}

// Reads --normal: three finite numbers, not all zero, normalized; false with `error` saying
// which number is wrong and why.
bool parseNormal(const std::string& text, std::array<float, 3>& normal, std::string& error) {
  constexpr std::array<const char*, 3> kNames = {"x", "y", "z"};
  std::array<double, 3> values{};
  std::size_t start = 0;
  for (int k = 0; k < 3; ++k) {
    const std::size_t comma = text.find(',', start);
    if ((k < 2) != (comma != std::string::npos)) {
      error = "takes three numbers x,y,z";
      return false;
    }
    const std::string_view item = std::string_view(text).substr(
        start, comma == std::string::npos ? std::string::npos : comma - start);
    if (!parseReal(item, values[k]) || !std::isfinite(values[k]) || std::abs(values[k]) > 1e30) {
      error = std::string(kNames[k]) + " '" + std::string(item) + "' is not a finite number";
      return false;
    }
    start = comma + 1;
  }
  const double length =
      std::sqrt(values[0] * values[0] + values[1] * values[1] + values[2] * values[2]);
  if (!(length > 0.0)) {
    error = "the normal must not be zero";
    return false;
  }
  for (int k = 0; k < 3; ++k)
    normal[k] = float(values[k] / length);
  return true;
}

// Checks --out before any work: a folder, or nothing there yet. A dangling symbolic link
// or a file is named as such (create_directories alone says "File exists").
bool checkOutputFolder(const std::string& outDir, std::string& error) {
  std::error_code ec;
  const fs::file_status linkStatus = fs::symlink_status(outDir, ec);
  const fs::file_status status = fs::status(outDir, ec);
  if (fs::is_symlink(linkStatus) && !fs::exists(status)) {
    const fs::path to = fs::read_symlink(outDir, ec);
    error = "is a dangling symbolic link (to " + to.string() + "); name a folder";
    return false;
  }
  if (fs::exists(status) && !fs::is_directory(status)) {
    error = "is a file, not a folder";
    return false;
  }
  return true;
}

// Checks --out and creates it; false (reported) when it is not a folder or cannot be made.
bool prepareOutputFolder(const std::string& outDir) {
  if (std::string error; !checkOutputFolder(outDir, error)) {
    std::cerr << "memograph bake: --out " << outDir << ": " << error << "\n";
    return false;
  }
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (ec || !fs::is_directory(outDir)) {
    std::cerr << "memograph bake: " << outDir << ": cannot create the folder"
              << (ec ? " (" + ec.message() + ")" : std::string()) << "\n";
    return false;
  }
  return true;
}

// The graphs named on the command line: files as given, folders as their .mgraph files in
// name order. A folder without one is an error of its own.
std::vector<std::string> expandInputs(const std::vector<std::string>& inputs,
                                      compiler::Diagnostics& diagnostics) {
  std::vector<std::string> files;
  for (const auto& input : inputs) {
    std::error_code ec;
    if (!fs::is_directory(input, ec)) {
      files.push_back(input);
      continue;
    }
    std::vector<std::string> found;
    for (const auto& entry : fs::directory_iterator(input, ec)) {
      if (entry.path().extension() == ".mgraph" && !entry.is_directory())
        found.push_back(entry.path().string());
    }
    if (ec)
      diagnostics.error(input, "cannot list the folder: " + ec.message());
    else if (found.empty())
      diagnostics.error(input, "the folder holds no .mgraph file");
    std::sort(found.begin(), found.end());
    files.insert(files.end(), found.begin(), found.end());
  }
  return files;
}

#ifdef MEMOGRAPH_HAVE_RUNTIME

enum class OutputKind { Colour, Scalar, Normal };

// One output image of a material in the writers' row order: `rgb` top row first.
struct OutputImage {
  std::string output;
  OutputKind kind = OutputKind::Colour;
  std::vector<float> rgb;
};

std::vector<OutputImage> outputImages(const runtime::BakeOutputs& baked,
                                      const std::vector<std::string>& written) {
  const std::uint32_t w = baked.width, h = baked.height;
  std::vector<OutputImage> images;
  for (const auto& name : written) {
    const std::vector<std::array<float, 3>>* colour = nullptr;
    const std::vector<float>* scalar = nullptr;
    OutputKind kind = OutputKind::Colour;
    if (name == "baseColor") {
      colour = &baked.baseColor;
    } else if (name == "emission") {
      colour = &baked.emission;
    } else if (name == "normal") {
      colour = &baked.normal;
      kind = OutputKind::Normal;
    } else if (name == "metallic") {
      scalar = &baked.metallic;
    } else if (name == "roughness") {
      scalar = &baked.roughness;
    } else if (name == "specular") {
      scalar = &baked.specular;
    } else if (name == "specularTint") {
      scalar = &baked.specularTint;
    } else if (name == "cyclesPrincipled") {
      scalar = &baked.cyclesPrincipled;
    } else if (name == "opacity") {
      scalar = &baked.opacity;
    } else if (name == "lobes") {
      throw std::runtime_error(
          "the material writes BSDF lobes (Diffuse, Glossy or Velvet BSDF), "
          "which a bake cannot store in textures: bake a Principled BSDF");
    } else {
      throw std::runtime_error("the material writes '" + name +
                               "', an output this bake does not know");
    }
    if (scalar)
      kind = OutputKind::Scalar;
    OutputImage image{name, kind, std::vector<float>(std::size_t(w) * h * 3)};
    // Baked row j (v near 0 first) is the image's row h - 1 - j (top row first).
    for (std::uint32_t j = 0; j < h; ++j) {
      for (std::uint32_t i = 0; i < w; ++i) {
        const std::size_t from = std::size_t(j) * w + i;
        float* to = &image.rgb[(std::size_t(h - 1 - j) * w + i) * 3];
        for (int c = 0; c < 3; ++c)
          to[c] = colour ? (*colour)[from][c] : (*scalar)[from];
      }
    }
    images.push_back(std::move(image));
  }
  return images;
}

// Writes one image into the staged (temporary) file `file`; the target's extension is the
// format.
bool stageOutputImage(files::StagedFile& file, const std::string& format, std::uint32_t width,
                      std::uint32_t height, const OutputImage& image,
                      compiler::Diagnostics& diagnostics) {
  const std::string target = file.target().string();
  std::string error;
  if (format == "pfm") {
    runtime::HdrImage hdr;
    hdr.width = width;
    hdr.height = height;
    hdr.rgba.resize(std::size_t(width) * height * 4);
    for (std::size_t p = 0; p < std::size_t(width) * height; ++p) {
      for (int c = 0; c < 3; ++c)
        hdr.rgba[p * 4 + c] = image.rgb[p * 3 + c];
      hdr.rgba[p * 4 + 3] = 1.0f;
    }
    if (!file.write(runtime::encodePfm(hdr), error)) {
      diagnostics.error(target, error);
      return false;
    }
    return true;
  }
#ifdef MEMOGRAPH_HAVE_IO
  const std::string temporary = file.temporaryPath().string();
  bool ok = false;
  if (format == "png" && image.kind == OutputKind::Normal) {
    std::vector<float> encoded(image.rgb.size());
    for (std::size_t k = 0; k < encoded.size(); ++k)
      encoded[k] = 0.5f * image.rgb[k] + 0.5f;
    ok =
        io::writeRgbImage(temporary, width, height, encoded, io::RgbEncoding::Linear8, diagnostics);
  } else if (format == "png") {
    ok = io::writeRgbImage(
        temporary, width, height, image.rgb,
        image.kind == OutputKind::Colour ? io::RgbEncoding::Srgb8 : io::RgbEncoding::Linear8,
        diagnostics);
  } else {
    ok =
        io::writeRgbImage(temporary, width, height, image.rgb, io::RgbEncoding::Float, diagnostics);
  }
  if (ok && !file.sync(error)) {
    diagnostics.error(target, error);
    ok = false;
  }
  return ok;
#else
  diagnostics.error(target, "this build writes only .pfm (no OpenImageIO)");
  return false;
#endif
}

// Writes a material's images as one set through the project's atomic output path
// (files::StagedFile, files::commitFileSet): every image is staged first; only when all
// were written are they renamed into place, and a rename failing part-way restores the
// files already replaced. A failure leaves no temporary behind.
bool writeMaterialImages(const std::string& outDir, const std::string& material,
                         const std::string& format, std::uint32_t width, std::uint32_t height,
                         const std::vector<OutputImage>& images, std::vector<std::string>& written,
                         compiler::Diagnostics& diagnostics) {
  std::vector<files::StagedFile> staged;
  for (const auto& image : images) {
    const fs::path target = fs::path(outDir) / (material + "_" + image.output + "." + format);
    files::StagedFile file;
    std::string error;
    if (!file.create(target, error)) {
      diagnostics.error(target.string(), error);
      return false;
    }
    if (!stageOutputImage(file, format, width, height, image, diagnostics))
      return false;
    staged.push_back(std::move(file));
  }
  std::string error;
  if (!files::commitFileSet(staged, error)) {
    diagnostics.error(outDir, error);
    return false;
  }
  for (const auto& file : staged)
    written.push_back(file.target().string());
  return true;
}

runtime::TextureImage loadTexture(const std::string& path) {
#ifdef MEMOGRAPH_HAVE_IO
  compiler::Diagnostics textureDiagnostics;
  auto image = io::readImageFloat(path, textureDiagnostics);
  if (!image)
    throw std::runtime_error(compiler::formatDiagnostics(textureDiagnostics));
  return runtime::TextureImage{{std::move(*image)}};
#else
  return runtime::loadTextureCore(path);
#endif
}

// One bake call: its settings, and what it keeps from one material to the next (the
// baker, made at the first material that needs it, and the names baked so far).
struct BakeRun {
  runtime::BakeSettings settings;
  std::string outDir, format;
  std::uint32_t timedDispatches = 0;  // --time: 0 bakes images
  int deviceIndex = -1;
  bool quiet = false;
  const compiler::NodeLibrary* library = nullptr;
  std::unique_ptr<runtime::MaterialBaker> baker;
  std::string deviceError;
  std::set<std::string> names;
};

runtime::MaterialBaker& bakerFor(BakeRun& run) {
  if (!run.baker && run.deviceError.empty()) {
    try {
      runtime::ContextOptions context;
      context.deviceIndex = run.deviceIndex;
      run.baker =
          std::make_unique<runtime::MaterialBaker>(context, runtime::defaultShaderCacheDirectory());
    } catch (const std::exception& e) {
      run.deviceError = std::string("no Vulkan device: ") + e.what();
    }
  }
  if (!run.baker)
    throw std::runtime_error(run.deviceError);
  return *run.baker;
}

// --time's line for one material on stdout, which tools/bench/node_costs_device.sh reads:
// "time NAME NS_PER_PIXEL ns/pixel (median of R dispatches of WxH)". The median, so that a
// first dispatch that warms caches or clocks does not count.
void printMedianTime(const std::string& name, const BakeRun& run, std::vector<double> dispatchNs) {
  std::sort(dispatchNs.begin(), dispatchNs.end());
  const std::size_t n = dispatchNs.size();
  const double median =
      n % 2 == 1 ? dispatchNs[n / 2] : 0.5 * (dispatchNs[n / 2 - 1] + dispatchNs[n / 2]);
  const double pixels = double(run.settings.width) * run.settings.height;
  std::ostringstream line;
  line.precision(6);  // a cheap evaluation is a few thousandths of a ns a pixel
  line << std::fixed << "time " << name << " " << median / pixels << " ns/pixel (median of " << n
       << " dispatches of " << run.settings.width << "x" << run.settings.height << ")";
  std::cout << line.str() << std::endl;
}

// Bakes the material compiled from `path` and writes its images; `written` receives their
// paths. False with `diagnostics` (or the returned `message`) saying why.
bool bakeCompiled(BakeRun& run, const std::string& path, const compiler::CompiledMaterial& material,
                  std::vector<std::string>& written, compiler::Diagnostics& diagnostics,
                  std::string& message) {
  try {
    runtime::MaterialBaker& baker = bakerFor(run);
    runtime::BakeMaterial bakeMaterial;
    bakeMaterial.name = material.metadata.name;
    bakeMaterial.glsl = material.glsl;
    const fs::path base = fs::path(path).parent_path();
    for (const auto& texture : material.metadata.textures) {
      fs::path texturePath(texture);
      if (texturePath.is_relative() && !base.empty())
        texturePath = base / texturePath;
      bakeMaterial.textures.push_back(loadTexture(texturePath.string()));
    }
    if (run.timedDispatches > 0) {
      printMedianTime(material.metadata.name, run,
                      baker.timeDispatches(bakeMaterial, run.settings, run.timedDispatches));
      return true;
    }
    const runtime::BakeOutputs baked = baker.bake(bakeMaterial, run.settings);
    const auto images = outputImages(baked, material.metadata.outputsWritten);
    return writeMaterialImages(run.outDir, material.metadata.name, run.format, run.settings.width,
                               run.settings.height, images, written, diagnostics);
  } catch (const std::exception& e) {
    message = std::string("memograph bake: ") + path + ": " + e.what();
    return false;
  }
}

// Compiles, bakes and writes one graph, reporting it as `prefix` ("[i/n] "). False when it
// failed (reported).
bool bakeOne(BakeRun& run, const std::string& path, const std::string& prefix) {
  compiler::Diagnostics diagnostics;
  std::string label = fs::path(path).stem().string();
  auto fail = [&](const std::string& message) {
    std::cerr << prefix << label << " ... failed\n";
    printDiagnostics(diagnostics);
    if (!message.empty())
      std::cerr << message << "\n";
    return false;
  };
  std::string error;
  const auto text = readFile(path, error);
  if (!text) {
    diagnostics.error(path, error);
    return fail("");
  }
  compiler::CompileOptions options;
  options.emitGlsl = true;
  options.emitHlsl = false;
  const compiler::SourceFile source{path, *text};
  const auto material = compiler::compileMaterial(source, *run.library, options, diagnostics);
  if (!material)
    return fail("");
  const std::string& name = material->metadata.name;
  label = name;
  if (!run.names.insert(name).second) {
    diagnostics.error(path, "material '" + name +
                                "' was already baked from another graph in this call; "
                                "rename one (file name or `material Name;`)");
    return fail("");
  }
  std::vector<std::string> written;
  if (std::string message; !bakeCompiled(run, path, *material, written, diagnostics, message))
    return fail(message);
  printDiagnostics(diagnostics);  // warnings
  if (!run.quiet) {
    std::cerr << prefix << name << " ... ok";
    if (written.empty() && run.timedDispatches == 0)
      std::cerr << " (writes no output)";
    std::cerr << "\n";
    for (const auto& file : written)
      std::cout << "wrote " << file << "\n";
  }
  return true;
}

#endif  // MEMOGRAPH_HAVE_RUNTIME

struct BakeArguments {
  std::string size, outDir, format, bounds, normal, nodesDir, device = "-1", shard, time;
  std::uint32_t shardIndex = 0, shardCount = 1;
  bool quiet = false;
  std::vector<std::string> inputs;
};

// The arguments, with what is required and the format checked.
std::optional<int> scanBakeArguments(std::span<const std::string_view> args, BakeArguments& a) {
  ArgumentScanner scanner("bake", args);
  scanner.option("--size", &a.size);
  scanner.option("--out", &a.outDir);
  scanner.option("-o", &a.outDir);
  scanner.option("--format", &a.format);
  scanner.option("--bounds", &a.bounds);
  scanner.option("--normal", &a.normal);
  scanner.option("--nodes", &a.nodesDir);
  scanner.option("--device", &a.device);
  scanner.option("--shard", &a.shard);
  scanner.option("--time", &a.time);
  scanner.flag("--quiet", &a.quiet);
  scanner.help(kHelp);
  if (const auto exitCode = scanner.scan(a.inputs))
    return exitCode;
  if (a.inputs.empty())
    return usageError("bake", "no graph files or folders given");
  if (a.outDir.empty() && a.time.empty())
    return usageError("bake", "--out DIR is required (or --time R, which writes no image)");
  if (a.size.empty())
    return usageError("bake", "--size WxH is required");
  if (!a.shard.empty()) {
    const std::size_t slash = a.shard.find('/');
    if (slash == std::string::npos ||
        !parseNumber(std::string_view(a.shard).substr(0, slash), a.shardIndex) ||
        !parseNumber(std::string_view(a.shard).substr(slash + 1), a.shardCount) ||
        a.shardCount == 0 || a.shardIndex >= a.shardCount)
      return usageError("bake",
                        "--shard takes I/N, shard I of N with 0 <= I < N (e.g. 0/4), "
                        "not '" +
                            a.shard + "'");
  }
#ifdef MEMOGRAPH_HAVE_IO
  if (a.format.empty())
    a.format = "exr";
  if (a.format != "exr" && a.format != "png" && a.format != "pfm")
    return usageError("bake", "--format must be exr, png or pfm, not '" + a.format + "'");
#else
  if (a.format.empty())
    a.format = "pfm";
  if (a.format != "pfm")
    return usageError(
        "bake", "this build writes only --format pfm (no OpenImageIO), not '" + a.format + "'");
#endif
  return std::nullopt;
}

#ifdef MEMOGRAPH_HAVE_RUNTIME
// --time's bound: all dispatches go in one command buffer, which must finish in seconds.
constexpr std::uint32_t kMaxTimedDispatches = 1000;

// The size, bounds, device and timing as the bake's settings.
std::optional<int> readBakeSettings(const BakeArguments& a, BakeRun& run) {
  if (std::string error; !parseImageSize(a.size, run.settings.width, run.settings.height, error))
    return usageError("bake", "--size: " + error);
  if (std::string error; !a.bounds.empty() && !parseBounds(a.bounds, run.settings.boundsMin,
                                                           run.settings.boundsMax, error))
    return usageError("bake", "--bounds '" + a.bounds + "': " + error);
  if (std::string error; !a.normal.empty() && !parseNormal(a.normal, run.settings.normal, error))
    return usageError("bake", "--normal '" + a.normal + "': " + error);
  std::uint32_t deviceIndex = 0;
  if (a.device != "-1" && (!parseNumber(a.device, deviceIndex) ||
                           deviceIndex > std::uint32_t(std::numeric_limits<int>::max())))
    return usageError("bake", "--device takes a device index, not '" + a.device + "'");
  run.deviceIndex = a.device == "-1" ? -1 : int(deviceIndex);
  if (const int code = checkDeviceIndex("bake", run.deviceIndex); code != kExitOk)
    return code;
  if (!a.time.empty() && (!parseNumber(a.time, run.timedDispatches) || run.timedDispatches == 0 ||
                          run.timedDispatches > kMaxTimedDispatches))
    return usageError("bake", "--time takes a number of dispatches from 1 to " +
                                  std::to_string(kMaxTimedDispatches) + ", not '" + a.time + "'");
  run.outDir = a.outDir;
  run.format = a.format;
  run.quiet = a.quiet;
  return std::nullopt;
}
#endif

}  // namespace

int runBake(std::span<const std::string_view> args) {
  BakeArguments a;
  if (const auto exitCode = scanBakeArguments(args, a))
    return *exitCode;
#ifndef MEMOGRAPH_HAVE_RUNTIME
  std::cerr << "memograph bake: this build has no Vulkan runtime\n";
  return kExitFailure;
#else
  BakeRun run;
  if (const auto exitCode = readBakeSettings(a, run))
    return *exitCode;
  compiler::Diagnostics setup;
  const auto library = loadNodeLibrary(a.nodesDir, setup);
  if (!library) {
    printDiagnostics(setup);
    return kExitFailure;
  }
  run.library = &*library;
  std::vector<std::string> files = expandInputs(a.inputs, setup);
  printDiagnostics(setup);
  if (a.shardCount > 1) {
    // By index in the expanded list, not by a hash of the name: the list is the same for
    // every shard given the same arguments, and shards differ in size by one at most.
    std::vector<std::string> shard;
    for (std::size_t index = a.shardIndex; index < files.size(); index += a.shardCount)
      shard.push_back(files[index]);
    if (!a.quiet)
      std::cerr << "shard " << a.shardIndex << "/" << a.shardCount << ": " << shard.size() << " of "
                << files.size() << " graphs\n";
    files = std::move(shard);
  }
  // A timing writes no file: it needs no folder.
  if (run.timedDispatches == 0 && !prepareOutputFolder(a.outDir))
    return kExitFailure;
  const std::size_t total = files.size();
  std::size_t failed = 0;
  for (std::size_t index = 0; index < total; ++index) {
    const std::string prefix = "[" + std::to_string(index + 1) + "/" + std::to_string(total) + "] ";
    if (!bakeOne(run, files[index], prefix))
      ++failed;
  }
  if (failed > 0) {
    std::cerr << "memograph bake: " << failed << " of " << total << " material"
              << (total == 1 ? "" : "s") << " failed"
              << (failed == total ? "; nothing written" : "; the others were written") << "\n";
  }
  return failed > 0 || setup.hasErrors() ? kExitFailure : kExitOk;
#endif
}

}  // namespace memograph::cli
