#include "file_confinement.h"

#include <cerrno>
#include <cstring>
#include <fstream>

#include "errors.h"
#include "input_limits.h"

namespace omnicam {

namespace fs = std::filesystem;

std::string withOutsideFilesHint(const std::string& message, std::string_view howToAllow) {
  if (message.find(kOutsideFolderWords) == std::string::npos) return message;
  return message + " (" + std::string(howToAllow) + ")";
}

bool isInsideFolder(const fs::path& folder, const fs::path& path) {
  std::error_code ec;
  const fs::path root = fs::weakly_canonical(folder, ec);
  if (ec) return false;
  const fs::path resolved = fs::weakly_canonical(path, ec);
  if (ec) return false;
  const fs::path rel = resolved.lexically_relative(root);
  if (rel.empty() || *rel.begin() == ".." || rel == ".") return false;
  // weakly_canonical resolves every link that leads somewhere; one left on the way is dangling,
  // and counts as outside: whether a file outside exists is not told by "not found".
  fs::path walked = root;
  for (const fs::path& part : rel) {
    walked /= part;
    if (fs::is_symlink(fs::symlink_status(walked, ec))) return false;
  }
  return true;
}

std::optional<fs::path> resolveConfined(const fs::path& folder, const std::string& name, bool allowOutside,
                                        std::string& why) {
  if (name.empty() || name.find('\0') != std::string::npos) {
    why = "file name is empty or holds a NUL byte";
    return std::nullopt;
  }
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(folder / name, ec);  // follows every symlink
  if (ec) {
    why = "cannot resolve " + quote(name) + " (" + ec.message() + ")";
    return std::nullopt;
  }
  // Confinement first: what lies outside is not even told apart (folder, file or nothing).
  if (!allowOutside && !isInsideFolder(folder, resolved)) {
    why = resolved == fs::weakly_canonical(folder, ec) ? quote(name) + " is the scene's folder, not a file"
                                                       : quote(name) + " " + std::string(kOutsideFolderWords);
    return std::nullopt;
  }
  if (fs::is_directory(resolved, ec)) {
    why = quote(name) + " is a folder, not a file";
    return std::nullopt;
  }
  if (!fs::is_regular_file(resolved, ec)) {
    why = fs::exists(resolved, ec) ? quote(name) + " is not a regular file" : "file not found: " + showPath(name);
    return std::nullopt;
  }
  return resolved;
}

std::optional<std::string> readWholeFile(const std::string& path, std::string& why, int64_t maxBytes) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    why = fs::is_directory(path, ec) ? "a folder, not a file" : fs::exists(path, ec) ? "not a regular file" : "no such file";
    return std::nullopt;
  }
  const auto size = fs::file_size(path, ec);
  if (ec || size > static_cast<uintmax_t>(maxBytes)) {
    why = ec ? ec.message() : "larger than the " + std::to_string(maxBytes >> 20) + " MiB limit";
    return std::nullopt;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    why = std::strerror(errno);
    return std::nullopt;
  }
  std::string bytes(static_cast<size_t>(size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  bytes.resize(static_cast<size_t>(in.gcount()));
  return bytes;
}

}  // namespace omnicam
