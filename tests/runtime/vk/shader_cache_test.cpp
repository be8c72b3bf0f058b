// The SPIR-V disk cache: a second start with the same sources compiles nothing; a changed
// source (another material) misses.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <map>

#include <gtest/gtest.h>

#include "render_test_support.h"
#include "runtime/vk/shader_compiler.h"

namespace memograph::runtime {
namespace {

TEST(ShaderCache, SecondRunLoadsSpirvFromDisk) {
  auto directory = std::filesystem::temp_directory_path() / "memograph-cache-test";
  std::filesystem::remove_all(directory);
  RendererOptions options = testing::testOptions();
  options.shaderCacheDirectory = directory;
  Scene scene = testing::greyQuadScene("A");
  RenderSettings settings;
  settings.width = settings.height = 8;

  Renderer renderer(options);
  RenderResult first = renderer.render(scene, settings);
  EXPECT_GT(first.stats.shadersCompiled, 0u);
  EXPECT_EQ(first.stats.shaderCacheHits, 0u);
  RenderResult second = renderer.render(scene, settings);
  EXPECT_EQ(second.stats.shadersCompiled, 0u);
  EXPECT_EQ(second.stats.shaderCacheHits, first.stats.shadersCompiled);
  std::printf("shader cache: first start compiled %u shaders in %.1f ms, second loaded %u\n",
              first.stats.shadersCompiled, first.stats.shaderCompileMilliseconds,
              second.stats.shaderCacheHits);

  scene.materials[0].graphText = testing::constantGraph("A", {0.9f, 0.5f, 0.5f}, 0.5f);
  RenderResult third = renderer.render(scene, settings);
  EXPECT_GT(third.stats.shadersCompiled, 0u);
  std::filesystem::remove_all(directory);
}

TEST(ShaderCache, EachCallableMaterialHasItsOwnEntry) {
  auto directory = std::filesystem::temp_directory_path() / "memograph-callable-cache-test";
  std::filesystem::remove_all(directory);
  RendererOptions options = testing::testOptions(Backend::RayTracingPipeline);
  options.materialDispatch = MaterialDispatch::Callable;
  options.shaderCacheDirectory = directory;
  Scene scene;
  scene.meshes.push_back(testing::quad(2.0f));
  for (const char* name : {"A", "B", "C"})
    scene.materials.push_back({name, "", testing::constantGraph(name, {0.5f, 0.5f, 0.5f}, 0.5f)});
  for (std::uint32_t i = 0; i < 3; ++i)
    scene.instances.push_back({0, i, glm::mat4(1.0f)});
  scene.camera.position = {0, 3, 1};
  RenderSettings settings;
  settings.width = settings.height = 8;

  Renderer renderer(options);
  RenderResult first = renderer.render(scene, settings);
  // Raygen, two misses, closest hit, three callables.
  EXPECT_EQ(first.stats.shadersCompiled, 7u);
  RenderResult second = renderer.render(scene, settings);
  EXPECT_EQ(second.stats.shadersCompiled, 0u);
  EXPECT_EQ(second.stats.shaderCacheHits, 7u);
  // Another graph for one material: only its callable is compiled again.
  scene.materials[1].graphText = testing::constantGraph("B", {0.9f, 0.5f, 0.5f}, 0.5f);
  RenderResult third = renderer.render(scene, settings);
  EXPECT_EQ(third.stats.shadersCompiled, 1u);
  EXPECT_EQ(third.stats.shaderCacheHits, 6u);
  std::printf(
      "callable cache: first start compiled %u, second loaded %u, one changed material "
      "compiled %u\n",
      first.stats.shadersCompiled, second.stats.shaderCacheHits, third.stats.shadersCompiled);
  std::filesystem::remove_all(directory);
}

// A truncated or corrupt entry used to reach the driver on every later run. It
// is now dropped (with a warning), compiled again and rewritten; no temporaries are left.
TEST(ShaderCache, CorruptEntriesAreDroppedAndRecompiled) {
  const auto directory = std::filesystem::temp_directory_path() /
                         ("memograph-corrupt-cache-test-" + std::to_string(::getpid()));
  std::filesystem::remove_all(directory);
  const std::map<std::string, std::string> sources = {
      {"tiny.comp", "#version 460\nlayout(local_size_x = 1) in;\nvoid main() {}\n"}};
  const ShaderCompileRequest request{"tiny.comp", ShaderStage::Compute, {}};
  std::vector<std::uint32_t> reference;
  {
    ShaderCompiler compiler(sources, directory);
    reference = compiler.compile(request);
    EXPECT_EQ(compiler.stats().compiled, 1u);
  }
  std::vector<std::filesystem::path> entries;
  for (const auto& e : std::filesystem::directory_iterator(directory))
    entries.push_back(e.path());
  ASSERT_EQ(entries.size(), 1u);
  const auto entry = entries[0];
  ASSERT_EQ(entry.extension(), ".spv");
  const auto goodSize = std::filesystem::file_size(entry);
  auto corruptWith = [&](auto change) {
    change();
    ShaderCompiler compiler(sources, directory);
    EXPECT_EQ(compiler.compile(request), reference);
    EXPECT_EQ(compiler.stats().hits, 0u);
    EXPECT_EQ(compiler.stats().compiled, 1u);
    // Repaired: the next start loads it.
    ShaderCompiler again(sources, directory);
    EXPECT_EQ(again.compile(request), reference);
    EXPECT_EQ(again.stats().hits, 1u);
    EXPECT_EQ(std::filesystem::file_size(entry), goodSize);
  };
  corruptWith([&] { std::filesystem::resize_file(entry, goodSize - 8); });  // truncated
  corruptWith([&] { std::filesystem::resize_file(entry, goodSize - 3); });  // not whole words
  corruptWith([&] {                                                         // a flipped byte
    std::fstream f(entry, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(std::streamoff(goodSize - 5));
    f.put('\x5a');
  });
  corruptWith([&] { std::ofstream(entry, std::ios::trunc); });  // empty
  std::size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(directory)) {
    EXPECT_EQ(e.path().extension(), ".spv") << e.path();
    ++files;
  }
  EXPECT_EQ(files, 1u);
  std::filesystem::remove_all(directory);
}

// A cache entry that cannot be written (a full disk; here a file-size limit, the
// same failed write(2) without root) is a warning; the compiled shader is returned and no
// temporary is left behind. The compile runs in a child process with RLIMIT_FSIZE below
// an entry's size and SIGXFSZ ignored, so each write fails with EFBIG part-way.
TEST(ShaderCache, AnUnwritableEntryIsAWarningAndLeavesNoTemporary) {
  const auto directory = std::filesystem::temp_directory_path() /
                         ("memograph-full-cache-test-" + std::to_string(::getpid()));
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  const std::map<std::string, std::string> sources = {
      {"tiny.comp", "#version 460\nlayout(local_size_x = 1) in;\nvoid main() {}\n"}};
  const ShaderCompileRequest request{"tiny.comp", ShaderStage::Compute, {}};
  const std::vector<std::uint32_t> reference = ShaderCompiler(sources, {}).compile(request);
  ASSERT_GT(reference.size() * 4, 64u);

  int pipeFds[2];
  ASSERT_EQ(::pipe(pipeFds), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::dup2(pipeFds[1], STDERR_FILENO);
    ::close(pipeFds[0]);
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{64, 64};  // bytes: the header and a few words of SPIR-V
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0)
      ::_exit(3);
    ShaderCompiler compiler(sources, directory);
    const bool same = compiler.compile(request) == reference && compiler.stats().compiled == 1;
    std::cerr.flush();
    ::_exit(same ? 0 : 4);
  }
  ::close(pipeFds[1]);
  std::string stderrText;
  char buffer[4096];
  for (ssize_t n; (n = ::read(pipeFds[0], buffer, sizeof buffer)) > 0;)
    stderrText.append(buffer, std::size_t(n));
  ::close(pipeFds[0]);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "the compile was killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 0) << "3: setrlimit failed, 4: a wrong result; " << stderrText;
  EXPECT_NE(stderrText.find("warning: cannot write the shader cache entry"), std::string::npos)
      << stderrText;
  EXPECT_NE(stderrText.find("File too large"), std::string::npos) << stderrText;
  std::vector<std::string> left;
  for (const auto& e : std::filesystem::directory_iterator(directory))
    left.push_back(e.path().filename().string());
  EXPECT_TRUE(left.empty()) << "left behind: " << left.front();
  // Without the limit the same folder takes the entry.
  ShaderCompiler compiler(sources, directory);
  EXPECT_EQ(compiler.compile(request), reference);
  ShaderCompiler again(sources, directory);
  again.compile(request);
  EXPECT_EQ(again.stats().hits, 1u);
  std::filesystem::remove_all(directory);
}

TEST(ShaderCache, CompileErrorsNameTheFile) {
  ShaderCompiler compiler({{"bad.comp", "#version 460\nvoid main() { undefined_call(); }\n"}}, {});
  try {
    compiler.compile({"bad.comp", ShaderStage::Compute, {}});
    ADD_FAILURE() << "compiled";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.comp"), std::string::npos) << e.what();
  }
}

// compileAll (the wavefront's passes, the path tracer and its tile fill) compiles on several
// threads and returns each request's SPIR-V in the order asked, as one at a time would; its
// statistics count every shader once, and no compile time when everything came from the cache.
TEST(ShaderCache, CompileAllKeepsTheRequestsOrder) {
  const auto directory = std::filesystem::temp_directory_path() /
                         ("memograph-compile-all-test-" + std::to_string(::getpid()));
  std::filesystem::remove_all(directory);
  const std::map<std::string, std::string> sources = {
      {"value.comp",
       "#version 460\nlayout(local_size_x = 1) in;\nlayout(set = 0, binding = 0) buffer B { "
       "uint v; };\nvoid main() { v = VALUE; }\n"}};
  std::vector<ShaderCompileRequest> requests;
  for (int i = 0; i < 7; ++i)
    requests.push_back({"value.comp", ShaderStage::Compute, {"VALUE=" + std::to_string(i)}});
  ShaderCompiler one(sources, {});
  std::vector<std::vector<std::uint32_t>> expected;
  for (const auto& request : requests)
    expected.push_back(one.compile(request));
  ShaderCompiler compiler(sources, directory);
  EXPECT_EQ(compiler.compileAll(requests, 3), expected);
  EXPECT_EQ(compiler.stats().compiled, 7u);
  EXPECT_EQ(compiler.stats().hits, 0u);
  EXPECT_GT(compiler.stats().compileMilliseconds, 0.0);
  ShaderCompiler again(sources, directory);
  EXPECT_EQ(again.compileAll(requests, 3), expected);
  EXPECT_EQ(again.stats().compiled, 0u);
  EXPECT_EQ(again.stats().hits, 7u);
  EXPECT_EQ(again.stats().compileMilliseconds, 0.0);
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace memograph::runtime
