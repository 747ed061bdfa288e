#include "job_folder.h"

#include <cstdlib>
#include <filesystem>

#include "errors.h"

namespace omnicam {

namespace fs = std::filesystem;

JobFolder::JobFolder(const std::string& prefix, bool keep) : keep_(keep) {
  std::string pattern = (fs::temp_directory_path() / (prefix + "-XXXXXX")).string();
  if (!::mkdtemp(pattern.data()))
    throw ExternalError(prefix + ": cannot create a job folder in " + fs::temp_directory_path().string());
  path_ = pattern;
}

JobFolder::~JobFolder() {
  std::error_code ignored;
  if (!keep_) fs::remove_all(path_, ignored);
}

}  // namespace omnicam
