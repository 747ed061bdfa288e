#pragma once
// Holds an omnicam process at a chosen point so a test can kill or interrupt it mid-run on any
// machine, fast or slow: the process, started with env(), stops right after it has written a
// manifest (or shard manifest) that lists at least one finished frame and is not complete, and
// stays there until release() or until it is killed (tests/hold_preload.cpp, an LD_PRELOAD
// wrapper of rename(2)). Nothing depends on how fast frames render.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace omnicam::testing {

class HoldPoint {
 public:
  // `folder`: created, holds the FIFO; `manifestName`: "manifest.json" or "shard-1-of-3.json".
  HoldPoint(const std::filesystem::path& folder, const std::string& manifestName);
  // Releases a held process that was not killed.
  ~HoldPoint();
  HoldPoint(const HoldPoint&) = delete;
  HoldPoint& operator=(const HoldPoint&) = delete;

  // Environment assignments for a shell command line ("LD_PRELOAD=... OMNICAM_HOLD_...=...").
  std::string shellAssignments() const;
  // The same as NAME=VALUE strings, for posix_spawn's envp.
  std::vector<std::string> environment() const;

  // True once the process is held; false if `ended()` says it ended first (or after `seconds`,
  // a guard against a process that never gets there).
  bool waitUntilHeld(const std::function<bool()>& ended, double seconds);
  // Lets the held process go on.
  void release();

 private:
  std::filesystem::path folder_;
  std::string manifestName_;
  int releaseFd_ = -1;
};

}  // namespace omnicam::testing
