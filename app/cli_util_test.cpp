#include "cli_util.h"

#include <fcntl.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <cstdio>
#include <functional>
#include <string>

#include <gtest/gtest.h>

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

TEST(Progress, ABarThatNeverDrewWritesNothing) {
  EXPECT_EQ(stderrOnTerminal([] { Progress bar("render path.json", 2, 0, "frames"); }), "");
}

}  // namespace
}  // namespace omnicam::cli
