#include "test_daemons.h"

#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <thread>

extern char** environ;

namespace omnicam::testing {

using Clock = std::chrono::steady_clock;

TestDaemons::~TestDaemons() {
  for (auto it = started_.rbegin(); it != started_.rend(); ++it) ::kill(it->second, SIGTERM);
  for (auto it = started_.rbegin(); it != started_.rend(); ++it) stopAndReap(it->second);
}

void TestDaemons::stop(const std::string& name) {
  for (auto it = started_.begin(); it != started_.end(); ++it)
    if (it->first == name) {
      ::kill(it->second, SIGTERM);
      stopAndReap(it->second);
      started_.erase(it);
      return;
    }
}

int TestDaemons::waitForExit(const std::string& name, double seconds) {
  for (auto it = started_.begin(); it != started_.end(); ++it)
    if (it->first == name) {
      int status = 0;
      if (!waitFor([&] { return ::waitpid(it->second, &status, WNOHANG) == it->second; }, seconds)) return -1;
      started_.erase(it);
      return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
  return -1;
}

// Waits for `pid`, already sent SIGTERM; SIGKILL after 10 s.
void TestDaemons::stopAndReap(pid_t pid) {
  const auto deadline = Clock::now() + std::chrono::seconds(10);
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (Clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

bool TestDaemons::start(const std::string& name, const std::vector<std::string>& argv, const std::filesystem::path& log,
                        const std::vector<std::string>& environment) {
  std::vector<std::string> variables = environment;
  for (char** e = environ; *e != nullptr; ++e) {
    const char* equals = std::strchr(*e, '=');
    const std::string key(*e, equals ? static_cast<size_t>(equals - *e) : std::strlen(*e));
    bool overridden = false;
    for (const std::string& v : environment) overridden = overridden || v.rfind(key + "=", 0) == 0;
    if (!overridden) variables.emplace_back(*e);
  }
  std::vector<char*> args, env;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  for (const std::string& v : variables) env.push_back(const_cast<char*>(v.c_str()));
  args.push_back(nullptr);
  env.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t child = 0;
  const bool started = ::posix_spawn(&child, args[0], &actions, nullptr, args.data(), env.data()) == 0;
  posix_spawn_file_actions_destroy(&actions);
  if (started) started_.emplace_back(name, child);
  return started;
}

pid_t TestDaemons::pid(const std::string& name) const {
  for (const auto& [n, p] : started_)
    if (n == name) return p;
  return 0;
}

bool TestDaemons::waitFor(const std::function<bool()>& ready, double seconds) {
  const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < deadline) {
    if (ready()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return ready();
}

int TestDaemons::freePort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address);
  socklen_t length = sizeof address;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length);
  ::close(fd);
  return ntohs(address.sin_port);
}

}  // namespace omnicam::testing
