#include "dataset_folder.h"

#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <limits>

#include "errors.h"
#include "safe_files.h"

namespace omnicam {

using nlohmann::json;

DatasetStatus datasetStatus(const std::string& dir) {
  const DatasetManifest manifest = readDatasetManifest(dir);
  DatasetStatus status;
  status.frames = manifest.header.value("frame_count", 0);
  status.finished = static_cast<int>(manifest.frames.size());
  status.complete = manifest.header.value("complete", false) && status.finished == status.frames;
  return status;
}

DatasetManifest readDatasetManifest(const SafeFolder& dir, const std::string& name) {
  // Missing: not a dataset folder. Otherwise read through the folder's descriptor, no link
  // followed, at most the manifest's size limit.
  if (dir.entry(name) == EntryKind::Missing) {
    std::error_code ec;
    if (!std::filesystem::exists(dir.path(), ec)) throw InputError(showPath(dir.path()) + ": no such folder");
    throw InputError(showPath(dir.path()) + ": not a dataset folder (no " + name + ")");
  }
  return manifestFromText(dir.readFile(name, kMaxManifestBytes), (std::filesystem::path(dir.path()) / name).string());
}

DatasetManifest readDatasetManifest(const std::string& dir, const std::string& name) {
  return readDatasetManifest(SafeFolder(dir), name);
}

bool wholeDatasetRunWriting(const std::string& dir) {
  // Read from the kernel's table of locks, not probed with a claim of our own: a probe would, for
  // an instant, make a run starting then find the folder taken.
  struct stat folder {};
  if (::lstat(dir.c_str(), &folder) != 0 || !S_ISDIR(folder.st_mode)) return false;
  char device[32];
  std::snprintf(device, sizeof device, "%02x:%02x:", major(folder.st_dev), minor(folder.st_dev));
  const std::string held = device + std::to_string(folder.st_ino);
  std::ifstream locks("/proc/locks");
  for (std::string line; std::getline(locks, line);) {
    if (line.find("->") != std::string::npos) continue;  // a process waiting for the lock, not holding it
    std::istringstream words(line);
    std::string number, kind, mode, access, pid, where;
    words >> number >> kind >> mode >> access >> pid >> where;
    if (kind == "FLOCK" && access == "WRITE" && where == held) return true;
  }
  return false;
}

bool stillAsRecorded(const SafeFolder& dir, const FileRecord& file) {
  const FileDigest digest = dir.sha256(file.path, kMaxDatasetFileBytes);
  return digest.ok() && digest.sha256 == file.sha256;
}

DatasetVerifyResult verifyDataset(const std::string& path, const std::string& manifestName) {
  const SafeFolder dir(path);
  const DatasetManifest manifest = readDatasetManifest(dir, manifestName);
  DatasetVerifyResult result;
  for (const FileRecord& file : manifestFiles(manifest)) {
    ++result.files;
    const FileDigest digest = dir.sha256(file.path, kMaxDatasetFileBytes);
    if (!digest.ok())
      result.problems.push_back(showPath(file.path) + ": " + digest.problem);
    else if (digest.sha256 != file.sha256)
      result.problems.push_back(showPath(file.path) + ": SHA-256 " + digest.sha256 + " differs from the manifest's " + file.sha256);
  }
  // A shard is complete with its own range of frames.
  const json shard = manifest.header.value("shard", json());
  const int wanted = shard.is_object() ? shard.at("end_frame").get<int>() - shard.at("first_frame").get<int>()
                                       : manifest.header.value("frame_count", 0);
  if (static_cast<int>(manifest.frames.size()) != wanted || !manifest.header.value("complete", false))
    result.problems.push_back(manifestName + ": incomplete: " + std::to_string(manifest.frames.size()) + " of " +
                              std::to_string(wanted) + " frames finished (" +
                              (wholeDatasetRunWriting(path) ? "a run is writing it now: wait for it to end"
                                                            : "run the same command again to resume") + ")");
  return result;
}

}  // namespace omnicam
