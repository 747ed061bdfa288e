// Outputs appear whole or not at all, and a failed write is an OutputError (exit 5), not bad input.
#include "atomic_file.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include "errors.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("omnicam_atomic_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(AtomicFileTest, WritesTheBytesAndLeavesNoTemporary) {
  const std::string path = (dir_ / "a.txt").string();
  writeBytesAtomically(path, "first");
  writeBytesAtomically(path, "second, longer");
  std::ifstream in(path);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "second, longer");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

// Temporaries are what atomicTemporaryName gives, nothing that merely looks like one.
TEST(AtomicTemporaryName, IsExactlyTheNamesItGives) {
  for (const std::string name : {"frame.png", "manifest.json", "poses.tum", "a.b.exr", "noextension"}) {
    const std::string temporary = atomicTemporaryName(name);
    EXPECT_TRUE(isAtomicTemporaryName(temporary)) << temporary;
  }
  for (const std::string name : {".thesis.tmp-draft.tex", ".x.tmp-ab.png", ".x.tmp-ABCDEFGHIJ.png", ".x.tmp-abcdefghijk.png",
                                 "x.tmp-abcdefghij.png", ".x.tmp-abcdefghij.png.bak", ".tmp-abcdefghij.png", ".x.tmp-abcdefghij."})
    EXPECT_FALSE(isAtomicTemporaryName(name)) << name;
}

// Only the named folders are cleaned, and only of temporaries: a user's files stay, and so does
// everything in a folder reached through a link.
TEST_F(AtomicFileTest, TemporariesGoOnlyFromTheFoldersNamed) {
  const auto plant = [&](const fs::path& relative) {
    fs::create_directories((dir_ / relative).parent_path());
    std::ofstream(dir_ / relative) << "x";
  };
  const std::string leftover = ".000001.tmp-a1b2c3d4e5.png";
  for (const fs::path& p : {fs::path("cam/rgb") / leftover, fs::path(".manifest.tmp-0123456789.json"), fs::path("cam/rgb/000000.png"),
                           fs::path("notes") / leftover, fs::path(".thesis.tmp-draft.tex"), fs::path("cam/rgb/deeper") / leftover,
                           fs::path("elsewhere") / leftover})
    plant(p);
  fs::create_directory_symlink(dir_ / "elsewhere", dir_ / "cam" / "linked");
  removeAtomicTemporaries(dir_.string(), withParentFolders({"cam/rgb", "cam/linked"}));
  EXPECT_FALSE(fs::exists(dir_ / "cam/rgb" / leftover));
  EXPECT_FALSE(fs::exists(dir_ / ".manifest.tmp-0123456789.json"));
  for (const fs::path& p : {fs::path("cam/rgb/000000.png"), fs::path("notes") / leftover, fs::path(".thesis.tmp-draft.tex"),
                           fs::path("cam/rgb/deeper") / leftover, fs::path("elsewhere") / leftover})
    EXPECT_TRUE(fs::exists(dir_ / p)) << p << " was removed";
  EXPECT_EQ(withParentFolders({"a/b/c", "d"}), (std::set<std::string>{"", "a", "a/b", "a/b/c", "d"}));
}

TEST_F(AtomicFileTest, AFolderIsRefusedAsInputAndAMissingFolderIsAnOutputError) {
  fs::create_directories(dir_ / "out.png");
  EXPECT_THROW(writeBytesAtomically((dir_ / "out.png").string(), "x"), InputError);
  EXPECT_THROW(checkOutputFile((dir_ / "out.png").string(), "-o"), InputError);
  EXPECT_THROW(checkOutputFile((dir_ / "missing" / "x.png").string(), "-o"), InputError);
  EXPECT_THROW(checkOutputFile((dir_ / (std::string(250, 'a') + ".png")).string(), "-o"), InputError);
  EXPECT_NO_THROW(checkOutputFile((dir_ / (std::string(200, 'a') + ".png")).string(), "-o"));
  EXPECT_THROW(writeBytesAtomically((dir_ / "no" / "such" / "x.png").string(), "x"), OutputError);
}

TEST_F(AtomicFileTest, PastTheFileSizeLimitNothingAppearsUnderTheFinalName) {
  // In a child: the file-size limit and the ignored SIGXFSZ are process-wide.
  const std::string path = (dir_ / "big.bin").string();
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{1024, 1024};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    try {
      writeBytesAtomically(path, std::string(100000, 'x'));
    } catch (const OutputError&) {
      ::_exit(5);
    }
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 5);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(dir_)) << "the temporary was left behind";
}

}  // namespace
}  // namespace omnicam
