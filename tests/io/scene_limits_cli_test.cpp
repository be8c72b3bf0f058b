// Hostile scenes through `memograph render`, as a user meets them (docs/guide/limits.md): an
// OBJ of 50 000 material switches, FIFOs where an OBJ names its material library or an MTL
// its texture, the full city on a device too small for it, a built-in option or a camera out
// of range. Each must end with a message and exit 1 (2 for a usage error), in seconds and
// within a bounded peak memory, measured from the child's own rusage (wait4).
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace {

namespace fs = std::filesystem;

struct CliRun {
  int exitCode = -1;  // -1: killed at the time limit
  std::string output;
  long peakRssKiB = 0;
  double seconds = 0.0;
};

// Runs the CLI with `args` in `dir`, killing it after `limitSeconds`; stdout and stderr
// together in `output`, its own peak RSS from wait4.
CliRun runCli(const fs::path& dir, const std::vector<std::string>& args, int limitSeconds = 60) {
  const fs::path log = dir / "cli_output.txt";
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = fork();
  if (child == 0) {
    if (chdir(dir.c_str()) != 0)
      _exit(127);
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    // MEMOGRAPH_CLI in the environment runs another build (e.g. one without a fix, to see
    // these tests fail on it).
    const char* cli = std::getenv("MEMOGRAPH_CLI") ? std::getenv("MEMOGRAPH_CLI") : MEMOGRAPH_CLI;
    std::vector<char*> argv{const_cast<char*>(cli)};
    for (const std::string& a : args)
      argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(cli, argv.data());
    _exit(127);
  }
  CliRun run;
  int status = 0;
  rusage usage{};
  for (;;) {
    const pid_t done = wait4(child, &status, WNOHANG, &usage);
    if (done == child)
      break;
    if (std::chrono::steady_clock::now() - start > std::chrono::seconds(limitSeconds)) {
      kill(child, SIGKILL);
      wait4(child, &status, 0, &usage);
      status = -1;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.exitCode = status == -1 ? -1 : (WIFEXITED(status) ? WEXITSTATUS(status) : 128);
  run.peakRssKiB = usage.ru_maxrss;
  std::ifstream in(log);
  run.output.assign(std::istreambuf_iterator<char>(in), {});
  return run;
}

class HostileScenes : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("memograph_hostile_" + std::string(info->name()) + "_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    setenv("XDG_RUNTIME_DIR", dir_.c_str(), 0);
  }
  void TearDown() override { fs::remove_all(dir_); }

  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
  }
  void fifo(const std::string& name) { ASSERT_EQ(mkfifo((dir_ / name).c_str(), 0644), 0); }
  CliRun render(const std::string& scene, std::vector<std::string> extra = {}) {
    std::vector<std::string> args{"render", scene, "--size", "4x4", "--out", "out.pfm"};
    args.insert(args.end(), extra.begin(), extra.end());
    return runCli(dir_, args);
  }
  bool wroteOutput() const { return fs::exists(dir_ / "out.pfm"); }

  fs::path dir_;
};

constexpr const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

// assimp's OBJ reader makes a mesh per material switch; 50 000 of them crashed lavapipe in
// its driver after 12 s and 1.9 GB. The OBJ pre-check refuses the mesh past the limit at its
// line, before assimp allocates anything.
TEST_F(HostileScenes, ObjWithFiftyThousandMaterialsIsRefusedAtTheMeshLimitCheaply) {
  std::string obj = kTriangle;
  for (int i = 0; i < 50000; ++i)
    obj += "usemtl m" + std::to_string(i) + "\nf 1 2 3\n";
  write("many.obj", obj);
  const CliRun run = render("many.obj");
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("many.obj:32773:1: error: this face starts mesh 16385"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("limit of 16384 meshes"), std::string::npos) << run.output;
  EXPECT_FALSE(wroteOutput());
  // Measured: 0.3 s and 140 MB; the bound is generous.
  EXPECT_LT(run.peakRssKiB, 1024 * 1024) << run.seconds << " s";
}

TEST_F(HostileScenes, ObjWhoseMaterialLibraryIsAFifoIsRefusedNotWaitedFor) {
  fifo("lib.mtl");
  write("fifo.obj", std::string("mtllib lib.mtl\n") + kTriangle + "f 1 2 3\n");
  const CliRun run = render("fifo.obj");
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("fifo.obj:1:8: error: the material library 'lib.mtl'"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("a FIFO"), std::string::npos) << run.output;
}

// A missing `mtllib` makes assimp open <obj name>.mtl instead: the pre-check follows it.
TEST_F(HostileScenes, ObjWhoseFallbackMaterialLibraryIsAFifoIsRefused) {
  fifo("fallback.mtl");
  write("fallback.obj", std::string("mtllib missing.mtl\n") + kTriangle + "f 1 2 3\n");
  const CliRun run = render("fallback.obj");
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("fallback.obj:1:8: error: the fallback material library "
                            "fallback.mtl (read in place of 'missing.mtl'): not a regular file "
                            "(a FIFO)"),
            std::string::npos)
      << run.output;
}

TEST_F(HostileScenes, MtlTextureThatIsAFifoIsRefusedAtItsLine) {
  fifo("wood.png");
  write("lib.mtl", "newmtl wood\nKd 1 1 1\nmap_Kd -o 0.5 0.5 1 -clamp on wood.png\n");
  write("tex.obj", std::string("mtllib lib.mtl\n") + kTriangle + "usemtl wood\nf 1 2 3\n");
  const CliRun run = render("tex.obj");
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("lib.mtl:3:31: error: the texture of 'map_Kd' 'wood.png'"),
            std::string::npos)
      << run.output;
}

// Found by the OBJ import fuzzer: assimp 5.2 crashed on it (exit 139).
TEST_F(HostileScenes, MtlTextureBeforeAnyMaterialIsRefusedNotCrashed) {
  write("early.mtl", "map_Kd wood.png\nnewmtl wood\n");
  write("early.obj", std::string("mtllib early.mtl\n") + kTriangle + "f 1 2 3\n");
  const CliRun run = render("early.obj");
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("early.mtl:1:1: error: 'map_Kd' comes before any 'newmtl'"),
            std::string::npos)
      << run.output;
}

TEST_F(HostileScenes, ObjMaterialLibraryWithAnAbsolutePathIsRefused) {
  write("abs.obj", std::string("mtllib /dev/zero\n") + kTriangle + "f 1 2 3\n");
  const CliRun run = render("abs.obj");
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("abs.obj:1:8: error: the material library '/dev/zero' is an "
                            "absolute path"),
            std::string::npos)
      << run.output;
}

// The full city needs 2.3 GB of vertices on lavapipe, whose storage binding holds 128 MiB:
// it was refused only after 40-60 s and 6.7 GB, by exit 2. The built-in scene now checks its
// buffers against the device after each mesh it adds, so the refusal comes once the vertices
// pass the device's range, before most of the city is made (measured: 0.5 s, 300 MB peak,
// where building the whole city first took 4 s and 2.3 GB); the bound is generous above it.
TEST_F(HostileScenes, CityTooLargeForTheDeviceIsRefusedWhileItIsBuilt) {
  const CliRun run = render("builtin:city", {"--size", "16x9"});
  if (run.output.find("llvmpipe") == std::string::npos)
    GTEST_SKIP() << "not lavapipe: the full city may fit this device\n" << run.output;
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("the scene's vertex buffer would need at least "), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("maxStorageBufferRange"), std::string::npos) << run.output;
  EXPECT_LT(run.peakRssKiB, 800 * 1024) << run.seconds << " s";
  EXPECT_FALSE(wroteOutput());
}

TEST_F(HostileScenes, BuiltinOptionOutOfRangeNamesTheOptionAndItsRange) {
  const CliRun run = render("builtin:landscape:terrain=0");
  EXPECT_EQ(run.exitCode, 2) << run.output;
  EXPECT_NE(run.output.find("terrain (the landscape's terrain grid: cells per side) is an "
                            "integer in 2..4096"),
            std::string::npos)
      << run.output;
  EXPECT_EQ(run.output.find("terrainCells"), std::string::npos) << run.output;
}

TEST_F(HostileScenes, CameraFarOutsideFloatRangeIsRefusedWithItsRange) {
  write("far.campath", "1e30 0 0 0 0 0 45\n");
  const CliRun run = render("builtin:landscape:terrain=2", {"--camera-path", "far.campath"});
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("far.campath:1:1: error: the camera's position (1e+30, 0, 0) is out "
                            "of range"),
            std::string::npos)
      << run.output;
  EXPECT_EQ(run.output.find("parallel"), std::string::npos) << run.output;
}

}  // namespace
