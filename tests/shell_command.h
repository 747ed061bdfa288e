#pragma once
// Runs a shell command line and captures what it prints (the end-to-end tests' one runner).
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace omnicam::testing {

struct CommandResult {
  int code;         // exit status, -1 if the command did not exit normally
  std::string out;  // its standard output (add "2>&1" to the command for stderr too)
};

inline CommandResult runShell(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  std::array<char, 4096> buf;
  while (size_t n = fread(buf.data(), 1, buf.size(), pipe)) out.append(buf.data(), n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

}  // namespace omnicam::testing
