#pragma once
// Daemons a test starts for itself (Slurm's, a ROS master): each spawned without a shell, its
// output in a log file, and stopped exactly by the pid it was started with — SIGTERM, then
// SIGKILL after 10 s. No systemd, nothing else is touched.
#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace omnicam::testing {

class TestDaemons {
 public:
  TestDaemons() = default;
  // Stops every daemon it started, the last started first.
  ~TestDaemons();
  TestDaemons(const TestDaemons&) = delete;
  TestDaemons& operator=(const TestDaemons&) = delete;

  // Starts argv (argv[0] a path) with stdout and stderr to `log` and `environment` ("NAME=value")
  // added to this process's. False if it could not be started.
  bool start(const std::string& name, const std::vector<std::string>& argv, const std::filesystem::path& log,
             const std::vector<std::string>& environment = {});
  // The pid of daemon `name`, 0 if none of that name is running.
  pid_t pid(const std::string& name) const;
  // Stops daemon `name` now (SIGTERM, SIGKILL after 10 s) and forgets it.
  void stop(const std::string& name);
  // Waits up to `seconds` for daemon `name` to end by itself: its exit code, then forgets it;
  // -1 if it did not end in time (it keeps running) or ended by a signal.
  int waitForExit(const std::string& name, double seconds);

  // Polls `ready` until it holds or `seconds` pass (the limit only bounds a failure).
  static bool waitFor(const std::function<bool()>& ready, double seconds);
  // A free TCP port on localhost (the kernel's pick, released again at once).
  static int freePort();

 private:
  static void stopAndReap(pid_t pid);

  std::vector<std::pair<std::string, pid_t>> started_;
};

}  // namespace omnicam::testing
