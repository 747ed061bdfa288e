// SIGTERM and SIGINT to verbs that run POV-Ray or Blender (issue #45, "No orphans"): the
// renderer's whole process group ends, no job folder and no partial output is left, and the
// verb ends as the signal says. The signal is sent once the renderer has written its first line
// and been stopped by the test's stand-in (tests/renderer_shim.h), so nothing depends on speed.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "renderer_shim.h"
#include "shell_command.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;
using testing::liveGroupMembers;
using testing::RendererShim;
using testing::SpawnedProcess;

constexpr double kGuardSeconds = 600.0;  // a run that never reaches its renderer fails, not hangs

class InterruptTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("omnicam_interrupt_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "tmp");
    fs::create_directories(dir_ / "out");
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs `args` with `variable` naming a shim of `renderer`, signals it once the renderer has
  // started and checks what every verb must leave: no process of the renderer's group, no job
  // folder (TMPDIR is the test's), and nothing but `allowed` in the output folder. With
  // `renderersGroupFirst`, the renderer's group gets the signal first (and is continued, so that
  // it ends), as a terminal's Ctrl-C or a service manager's stop sends it to every process.
  int interruptAtFirstLine(const std::vector<std::string>& args, const std::string& variable, const std::string& renderer,
                           int signal, bool renderersGroupFirst = false) {
    const RendererShim shim(dir_ / "shim", renderer);
    std::vector<std::string> argv{OMNICAM_BINARY};
    argv.insert(argv.end(), args.begin(), args.end());
    SpawnedProcess run(argv, {variable + "=" + shim.script(), "TMPDIR=" + (dir_ / "tmp").string()}, dir_ / "log");
    const auto start = shim.waitForStart(0, [&] { return run.ended(); }, kGuardSeconds);
    EXPECT_TRUE(start.has_value()) << "the renderer never started:\n" << testing::readFile(dir_ / "log");
    if (!start) return -1;
    EXPECT_FALSE(liveGroupMembers(start->shell).empty());  // the stand-in and its renderer, stopped
    if (renderersGroupFirst) {
      ::kill(-start->shell, signal);
      ::kill(-start->shell, SIGCONT);
    }
    ::kill(run.pid(), signal);
    const int status = run.waitForEnd();
    EXPECT_EQ(liveGroupMembers(start->shell), std::vector<pid_t>{}) << "the renderer's group outlived omnicam";
    EXPECT_TRUE(fs::is_empty(dir_ / "tmp")) << "a job folder was left: " << fs::directory_iterator(dir_ / "tmp")->path();
    return status;
  }

  std::string log() const { return testing::readFile(dir_ / "log"); }
  // A POV-Ray dataset of three small frames.
  fs::path povrayDatasetSpec() const {
    const fs::path spec = dir_ / "spec.json";
    std::ofstream(spec) << nlohmann::json{{"format", "omnicam-dataset/1"},
                                          {"scene", std::string(OMNICAM_SOURCE_DIR) + "/scenes/robocup2006.json"},
                                          {"engine", "povray"},
                                          {"size", 48},
                                          {"poses", {{"path", "thesis-loop"}, {"frames", 3}}}}
                               .dump();
    return spec;
  }

  fs::path dir_;
};

TEST_F(InterruptTest, SigtermToAPovrayRenderEndsPovrayAndLeavesNothing) {
  const int status = interruptAtFirstLine({"render", std::string(OMNICAM_SOURCE_DIR) + "/scenes/robocup2006.json", "--engine",
                                           "povray", "--size", "64", "-o", (dir_ / "out" / "frame.png").string()},
                                          "OMNICAM_POVRAY", "povray", SIGTERM);
  ASSERT_TRUE(WIFSIGNALED(status)) << log();
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_TRUE(fs::is_empty(dir_ / "out")) << "partial output";
  EXPECT_NE(log().find("omnicam: interrupted by SIGTERM (povray"), std::string::npos) << log();
}

TEST_F(InterruptTest, SigintToABlenderRenderEndsBlenderAndLeavesNothing) {
  const int status = interruptAtFirstLine({"render", std::string(OMNICAM_SOURCE_DIR) + "/scenes/robocup2006.json", "--engine",
                                           "blender", "--size", "64", "-o", (dir_ / "out" / "frame.png").string()},
                                          "OMNICAM_BLENDER", "blender", SIGINT);
  ASSERT_TRUE(WIFSIGNALED(status)) << log();
  EXPECT_EQ(WTERMSIG(status), SIGINT);
  EXPECT_TRUE(fs::is_empty(dir_ / "out")) << "partial output";
}

// A dataset stops resumably: its manifest lists what finished, no frame is half-written, and the
// run says how to resume (exit 130, as for Ctrl-C between frames).
TEST_F(InterruptTest, SigtermToAPovrayDatasetEndsPovrayAndLeavesAResumableFolder) {
  const fs::path spec = povrayDatasetSpec();
  const fs::path out = dir_ / "out" / "ds";
  const int status = interruptAtFirstLine({"dataset", spec.string(), "-o", out.string()}, "OMNICAM_POVRAY", "povray", SIGTERM);
  ASSERT_TRUE(WIFEXITED(status)) << log();
  EXPECT_EQ(WEXITSTATUS(status), 130) << log();
  EXPECT_NE(log().find("interrupted by SIGTERM (povray"), std::string::npos) << log();
  EXPECT_NE(log().find("run the same command again to resume"), std::string::npos) << log();
  for (const auto& f : fs::recursive_directory_iterator(out))
    EXPECT_EQ(f.path().filename().string().find(".tmp-"), std::string::npos) << f.path();
  const auto status2 = testing::runShell(std::string(OMNICAM_BINARY) + " dataset --status " + out.string() + " 2>&1");
  EXPECT_EQ(status2.code, 1) << status2.out;  // incomplete, and readable
  EXPECT_NE(status2.out.find("0 of 3 frames finished"), std::string::npos) << status2.out;
}

// The signal to every process, the renderer's group first: POV-Ray ends by it before omnicam's
// loop sees its own, which is still an interruption (exit 130, resumable), not "povray: failed".
TEST_F(InterruptTest, SigtermToTheRendererTooIsAnInterruptionNotARendererFailure) {
  const fs::path spec = povrayDatasetSpec();
  const int status = interruptAtFirstLine({"dataset", spec.string(), "-o", (dir_ / "out" / "ds").string()}, "OMNICAM_POVRAY", "povray",
                                          SIGTERM, /*renderersGroupFirst=*/true);
  ASSERT_TRUE(WIFEXITED(status)) << log();
  EXPECT_EQ(WEXITSTATUS(status), 130) << log();
  EXPECT_NE(log().find("interrupted by SIGTERM (povray"), std::string::npos) << log();
  EXPECT_EQ(log().find("failed"), std::string::npos) << log();
}

// The demo's sections are omnicam processes of their own: the signal reaches the section, which
// ends its renderer; the report is not written half.
TEST_F(InterruptTest, SigtermToTheDemoEndsItsSectionAndTheSectionsRenderer) {
  const int status = interruptAtFirstLine({"demo", "--no-blender", "-o", (dir_ / "out" / "demo").string()},
                                          "OMNICAM_POVRAY", "povray", SIGTERM);
  ASSERT_TRUE(WIFSIGNALED(status)) << log();
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_FALSE(fs::exists(dir_ / "out" / "demo" / "index.html"));
  for (const auto& f : fs::recursive_directory_iterator(dir_ / "out"))
    EXPECT_EQ(f.path().filename().string().find(".tmp-"), std::string::npos) << f.path();
}

}  // namespace
}  // namespace omnicam
