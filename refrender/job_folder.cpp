#include "job_folder.h"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "atomic_file.h"
#include "errors.h"

namespace omnicam {

namespace fs = std::filesystem;

namespace {

constexpr const char* kOwnerFile = "owner.pid";

// Where a process id means something: this machine (a TMPDIR may be shared scratch) and its pid
// namespace (containers may share one /tmp). A folder of another place is never judged from here.
std::string processPlace() {
  char host[256] = {};
  if (::gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
  std::error_code ec;
  const std::string pidNamespace = fs::read_symlink("/proc/self/ns/pid", ec).string();
  return std::string(host) + " " + pidNamespace;
}

// The folder's owner process, if the folder is one of ours (same user, an owner.pid inside) and
// its owner ran here: "<pid>\n<host> <pid namespace>\n" (a pid alone: written before the place was).
std::optional<pid_t> ownerOf(const fs::path& folder) {
  struct stat info {};
  if (::lstat(folder.c_str(), &info) != 0 || !S_ISDIR(info.st_mode) || info.st_uid != ::getuid()) return std::nullopt;
  std::ifstream in(folder / kOwnerFile);
  long pid = 0;
  if (!(in >> pid) || pid <= 0) return std::nullopt;
  std::string place;
  in >> std::ws;
  if (std::getline(in, place) && place != processPlace()) return std::nullopt;
  return static_cast<pid_t>(pid);
}

}  // namespace

int removeStaleJobFolders(const std::string& prefix) {
  int removed = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(fs::temp_directory_path(), ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix + "-", 0) != 0 || name.size() != prefix.size() + 7) continue;
    const auto owner = ownerOf(entry.path());
    if (!owner || *owner == ::getpid()) continue;
    if (::kill(*owner, 0) == 0 || errno != ESRCH) continue;  // alive (or not ours to judge)
    std::error_code ignored;
    if (fs::remove_all(entry.path(), ignored) > 0) ++removed;
  }
  return removed;
}

JobFolder::JobFolder(const std::string& prefix, bool keep) : keep_(keep) {
  removeStaleJobFolders(prefix);  // left by runs that were killed before they could clean up
  std::string pattern = (fs::temp_directory_path() / (prefix + "-XXXXXX")).string();
  if (!::mkdtemp(pattern.data()))
    throw ExternalError(prefix + ": cannot create a job folder in " + showPath(fs::temp_directory_path().string()));
  path_ = pattern;
  try {
    writeTextAtomically((fs::path(path_) / kOwnerFile).string(), std::to_string(::getpid()) + "\n" + processPlace() + "\n");
  } catch (const std::exception& e) {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
    throw ExternalError(prefix + ": cannot prepare a job folder (" + e.what() + ")");
  }
}

JobFolder::~JobFolder() {
  std::error_code ignored;
  if (!keep_) fs::remove_all(path_, ignored);
}

}  // namespace omnicam
