// build/bin/omnicam: starts omnicam-cli (omnicam-ros for `omnicam ros`), beside it, with
// CPU-independent math in its environment
// (base/cpu_independent_math.h). glibc reads that setting only when a program starts, so the CLI
// would otherwise start itself a second time and load its ~280 shared libraries twice: about
// half of what a short command costs (docs/performance.md, "What an omnicam command pays"). The
// launcher links none of them. The CLI still restarts itself when started some other way.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "cpu_independent_math.h"
#include "sibling_program.h"

int main(int argc, char** argv) {
  const std::string tunables = omnicam::tunablesForPlainMath(std::getenv("GLIBC_TUNABLES"));
  if (!tunables.empty()) ::setenv("GLIBC_TUNABLES", tunables.c_str(), 1);
  // `omnicam ros` is its own executable, the one that links ROS: the other verbs load none of it.
  const bool ros = argc > 1 && std::strcmp(argv[1], "ros") == 0;
  // The same process: its pid, signals and exit code are the program's.
  const std::string why = omnicam::execSibling(ros ? "omnicam-ros" : "omnicam-cli", argv);
  std::fprintf(stderr, "omnicam: %s\n", why.c_str());
  return 2;
}
