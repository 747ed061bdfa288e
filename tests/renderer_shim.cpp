#include "renderer_shim.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "markup.h"

extern char** environ;

namespace omnicam::testing {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> linesOf(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  return lines;
}

}  // namespace

RendererShim::RendererShim(const fs::path& folder, const std::string& realProgram) : folder_(folder) {
  fs::create_directories(folder);
  script_ = (folder / realProgram).string();  // omnicam names the program it ended by this name
  const std::string starts = (folder / "starts").string();
  std::ofstream out(script_);
  out << "#!/bin/sh\n"
         "# Test stand-in: the real renderer, stopped after its first output line.\n"
         "case \"$1\" in --version) exec " << realProgram << " \"$@\";; esac\n"
         "pipe=" << shellQuote((folder / "pipe").string()) << ".$$\n"
         "mkfifo \"$pipe\"\n"
      << realProgram << " \"$@\" >\"$pipe\" 2>&1 &\n"
         "renderer=$!\n"
         "{ IFS= read -r first; printf '%s\\n' \"$first\"; kill -STOP \"$renderer\"; echo \"$$ $renderer\" >> "
      << shellQuote(starts) << "; cat; } <\"$pipe\"\n"
         "rm -f \"$pipe\"\n"
         "wait \"$renderer\"\n";
  out.close();
  fs::permissions(script_, fs::perms::owner_all);
}

std::optional<ShimStart> RendererShim::waitForStart(size_t seen, const std::function<bool()>& ended,
                                                     double guardSeconds) const {
  const auto guard = std::chrono::steady_clock::now() + std::chrono::duration<double>(guardSeconds);
  while (true) {
    const std::vector<std::string> lines = linesOf(folder_ / "starts");
    if (lines.size() > seen) {
      std::istringstream words(lines[seen]);
      ShimStart start;
      words >> start.shell >> start.renderer;
      return start;
    }
    if (ended() || std::chrono::steady_clock::now() >= guard) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // polling the file, not waiting out a time
  }
}

SpawnedProcess::SpawnedProcess(const std::vector<std::string>& argv, const std::vector<std::string>& assignments,
                               const fs::path& log) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::vector<std::string> environment(assignments);
  for (char** e = environ; *e; ++e) environment.emplace_back(*e);
  std::vector<char*> envp;
  for (auto& e : environment) envp.push_back(e.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  const int failed = ::posix_spawn(&pid_, args[0], &actions, nullptr, args.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (failed) throw std::runtime_error("cannot start " + argv[0]);
}

SpawnedProcess::~SpawnedProcess() {
  if (reaped_) return;
  ::kill(pid_, SIGKILL);
  ::waitpid(pid_, &status_, 0);
}

bool SpawnedProcess::ended() {
  if (!reaped_ && ::waitpid(pid_, &status_, WNOHANG) == pid_) reaped_ = true;
  return reaped_;
}

int SpawnedProcess::waitForEnd() {
  if (!reaped_ && ::waitpid(pid_, &status_, 0) == pid_) reaped_ = true;
  return status_;
}

std::vector<pid_t> liveGroupMembers(pid_t group) {
  std::vector<pid_t> members;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(entry.path() / "stat");
    std::string stat;
    if (!std::getline(in, stat)) continue;
    // pid (comm) state ppid pgrp ...: comm may hold spaces, so read after the last ')'.
    std::istringstream rest(stat.substr(stat.rfind(')') + 1));
    char state = 0;
    long ppid = 0, pgrp = 0;
    rest >> state >> ppid >> pgrp;
    if (pgrp == group && state != 'Z' && state != 'X') members.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return members;
}

std::vector<std::string> tempFoldersStartingWith(const std::string& prefix) {
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(fs::temp_directory_path()))
    if (entry.path().filename().string().rfind(prefix, 0) == 0) found.push_back(entry.path().string());
  return found;
}

}  // namespace omnicam::testing
