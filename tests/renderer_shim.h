#pragma once
// Stand-ins for what the interrupt and demo tests drive, so that they synchronise on what
// processes have written, never on time:
// - RendererShim: a script named by OMNICAM_POVRAY or OMNICAM_BLENDER that runs the real renderer
//   and, once it has written its first line, stops it (SIGSTOP) and appends "<shell pid> <renderer
//   pid>" to a file the test reads. The renderer cannot finish before the test acts; omnicam's
//   SIGTERM + SIGCONT to the group ends it. `--version` runs the real program untouched.
// - SpawnedProcess: a command started with its own pid (to signal it) and its output in a file.
// - liveGroupMembers: what is left of a process group (zombies count as gone).
#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace omnicam::testing {

struct ShimStart {
  pid_t shell = -1;     // the script: leader of the process group omnicam gave the renderer
  pid_t renderer = -1;  // the real renderer, stopped after its first line
};

class RendererShim {
 public:
  // `folder` is created; `realProgram` is "povray" or "blender" (found on PATH).
  RendererShim(const std::filesystem::path& folder, const std::string& realProgram);
  const std::string& script() const { return script_; }
  // The start after `seen` earlier ones, once its renderer has written its first line and is
  // stopped; nullopt if `ended()` says the process under test ended first, or after a guard of
  // `guardSeconds` (a test that never gets there fails instead of hanging).
  std::optional<ShimStart> waitForStart(size_t seen, const std::function<bool()>& ended, double guardSeconds) const;

 private:
  std::filesystem::path folder_;
  std::string script_;
};

class SpawnedProcess {
 public:
  // `assignments`: extra NAME=VALUE environment entries; stdout and stderr go to `log`.
  SpawnedProcess(const std::vector<std::string>& argv, const std::vector<std::string>& assignments,
                 const std::filesystem::path& log);
  ~SpawnedProcess();  // kills and reaps a process the test did not wait for
  SpawnedProcess(const SpawnedProcess&) = delete;
  SpawnedProcess& operator=(const SpawnedProcess&) = delete;
  pid_t pid() const { return pid_; }
  bool ended();        // reaps it if it has ended
  int waitForEnd();    // its wait status
  int status() const { return status_; }

 private:
  pid_t pid_ = -1;
  bool reaped_ = false;
  int status_ = 0;
};

// Live processes (not zombies) whose process group is `group`.
std::vector<pid_t> liveGroupMembers(pid_t group);
// Folders in the temporary folder whose name starts with `prefix` (job folders of renderers).
std::vector<std::string> tempFoldersStartingWith(const std::string& prefix);

}  // namespace omnicam::testing
