#include "atomic_file.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "errors.h"

namespace omnicam {

namespace fs = std::filesystem;

void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  const fs::path target(path);
  const fs::path tmp = target.parent_path() /
                       ("." + target.stem().string() + ".tmp-" + std::to_string(::getpid()) +
                        target.extension().string());
  try {
    write(tmp.string());
    fs::rename(tmp, target);
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

void writeTextAtomically(const std::string& path, const std::string& text) {
  writeAtomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw InputError(path + ": cannot write file");
  });
}

}  // namespace omnicam
