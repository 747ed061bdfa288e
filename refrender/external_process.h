#pragma once
// Runs an external renderer headless: its own working folder and HOME, output captured to a
// log file, a wall-clock timeout. No shell is involved (arguments are passed as a vector).
#include <functional>
#include <string>
#include <vector>

namespace omnicam {

struct ProcessResult {
  int exitCode = -1;
  bool timedOut = false;
  bool notFound = false;
  std::string logTail;  // last lines of stdout + stderr
};

ProcessResult runProcess(const std::vector<std::string>& argv, const std::string& workDir,
                         const std::string& logPath, double timeoutSeconds);

// Runs task(0) … task(count − 1) on up to `workers` threads at once, for work that mostly waits
// on external processes. The first exception a task throws is rethrown once every running task is
// done; tasks not yet started then do not start.
void runConcurrently(size_t count, int workers, const std::function<void(size_t)>& task);

// Last `lines` lines of a text file ("" if unreadable).
std::string tailOfFile(const std::string& path, int lines);

}  // namespace omnicam
