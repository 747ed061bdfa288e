#include "external_process.h"

#include <fcntl.h>
#include <spawn.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "errors.h"
#include "interrupts.h"

extern char** environ;

namespace omnicam {

std::string tailOfFile(const std::string& path, int lines) {
  std::ifstream in(path);
  std::deque<std::string> last;
  std::string line;
  while (std::getline(in, line)) {
    last.push_back(line);
    if (static_cast<int>(last.size()) > lines) last.pop_front();
  }
  std::string out;
  for (const auto& l : last) out += l + "\n";
  return out;
}

namespace {

using Clock = std::chrono::steady_clock;

// True once the leader `pid` has exited; it is left unreaped (a zombie), so its process group id
// cannot be taken by another group while the group is swept.
bool leaderExited(pid_t pid) {
  siginfo_t info{};
  return ::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid;
}

// Ends what is left of the group of the exited leader `pid` (helpers it left behind), reaps the
// leader, then the members its end handed to omnicam (the CLI is a child subreaper,
// base/interrupts.h), so that none still runs when this returns. Returns the leader's status.
int sweepAndReap(pid_t pid) {
  ::kill(-pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  while (::waitpid(-pid, nullptr, 0) > 0) {
  }
  return status;
}

// Ends the process group led by `pid`: SIGTERM (and SIGCONT), up to `graceSeconds` for the leader
// to exit, then SIGKILL to the whole group. Returns the leader's wait status.
int endProcessGroup(pid_t pid, double graceSeconds) {
  ::kill(-pid, SIGTERM);
  ::kill(-pid, SIGCONT);  // a stopped member acts on SIGTERM only once it runs
  const auto deadline = Clock::now() + std::chrono::duration<double>(graceSeconds);
  while (!leaderExited(pid) && Clock::now() <= deadline) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  return sweepAndReap(pid);  // SIGKILL: the members still there, the leader too if it outlived its grace
}

// Copies what was appended to the file at `path` since `offset` to stdout.
void echoNewOutput(const std::string& path, std::streamoff& offset) {
  std::ifstream in(path, std::ios::binary);
  if (!in.seekg(offset)) return;
  char buffer[4096];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    std::fwrite(buffer, 1, static_cast<size_t>(in.gcount()), stdout);
    offset += in.gcount();
  }
  std::fflush(stdout);
}

// A search path's entries made absolute from omnicam's folder (an empty one is that folder).
std::vector<std::filesystem::path> searchFolders(const std::string& path) {
  std::vector<std::filesystem::path> folders;
  size_t begin = 0;
  while (true) {
    const size_t end = path.find(':', begin);
    const std::string entry = path.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
    folders.push_back(entry.empty() ? std::filesystem::current_path() : std::filesystem::absolute(entry));
    if (end == std::string::npos) return folders;
    begin = end + 1;
  }
}

// PATH as the program gets it: its relative and empty entries made absolute, so that what the
// program itself starts (a script's interpreter through env, a wrapper's renderer) is found where
// findExecutable found the program, not in the folder it runs in.
std::string pathFromHere(const std::string& path) {
  std::string absolute;
  for (const std::filesystem::path& folder : searchFolders(path)) absolute += (absolute.empty() ? "" : ":") + folder.string();
  return absolute;
}

}  // namespace

std::string findExecutable(const std::string& command) {
  namespace fs = std::filesystem;
  if (command.empty()) return "";
  const auto executable = [](const fs::path& path) {
    std::error_code error;
    return fs::is_regular_file(path, error) && ::access(path.c_str(), X_OK) == 0;
  };
  if (command.find('/') != std::string::npos) {
    const fs::path path = fs::absolute(command);  // not normalised: "link/../x" is the kernel's to resolve
    return executable(path) ? path.string() : "";
  }
  // As execvp: PATH's entries in order, an empty one meaning the current folder, and the
  // system's default search path when PATH is unset.
  std::string searchPath;
  if (const char* path = std::getenv("PATH")) {
    searchPath = path;
  } else {
    searchPath.resize(::confstr(_CS_PATH, nullptr, 0));
    ::confstr(_CS_PATH, searchPath.data(), searchPath.size());
    searchPath.resize(std::strlen(searchPath.c_str()));
  }
  for (const fs::path& folder : searchFolders(searchPath))
    if (executable(folder / command)) return (folder / command).string();
  return "";
}

ProcessResult runProcess(const std::vector<std::string>& argv, const std::string& workDir,
                         const std::string& logPath, const ProcessOptions& options) {
  const DeferInterrupts deferred;
  throwIfInterrupted(argv.at(0) + " not started");
  ProcessResult result;
  // posix_spawn, not fork + exec: between fork and exec only async-signal-safe calls are allowed,
  // and setenv/open are not while TBB's threads exist. Everything the child needs — its own
  // process group (a timeout or an interrupt ends helpers too), working folder, HOME, log,
  // stdin — is prepared here and applied by the spawn itself.
  // Found here, in omnicam's own folder, as the user's shell would find it: the spawn changes
  // into workDir first, where a relative PATH entry or program path would find something else
  // (a program planted in an output folder).
  const std::string program = findExecutable(argv.at(0));
  if (program.empty()) {
    result.notFound = true;
    result.logTail = "cannot start: " + showPath(argv[0]) + ": no such program" +
                     (argv[0].find('/') == std::string::npos ? " in PATH" : "");
    return result;
  }
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::vector<std::string> environment;
  const auto withheld = [&](const char* variable) {
    for (const std::string& prefix : options.withoutVariables)
      if (std::strncmp(variable, prefix.c_str(), prefix.size()) == 0) return true;
    return std::strncmp(variable, "HOME=", 5) == 0 || (options.temporaryFilesInWorkDir && std::strncmp(variable, "TMPDIR=", 7) == 0);
  };
  for (char** e = environ; *e; ++e)
    if (!withheld(*e)) environment.emplace_back(std::strncmp(*e, "PATH=", 5) == 0 ? "PATH=" + pathFromHere(*e + 5) : std::string(*e));
  environment.push_back("HOME=" + workDir);
  if (options.temporaryFilesInWorkDir) environment.push_back("TMPDIR=" + workDir);
  std::vector<char*> envp;
  for (auto& e : environment) envp.push_back(e.data());
  envp.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attributes;
  posix_spawn_file_actions_init(&actions);
  posix_spawnattr_init(&attributes);
  posix_spawn_file_actions_addchdir_np(&actions, workDir.c_str());
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  // O_NOFOLLOW: a link planted where the log goes is never written through.
  // Absolute: the spawn changes into workDir before it opens the log.
  const std::string log = std::filesystem::absolute(logPath).string();
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawnattr_setpgroup(&attributes, 0);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGXFSZ);  // omnicam ignores it; the renderer gets the usual behaviour
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF);
  pid_t pid = -1;
  const int spawned = ::posix_spawn(&pid, program.c_str(), &actions, &attributes, args.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (spawned != 0) {
    result.notFound = spawned == ENOENT || spawned == EACCES;
    result.logTail = std::string("cannot start: ") + std::strerror(spawned);
    return result;
  }
  const auto interruption = [&](int signal) {
    return Interrupted(signal, "interrupted by " + signalName(signal) + " (" + std::filesystem::path(argv[0]).filename().string() + " ended)");
  };
  const auto deadline = Clock::now() + std::chrono::duration<double>(options.timeoutSeconds);
  std::streamoff echoed = 0;
  int status = 0;
  bool exited = false;
  while (!(exited = leaderExited(pid))) {
    if (options.echoOutput) echoNewOutput(logPath, echoed);
    if (const int signal = pendingInterrupt()) {
      endProcessGroup(pid, options.terminationGraceSeconds);
      throw interruption(signal);
    }
    if (Clock::now() > deadline) {
      status = endProcessGroup(pid, options.terminationGraceSeconds);
      result.timedOut = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (exited) status = sweepAndReap(pid);
  if (options.echoOutput) echoNewOutput(logPath, echoed);
  if (!result.timedOut && WIFEXITED(status)) result.exitCode = WEXITSTATUS(status);
  if (!result.timedOut && WIFSIGNALED(status)) result.endedBySignal = WTERMSIG(status);
  // The same signal reached the program too (a terminal's Ctrl-C, a service manager stopping the
  // whole group) and it ended before the loop saw ours: an interruption, not the program's failure.
  if (const int signal = pendingInterrupt(); signal && !result.timedOut && (result.exitCode != 0 || result.endedBySignal))
    throw interruption(signal);
  result.notFound = result.exitCode == 127;  // a shell's or env's "command not found" (a script's interpreter)
  result.logTail = tailOfFile(logPath, 15);
  // A failure's message quotes the tail: a blank there reads as a lost message.
  if (result.logTail.empty() && (result.timedOut || result.exitCode != 0)) result.logTail = "(no output)\n";
  return result;
}

void runConcurrently(size_t count, int workers, const std::function<void(size_t)>& task) {
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr first;
  std::mutex mutex;
  const auto work = [&] {
    for (size_t k = next++; k < count && !failed; k = next++) {
      try {
        task(k);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!first) first = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> threads;
  for (int w = 1; w < workers && static_cast<size_t>(w) < count; ++w) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  if (first) std::rethrow_exception(first);
}

}  // namespace omnicam
