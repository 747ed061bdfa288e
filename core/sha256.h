#pragma once
#include <string>

namespace omnicam {
// Lower-case hex SHA-256 of a file's bytes; throws InputError if it cannot be read.
std::string sha256OfFile(const std::string& path);
}  // namespace omnicam
