#pragma once
// What the end-to-end tests share: running a shell command line and capturing what it prints,
// reading a file whole, and the one-line rule for messages (docs/robustness.md).
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
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

// The whole file as bytes ("" if it cannot be read).
inline std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// Exactly one line: one newline, at the end, and no other control character (a \r or a terminal
// escape sequence echoed from the input garbles the line as surely as a newline splits it).
inline bool isOneLine(const std::string& out) {
  if (out.empty() || out.back() != '\n') return false;
  return std::none_of(out.begin(), out.end() - 1, [](char ch) {
    const auto byte = static_cast<unsigned char>(ch);
    return byte < 0x20 || byte == 0x7F;
  });
}

}  // namespace omnicam::testing
