#pragma once
// Runs an external renderer headless: its own working folder and HOME, output captured to a
// log file, a wall-clock timeout. No shell is involved (arguments are passed as a vector).
#include <functional>
#include <string>
#include <vector>

namespace omnicam {

struct ProcessResult {
  int exitCode = -1;   // -1: not started, timed out, or ended by a signal
  int endedBySignal = 0;  // the signal that ended it, if one did (not by omnicam's timeout)
  bool timedOut = false;
  bool notFound = false;
  std::string logTail;  // last lines of stdout + stderr; "(no output)" when a failed or timed-out program wrote none
};

struct ProcessOptions {
  double timeoutSeconds = 600.0;
  // Copies what the program writes to the log onto omnicam's stdout as it comes (progress).
  bool echoOutput = false;
  // After SIGTERM (timeout or interrupt) the program's group has this long before SIGKILL: a
  // program of omnicam's own then ends its renderers and removes its job folders.
  double terminationGraceSeconds = 10.0;
  // TMPDIR is the working folder too (a renderer's job folder): what the program leaves in its
  // temporary folder when it is ended goes with the job folder.
  bool temporaryFilesInWorkDir = false;
  // Variables of omnicam's environment the program does not get, by prefix ("SQUEUE_": squeue's
  // own defaults, which would change what it lists).
  std::vector<std::string> withoutVariables;
};

// The absolute path of the program `command` names, as execvp would find it from the current
// folder: a path with a slash as it is, a bare name in PATH. "" when there is none.
std::string findExecutable(const std::string& command);

// argv[0] is found by findExecutable before the program is started in workDir.
// SIGTERM or SIGINT while it waits (base/interrupts.h) ends the program's whole process group and
// throws Interrupted; a timeout ends it the same way and reports timedOut.
ProcessResult runProcess(const std::vector<std::string>& argv, const std::string& workDir,
                         const std::string& logPath, const ProcessOptions& options);
inline ProcessResult runProcess(const std::vector<std::string>& argv, const std::string& workDir,
                                const std::string& logPath, double timeoutSeconds) {
  ProcessOptions options;
  options.timeoutSeconds = timeoutSeconds;
  return runProcess(argv, workDir, logPath, options);
}
// A renderer (POV-Ray, Blender) in its job folder: HOME and TMPDIR there.
inline ProcessResult runRenderer(const std::vector<std::string>& argv, const std::string& jobFolder,
                                 const std::string& logPath, double timeoutSeconds) {
  ProcessOptions options;
  options.timeoutSeconds = timeoutSeconds;
  options.temporaryFilesInWorkDir = true;
  return runProcess(argv, jobFolder, logPath, options);
}

// Runs task(0) … task(count − 1) on up to `workers` threads at once, for work that mostly waits
// on external processes. The first exception a task throws is rethrown once every running task is
// done; tasks not yet started then do not start.
void runConcurrently(size_t count, int workers, const std::function<void(size_t)>& task);

// Last `lines` lines of a text file ("" if unreadable).
std::string tailOfFile(const std::string& path, int lines);

}  // namespace omnicam
