#include "cli_util.h"

#include <fcntl.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "errors.h"

namespace omnicam::cli {
namespace {

// What `draw` writes to stderr while stderr is a terminal (a pseudo-terminal in raw mode, so that
// the bytes come back as written).
std::string stderrOnTerminal(const std::function<void()>& draw) {
  int terminal = -1, device = -1;
  if (::openpty(&terminal, &device, nullptr, nullptr, nullptr) != 0) throw std::runtime_error("openpty failed");
  termios raw{};
  ::tcgetattr(device, &raw);
  ::cfmakeraw(&raw);
  ::tcsetattr(device, TCSANOW, &raw);
  std::fflush(stderr);
  const int saved = ::dup(STDERR_FILENO);
  ::dup2(device, STDERR_FILENO);
  draw();
  std::fflush(stderr);
  ::dup2(saved, STDERR_FILENO);
  ::close(saved);
  ::close(device);
  ::fcntl(terminal, F_SETFL, O_NONBLOCK);
  std::string written;
  char chunk[4096];
  for (ssize_t n; (n = ::read(terminal, chunk, sizeof chunk)) > 0;) written.append(chunk, static_cast<size_t>(n));
  ::close(terminal);
  return written;
}

TEST(Progress, ABarLeftUnfinishedByAnErrorEndsItsLineSoTheErrorStartsOne) {
  const std::string written = stderrOnTerminal([] {
    try {
      Progress bar("render path.json", 4, 0, "frames");
      bar.step();
      throw std::runtime_error("frame 2 failed");
    } catch (const std::runtime_error&) {
      std::fprintf(stderr, "omnicam: frame 2 failed\n");
    }
  });
  ASSERT_NE(written.find("1/4"), std::string::npos) << written;
  EXPECT_NE(written.find(" \nomnicam: frame 2 failed\n"), std::string::npos) << written;
}

TEST(Progress, AFinishedBarEndsItsLineOnce) {
  const std::string written = stderrOnTerminal([] {
    Progress bar("render path.json", 2, 0, "frames");
    bar.step();
    bar.step();
    bar.finish();
  });
  ASSERT_NE(written.find("2/2"), std::string::npos) << written;
  EXPECT_EQ(written.back(), '\n') << written;
  EXPECT_NE(written[written.size() - 2], '\n') << written;
}

// A bar made when its first step is already done (an experiment's stage reports steps after
// they finish) has timed nothing: no rate (it printed millions of steps/s) and no ETA.
TEST(Progress, NoRateBeforeAStepWasTimed) {
  const std::string written = stderrOnTerminal([] {
    Progress bar("before", 15, 1, "before");
    bar.advanceTo(1);
  });
  EXPECT_NE(written.find("1/15  - before/s  ETA - "), std::string::npos) << written;
}

// What `draw` writes to stderr while stderr is a file (a log, no terminal).
std::string stderrInLog(const std::function<void()>& draw) {
  std::FILE* log = std::tmpfile();
  if (!log) throw std::runtime_error("tmpfile failed");
  std::fflush(stderr);
  const int saved = ::dup(STDERR_FILENO);
  ::dup2(::fileno(log), STDERR_FILENO);
  draw();
  std::fflush(stderr);
  ::dup2(saved, STDERR_FILENO);
  ::close(saved);
  std::rewind(log);
  std::string written;
  char chunk[4096];
  for (size_t n; (n = std::fread(chunk, 1, sizeof chunk, log)) > 0;) written.append(chunk, n);
  std::fclose(log);
  return written;
}

// In a log, a line per tenth of the work, and one at the first step 30 s after the last line: a
// long run's log shows it moving before its first tenth. The clock is the test's: a step a second.
TEST(Progress, ALogGetsALineEachTenthAndEvery30Seconds) {
  const std::string log = stderrInLog([] {
    auto now = std::chrono::steady_clock::time_point{};
    Progress bar("render rolling.json", 1000, 0, "renders", [&now] { return now; });
    for (int step = 1; step <= 120; ++step) {
      now += std::chrono::seconds(1);
      bar.step();
    }
  });
  EXPECT_EQ(log,
            "render rolling.json 30/1000  1.0 renders/s  ETA 16:10\n"
            "render rolling.json 60/1000  1.0 renders/s  ETA 15:40\n"
            "render rolling.json 90/1000  1.0 renders/s  ETA 15:10\n"
            "render rolling.json 100/1000  1.0 renders/s  ETA 15:00\n");
}

TEST(Progress, ABarThatNeverDrewWritesNothing) {
  EXPECT_EQ(stderrOnTerminal([] { Progress bar("render path.json", 2, 0, "frames"); }), "");
}

// Three numbers as people write them: spaces around each (copied from JSON) are no part of them.
TEST(ParseTriple, SpacesAroundTheNumbersAreIgnoredAndAnythingElseIsRefused) {
  const Vec3 v = parseTriple("1, 0, 90", "--velocity", "VX,VY,YAW_RATE");
  EXPECT_EQ(v.x(), 1.0);
  EXPECT_EQ(v.y(), 0.0);
  EXPECT_EQ(v.z(), 90.0);
  const Vec3 spaced = parseTriple(" -2.5 ,+3,  1e2 ", "--pose", "X,Y,YAW");
  EXPECT_EQ(spaced.x(), -2.5);
  EXPECT_EQ(spaced.y(), 3.0);
  EXPECT_EQ(spaced.z(), 100.0);
  const auto message = [](const std::string& text) {
    try {
      parseTriple(text, "--pose", "X,Y,YAW");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(message("1,2,3,4"), "--pose: expected three comma-separated numbers X,Y,YAW (got \"1,2,3,4\")");
  EXPECT_EQ(message("1,2 3,4"), "--pose: \"2 3\" is not a number");
  EXPECT_EQ(message("1, 2 3, 4"), "--pose: \"2 3\" is not a number");
  EXPECT_EQ(message("1, ,4"), "--pose: \"\" is not a number");
}

}  // namespace
}  // namespace omnicam::cli
