#pragma once
// Reading a dataset folder someone else may have written: its manifest (reached without
// following a link), its status and a full re-hash (`dataset --status`, `--verify`). Nothing
// here renders, so the fuzz build links it as it is (fuzz/CMakeLists.txt).
#include <cstdint>
#include <string>
#include <vector>

#include "manifest.h"

namespace omnicam {

// The largest file omnicam reads or hashes in a dataset folder: above the largest frame it
// writes (a 16384² RGBA float EXR, 4 GiB uncompressed), so a planted multi-gigabyte file is
// refused by its size instead of read.
inline constexpr int64_t kMaxDatasetFileBytes = int64_t{5} << 30;
// Whether `file` is still in `dir` as its record says: a regular file (no link followed) whose
// SHA-256 is the record's.
bool stillAsRecorded(const SafeFolder& dir, const FileRecord& file);

// Frames planned by the spec and how many the folder's manifest has finished (`dataset --status`).
struct DatasetStatus {
  int frames = 0, finished = 0;
  bool complete = false;
};
DatasetStatus datasetStatus(const std::string& dir);

// Whether a whole-dataset run holds DIR now (its exclusive claim, dataset_runner.cpp), as the
// kernel lists it in /proc/locks; shards running together hold shared claims and do not show.
bool wholeDatasetRunWriting(const std::string& dir);

struct DatasetVerifyResult {
  int files = 0;  // checked
  // One line each: missing, changed, a link or not a regular file (never followed or read),
  // incomplete.
  std::vector<std::string> problems;
  bool ok() const { return problems.empty(); }
};
// DIR/manifest.json (or DIR/`name`: a shard's manifest), read strictly (manifestFromText) as a
// regular file reached without following a link, at most kMaxManifestBytes.
DatasetManifest readDatasetManifest(const SafeFolder& dir, const std::string& name = kManifestName);
DatasetManifest readDatasetManifest(const std::string& dir, const std::string& name = kManifestName);

// Re-hashes every file the manifest (or the shard manifest `manifestName`) lists. InputError if
// DIR has no readable manifest.
DatasetVerifyResult verifyDataset(const std::string& dir, const std::string& manifestName = "manifest.json");

}  // namespace omnicam
