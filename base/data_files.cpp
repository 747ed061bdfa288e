#include "data_files.h"

#include <dlfcn.h>
#include <link.h>

#include <stdexcept>

#include "errors.h"

namespace omnicam {

namespace fs = std::filesystem;

#ifdef OMNICAM_PACKAGE_DATA
namespace {

// The folder of the binary this function is linked into: the Python extension
// (`omnicam/_omnicam*.so`) or the CLI (`omnicam/bin/omnicam-cli`). The loader names a shared
// object by the path it opened; the program itself has no name there, hence /proc/self/exe.
fs::path folderOfThisBinary() {
  Dl_info info{};
  link_map* map = nullptr;
  if (::dladdr1(reinterpret_cast<const void*>(&folderOfThisBinary), &info, reinterpret_cast<void**>(&map),
                RTLD_DL_LINKMAP) == 0 || map == nullptr)
    return {};
  const fs::path binary = map->l_name[0] != '\0' ? fs::path(map->l_name) : fs::path("/proc/self/exe");
  std::error_code ec;
  const fs::path resolved = fs::canonical(binary, ec);
  return ec ? fs::path() : resolved.parent_path();
}

}  // namespace

// The package's `data/` folder: beside the extension, one level up from `bin/`. Never a folder
// relative to the working directory.
fs::path dataRoot() {
  static const fs::path root = [] {
    const fs::path here = folderOfThisBinary();
    if (here.empty()) throw std::runtime_error("cannot locate the folder of omnicam's binary, hence its data files");
    return (here.filename() == "bin" ? here.parent_path() : here) / OMNICAM_PACKAGE_DATA;
  }();
  return root;
}
#else
fs::path dataRoot() { return OMNICAM_SOURCE_ROOT; }
#endif

fs::path dataFile(std::string_view relative) { return dataRoot() / fs::path(relative); }

std::string bundledFileHint(const std::string& name, std::string_view folder) {
  std::error_code ec;
  const fs::path given(name);
  if (!given.has_filename() || given.is_absolute() || *given.lexically_normal().begin() == ".." || fs::exists(given, ec)) return "";
  try {
    const fs::path bundled = given.has_parent_path() ? dataFile(given.lexically_normal().string()) : dataFile(folder) / given;
    if (fs::is_regular_file(bundled, ec)) return "; omnicam comes with " + showPath(bundled.string());
  } catch (const std::runtime_error&) {  // no data root to look in: no hint
  }
  return "";
}

}  // namespace omnicam
