#pragma once
// A private, freshly created folder for one external render job (under the system temp folder),
// removed when done unless kept for debugging. External renderers get it as cwd and HOME.
// It records its owner's pid (owner.pid), so folders of killed runs are recognised and removed
// by the next run instead of piling up in /tmp.
#include <optional>
#include <string>
#include <sys/types.h>

#include "interrupts.h"

namespace omnicam {

// Removes <tmp>/<prefix>-XXXXXX folders of this user whose owner process has exited; returns
// how many. Folders of running processes, of other users or without owner.pid are left alone.
int removeStaleJobFolders(const std::string& prefix);

class JobFolder {
 public:
  JobFolder(const std::string& prefix, bool keep);
  ~JobFolder();
  JobFolder(const JobFolder&) = delete;
  JobFolder& operator=(const JobFolder&) = delete;
  const std::string& path() const { return path_; }

 private:
  // A signal received while the folder exists is acted on by whoever waits on the job, after the
  // folder is gone (base/interrupts.h); declared first, so it outlives the folder.
  DeferInterrupts deferred_;
  std::string path_;
  bool keep_;
};

}  // namespace omnicam
