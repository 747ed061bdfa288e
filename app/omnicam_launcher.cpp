// build/bin/omnicam: starts omnicam-cli, beside it, with CPU-independent math in its environment
// (base/cpu_independent_math.h). glibc reads that setting only when a program starts, so the CLI
// would otherwise start itself a second time and load its ~280 shared libraries twice: about
// half of what a short command costs (docs/performance.md, "What an omnicam command pays"). The
// launcher links none of them. The CLI still restarts itself when started some other way.
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "cpu_independent_math.h"

namespace {

// The CLI's path: omnicam-cli in this program's own folder, wherever it was started from.
std::string cliBesideThisProgram() {
  char self[PATH_MAX];
  const ssize_t length = ::readlink("/proc/self/exe", self, sizeof self - 1);
  if (length <= 0) return "omnicam-cli";
  const std::string path(self, static_cast<size_t>(length));
  return path.substr(0, path.rfind('/') + 1) + "omnicam-cli";
}

}  // namespace

int main(int, char** argv) {
  const std::string tunables = omnicam::tunablesForPlainMath(std::getenv("GLIBC_TUNABLES"));
  if (!tunables.empty()) ::setenv("GLIBC_TUNABLES", tunables.c_str(), 1);
  const std::string cli = cliBesideThisProgram();
  ::execv(cli.c_str(), argv);  // the same process: its pid, signals and exit code are the CLI's
  std::fprintf(stderr, "omnicam: cannot start %s: %s (build it with `make build`)\n", cli.c_str(), std::strerror(errno));
  return 2;
}
