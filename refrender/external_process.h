#pragma once
// Runs an external renderer headless: its own working folder and HOME, output captured to a
// log file, a wall-clock timeout. No shell is involved (arguments are passed as a vector).
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

// Last `lines` lines of a text file ("" if unreadable).
std::string tailOfFile(const std::string& path, int lines);

}  // namespace omnicam
