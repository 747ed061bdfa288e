#pragma once
// omnicam's executables start each other (the launcher the CLI, the CLI the ROS node): always the
// one in the starting program's own folder, wherever it was started from and whatever PATH says.
#include <string>

namespace omnicam {

// `name` in the folder of this process's executable (/proc/self/exe); `name` alone if that
// cannot be read.
std::string siblingProgram(const std::string& name);

// Replaces this process with sibling `name` (same pid, signals and exit code), passing `argv`.
// Returns only if it could not: "cannot start PATH: why".
std::string execSibling(const std::string& name, char** argv);

}  // namespace omnicam
