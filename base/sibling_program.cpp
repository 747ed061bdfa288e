#include "sibling_program.h"

#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>

namespace omnicam {

std::string siblingProgram(const std::string& name) {
  char self[PATH_MAX];
  const ssize_t length = ::readlink("/proc/self/exe", self, sizeof self - 1);
  if (length <= 0) return name;
  const std::string path(self, static_cast<size_t>(length));
  return path.substr(0, path.rfind('/') + 1) + name;
}

std::string execSibling(const std::string& name, char** argv) {
  const std::string program = siblingProgram(name);
  ::execv(program.c_str(), argv);
  return "cannot start " + program + ": " + std::strerror(errno) + " (build it with `make build`)";
}

}  // namespace omnicam
