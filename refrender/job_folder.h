#pragma once
// A private, freshly created folder for one external render job (under the system temp folder),
// removed when done unless kept for debugging. External renderers get it as cwd and HOME.
#include <string>

namespace omnicam {

class JobFolder {
 public:
  JobFolder(const std::string& prefix, bool keep);
  ~JobFolder();
  JobFolder(const JobFolder&) = delete;
  JobFolder& operator=(const JobFolder&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  bool keep_;
};

}  // namespace omnicam
