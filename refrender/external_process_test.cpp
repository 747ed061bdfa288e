// How runProcess finds the program it starts: from omnicam's own folder, as the user's shell
// would, never from the working folder it gives the program (an output folder someone else may
// write into).
#include "external_process.h"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "scratch_folder.h"

namespace fs = std::filesystem;
using omnicam::findExecutable;
using omnicam::ProcessResult;
using omnicam::runProcess;
using omnicam::test_support::ScratchFolder;

namespace {

// A script that prints `words`, executable.
void writeTool(const fs::path& path, const std::string& words) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << "#!/bin/sh\necho " << words << "\n";
  ::chmod(path.c_str(), 0755);
}

std::string contents(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Sets the current folder and PATH for one test and puts both back after it.
class CurrentFolderAndPath {
 public:
  CurrentFolderAndPath(const fs::path& folder, const std::optional<std::string>& path) : folder_(fs::current_path()) {
    if (const char* old = std::getenv("PATH")) path_ = old;
    fs::current_path(folder);
    if (path) ::setenv("PATH", path->c_str(), 1);
    else ::unsetenv("PATH");
  }
  ~CurrentFolderAndPath() {
    fs::current_path(folder_);
    if (path_) ::setenv("PATH", path_->c_str(), 1);
    else ::unsetenv("PATH");
  }
  CurrentFolderAndPath(const CurrentFolderAndPath&) = delete;
  CurrentFolderAndPath& operator=(const CurrentFolderAndPath&) = delete;

 private:
  fs::path folder_;
  std::optional<std::string> path_;
};

}  // namespace

TEST(FindExecutable, IsWhatExecvpWouldStartFromTheCurrentFolder) {
  const ScratchFolder scratch("find_executable");
  writeTool(scratch.path() / "home/bin/tool", "home");
  writeTool(scratch.path() / "home/later/tool", "later");
  std::ofstream(scratch.path() / "home/bin/plain") << "not executable\n";
  fs::create_directories(scratch.path() / "home/bin/folder");
  const fs::path home = fs::canonical(scratch.path() / "home");
  {
    const CurrentFolderAndPath here(home, "/nowhere:bin:later:/usr/bin:/bin");
    EXPECT_EQ(findExecutable("tool"), (home / "bin/tool").string()) << "the first PATH entry that has it, from here";
    EXPECT_EQ(findExecutable("plain"), "") << "a file without x permission is no program";
    EXPECT_EQ(findExecutable("folder"), "") << "nor is a folder";
    EXPECT_TRUE(findExecutable("sh") == "/usr/bin/sh" || findExecutable("sh") == "/bin/sh") << findExecutable("sh");
    EXPECT_EQ(findExecutable("./later/tool"), (home / "./later/tool").string()) << "a path with a slash is taken as it is";
    EXPECT_EQ(findExecutable("/bin/sh"), "/bin/sh");
    EXPECT_EQ(findExecutable("no-such-program-anywhere"), "");
    EXPECT_EQ(findExecutable(""), "");
  }
  {
    const CurrentFolderAndPath emptyEntry(home / "bin", "/nowhere::/bin");
    EXPECT_EQ(findExecutable("tool"), (home / "bin/tool").string()) << "an empty PATH entry is the current folder";
  }
  {
    const CurrentFolderAndPath unset(home, std::nullopt);
    EXPECT_EQ(findExecutable("tool"), "") << "without PATH only the system's default search path";
    EXPECT_NE(findExecutable("sh"), "") << "the system's default search path has sh";
  }
}

// omnicam's folder `home` and the folder the program runs in, `work`, each with its bin/tool,
// which says which it is.
struct HomeAndWork {
  explicit HomeAndWork(const ScratchFolder& scratch) {
    writeTool(scratch.path() / "home/bin/tool", "home");
    writeTool(scratch.path() / "work/bin/tool", "planted");
    home = fs::canonical(scratch.path() / "home");
    work = fs::canonical(scratch.path() / "work");
  }
  fs::path home, work;
};

TEST(RunProcess, FindsTheProgramFromOmnicamsFolderNotFromTheOneItRunsIn) {
  const ScratchFolder scratch("run_process_path");
  const auto [home, work] = HomeAndWork(scratch);
  const CurrentFolderAndPath here(home, "bin:/usr/bin:/bin");
  for (const std::string& command : {std::string("tool"), std::string("bin/tool"), std::string("./bin/tool")}) {
    const fs::path log = scratch.path() / "tool.log";
    const ProcessResult result = runProcess({command}, work.string(), log.string(), 60.0);
    EXPECT_EQ(result.exitCode, 0) << command << ": " << result.logTail;
    EXPECT_EQ(contents(log), "home\n") << command << " must start ./bin/tool of omnicam's folder, not of the work folder";
  }
}

// What the program itself starts through PATH (a script's `#!/usr/bin/env tool`, a wrapper's
// renderer) is found from omnicam's folder too: PATH's relative entries reach it made absolute.
TEST(RunProcess, WhatTheProgramStartsThroughPathIsFoundFromOmnicamsFolderToo) {
  const ScratchFolder scratch("run_process_child_path");
  const auto [home, work] = HomeAndWork(scratch);
  const CurrentFolderAndPath here(home, "bin::/usr/bin:/bin");
  const fs::path log = scratch.path() / "env.log";
  const ProcessResult result = runProcess({"/usr/bin/env", "tool"}, work.string(), log.string(), 60.0);
  EXPECT_EQ(result.exitCode, 0) << result.logTail;
  EXPECT_EQ(contents(log), "home\n");
  const ProcessResult path = runProcess({"/bin/sh", "-c", "echo \"$PATH\""}, work.string(), log.string(), 60.0);
  EXPECT_EQ(contents(log), (home / "bin").string() + ":" + home.string() + ":/usr/bin:/bin\n") << "an empty entry is omnicam's folder";
}

TEST(RunProcess, AProgramThatIsNowhereIsReportedNotFoundWithoutStartingAnything) {
  const ScratchFolder scratch("run_process_missing");
  const fs::path log = scratch.path() / "missing.log";
  const ProcessResult bare = runProcess({"no-such-program-anywhere", "--version"}, scratch.path().string(), log.string(), 60.0);
  EXPECT_TRUE(bare.notFound);
  EXPECT_EQ(bare.exitCode, -1);
  EXPECT_EQ(bare.logTail, "cannot start: no-such-program-anywhere: no such program in PATH");
  EXPECT_FALSE(fs::exists(log)) << "nothing was started, so no log";
  const ProcessResult path = runProcess({scratch.file("absent/tool")}, scratch.path().string(), log.string(), 60.0);
  EXPECT_TRUE(path.notFound);
  EXPECT_EQ(path.logTail, "cannot start: " + scratch.file("absent/tool") + ": no such program");
}

TEST(RunProcess, AFailureThatWroteNothingSaysSo) {
  const ScratchFolder scratch("run_process_silent");
  const fs::path log = scratch.path() / "silent.log";
  const ProcessResult failed = runProcess({"/bin/sh", "-c", "exit 3"}, scratch.path().string(), log.string(), 60.0);
  EXPECT_EQ(failed.exitCode, 3);
  EXPECT_EQ(failed.logTail, "(no output)\n");
  const ProcessResult passed = runProcess({"/bin/sh", "-c", "exit 0"}, scratch.path().string(), log.string(), 60.0);
  EXPECT_EQ(passed.exitCode, 0);
  EXPECT_EQ(passed.logTail, "") << "a program that succeeds silently has nothing to say";
  const ProcessResult said = runProcess({"/bin/sh", "-c", "echo why; exit 3"}, scratch.path().string(), log.string(), 60.0);
  EXPECT_EQ(said.logTail, "why\n");
}
