#pragma once
// What a folder holds, to prove a command left it as it was: every entry under it by its relative
// path — a file's bytes, a link's target (never followed), "" for a folder.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

namespace omnicam::test_support {

inline std::map<std::string, std::string> folderSnapshot(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::map<std::string, std::string> entries;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const std::string name = fs::relative(entry.path(), dir).string();
    if (entry.is_symlink()) {
      entries[name] = "-> " + fs::read_symlink(entry.path()).string();
    } else if (entry.is_regular_file()) {
      std::ifstream in(entry.path(), std::ios::binary);
      entries[name] = std::string(std::istreambuf_iterator<char>(in), {});
    } else {
      entries[name] = "";
    }
  }
  return entries;
}

}  // namespace omnicam::test_support
