#pragma once
#include <string>
#include <string_view>

namespace omnicam {
// Lower-case hex SHA-256 of a file's bytes; throws InputError if it cannot be read.
std::string sha256OfFile(const std::string& path);
std::string sha256OfBytes(std::string_view bytes);
}  // namespace omnicam
