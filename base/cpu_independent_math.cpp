#include "cpu_independent_math.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace omnicam {

std::string tunablesForPlainMath(const char* current) {
  const std::string tunables = current ? current : "";
  if (tunables.find("glibc.cpu.hwcaps=") != std::string::npos) return "";
  return tunables.empty() ? kPlainMathTunable : tunables + ":" + kPlainMathTunable;
}

void restartWithPlainMath(char** argv) {
  const std::string tunables = tunablesForPlainMath(std::getenv("GLIBC_TUNABLES"));
  if (tunables.empty()) return;
  if (::setenv("GLIBC_TUNABLES", tunables.c_str(), 1) == 0) ::execv("/proc/self/exe", argv);
  std::fprintf(stderr, "omnicam: warning: cannot restart with CPU-independent math (%s): pixels may differ in the last bit from other machines' (docs/conventions.md)\n",
               std::strerror(errno));
}

}  // namespace omnicam
