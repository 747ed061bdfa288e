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
