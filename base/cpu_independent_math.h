#pragma once
// Process-wide: math whose results do not depend on the CPU. glibc's libm takes, per CPU, a
// build of exp, log, pow, sin, cos, tan, atan, atan2, asin, acos (and others) made with fused
// multiply-adds, or a plain one; the two differ in the last bit of about one result in 1500
// (docs/conventions.md, "Reproducible pixels"). glibc picks once, when a program starts, from the
// tunable glibc.cpu.hwcaps; with FMA and FMA4 masked it takes the plain builds, whose results are
// the same on every x86-64 (its SSE2 and AVX builds agree bit for bit).
#include <string>

namespace omnicam {

// The tunable omnicam starts its processes with, and the GLIBC_TUNABLES value that adds it to
// `current` (the environment's value, or null). Empty if `current` already sets
// glibc.cpu.hwcaps: then the user's choice holds.
inline constexpr const char* kPlainMathTunable = "glibc.cpu.hwcaps=-FMA,-FMA4";
std::string tunablesForPlainMath(const char* current);

// Called first thing in main: if GLIBC_TUNABLES lacks the tunable, the program starts itself
// again (execv of /proc/self/exe, same arguments) with it added, since glibc reads it only at
// start. Returns if nothing needs doing; if the restart fails, after a warning on stderr.
void restartWithPlainMath(char** argv);

}  // namespace omnicam
