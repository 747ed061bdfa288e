#include "dataset_shards.h"

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <set>

#include "atomic_file.h"
#include "annotation_files.h"
#include "calibration_bag.h"
#include "dataset_folder.h"
#include "errors.h"
#include "manifest.h"
#include "number_format.h"
#include "markup.h"
#include "safe_files.h"

namespace omnicam {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

void checkShardCount(int count) {
  if (count < 1 || count > kMaxShards)
    throw InputError("shard count " + std::to_string(count) + ": must be in [1, " + std::to_string(kMaxShards) + "]");
}

bool hasShardManifest(const SafeFolder& dir, const std::string& name) { return dir.entry(name) != EntryKind::Missing; }

// Shard `index` of `count`'s manifest, and its frame range: the manifest reader checked the
// range's fields; this checks that the file is the shard its name says (a plain manifest or
// another shard's copied there is not).
struct ShardManifest {
  DatasetManifest manifest;
  int first = 0, end = 0;
};

ShardManifest readShardManifest(const SafeFolder& dir, int index, int count) {
  const std::string name = shardManifestName(index, count);
  ShardManifest shard{readDatasetManifest(dir, name)};
  const json range = shard.manifest.header.value("shard", json());
  if (!range.is_object() || range.at("index") != index || range.at("count") != count)
    throw InputError(showPath(dir.path() + "/" + name) + ": shard: must say shard " + std::to_string(index) + " of " +
                     std::to_string(count) + " (the file is not that shard's manifest)");
  shard.first = range.at("first_frame").get<int>();
  shard.end = range.at("end_frame").get<int>();
  // The range is the formula's, not the file's to choose: a forged one would hand a shard's
  // frames to another, or call an empty shard complete.
  const ShardFrames frames = shardFrames(shard.manifest.header.value("frame_count", 0), index, count);
  if (shard.first != frames.first || shard.end != frames.end)
    throw InputError(showPath(dir.path() + "/" + name) + ": shard: frames [" + std::to_string(shard.first) + ", " +
                     std::to_string(shard.end) + ") are not shard " + std::to_string(index) + " of " + std::to_string(count) +
                     "'s, [" + std::to_string(frames.first) + ", " + std::to_string(frames.end) + ")");
  return shard;
}

// The names runs of the folder's shards hold: the folder by its device and inode (one folder,
// however it is reached), then each shard by index and count. "" for a folder that is not there.
std::string shardNamesPrefix(const std::string& dir) {
  struct stat folder {};
  if (::stat(dir.c_str(), &folder) != 0 || !S_ISDIR(folder.st_mode)) return "";
  return "omnicam/dataset-shard/" + std::to_string(static_cast<unsigned long long>(folder.st_dev)) + ":" +
         std::to_string(static_cast<unsigned long long>(folder.st_ino)) + "/";
}

std::string shardName(const std::string& prefix, int index, int count) {
  return prefix + std::to_string(index) + "-of-" + std::to_string(count);
}

}  // namespace

std::optional<HeldName> holdShard(const std::string& dir, int index, int count) {
  const std::string prefix = shardNamesPrefix(dir);
  if (prefix.empty()) throw InputError(showPath(dir) + ": no such folder");
  return HeldName::tryHold(shardName(prefix, index, count));
}

std::vector<ShardState> shardStates(const std::string& path, int count, bool checkFiles) {
  checkShardCount(count);
  const SafeFolder dir(path);  // opened once for every shard's manifest
  const std::string prefix = shardNamesPrefix(path);
  const std::set<std::string> running = prefix.empty() ? std::set<std::string>() : heldNames(prefix);
  std::vector<ShardState> states;
  for (int i = 0; i < count; ++i) {
    ShardState s;
    s.index = i;
    s.running = !prefix.empty() && running.count(shardName(prefix, i, count));
    const std::string name = shardManifestName(i, count);
    if (hasShardManifest(dir, name)) {
      const ShardManifest shard = readShardManifest(dir, i, count);
      const DatasetManifest& m = shard.manifest;
      s.started = true;
      s.frames = shard.end - shard.first;
      s.finished = static_cast<int>(m.frames.size());
      s.complete = m.header.value("complete", false) && s.finished == s.frames;
      if (s.complete && checkFiles) {
        s.problems = verifyDataset(path, name).problems;
        s.complete = s.problems.empty();
      }
    }
    states.push_back(s);
  }
  return states;
}

std::vector<int> shardCountsIn(const std::string& dir) {
  std::set<int> counts;
  const std::regex name(R"(shard-\d+-of-([1-9]\d{0,5})\.json)");
  if (entryInside(dir, "shards") != EntryKind::Folder) return {};  // never listed through a link
  std::error_code ec;
  for (auto it = fs::directory_iterator(fs::path(dir) / "shards", ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
    std::smatch m;
    const std::string file = it->path().filename().string();
    if (std::regex_match(file, m, name) && std::stoi(m[1]) <= kMaxShards) counts.insert(std::stoi(m[1]));
  }
  return {counts.begin(), counts.end()};
}

void removeShardManifestsOf(const SafeFolder& dir, const json& header) {
  if (dir.entry("shards") != EntryKind::Folder) return;  // never listed through a link
  const std::regex name(R"(shard-\d+-of-[1-9]\d{0,5}\.json)");
  std::vector<std::string> names;
  std::error_code ec;
  for (auto it = fs::directory_iterator(fs::path(dir.path()) / "shards", ec); !ec && it != fs::directory_iterator(); it.increment(ec))
    if (const std::string file = it->path().filename().string(); std::regex_match(file, name)) names.push_back("shards/" + file);
  for (const std::string& shard : names) {
    try {
      if (identityDifference(readDatasetManifest(dir, shard).header, header).empty()) dir.removeFile(shard);
    } catch (const InputError&) {  // not one of its manifests: not omnicam's to remove
    }
  }
  dir.removeEmptyFolder("shards");
}

DatasetManifest readMergedDatasetManifest(const SafeFolder& dir) {
  if (dir.entry(kManifestName) == EntryKind::Missing && !shardCountsIn(dir.path()).empty())
    throw InputError(showPath(dir.path()) + ": shards not merged yet: no " + kManifestName + " (" + unmergedShardsNextStep(dir.path()) + ")");
  return readDatasetManifest(dir);
}

std::string unmergedShardsNextStep(const std::string& path) {
  const std::vector<int> counts = shardCountsIn(path);
  // Submitted to Slurm (docs/cluster.md): its merge job merges, and a resubmission renders what
  // is left; the by-hand steps are the fallback.
  const bool submitted = entryInside(path, "slurm/render.sbatch") == EntryKind::File;
  int running = 0;
  for (int count : counts) {
    const std::vector<ShardState> states = shardStates(path, count, false);
    if (std::all_of(states.begin(), states.end(), [](const ShardState& s) { return s.complete; }))
      return "every shard of " + std::to_string(count) + " is finished: " +
             (submitted ? "the Slurm merge job merges them once the array has ended (by hand: " : "merge them with ") +
             "omnicam dataset --merge " + shellPath(path) + (submitted ? ")" : "");
    running += static_cast<int>(std::count_if(states.begin(), states.end(), [](const ShardState& s) { return s.running; }));
  }
  const std::string status = "omnicam dataset --status " + shellPath(path) + " lists them";
  const std::string rest =
      submitted ? "once the Slurm array has ended, submit the same command again to render the shards not yet finished (" + status +
                      "; slurm/render.sbatch says how it was submitted)"
                : "run the shards not yet finished (--shard I/" + (counts.size() == 1 ? std::to_string(counts.front()) : "N") + "; " +
                      status + "), then omnicam dataset --merge " + shellPath(path);
  if (running)
    return countOf(running, "shard") + (running == 1 ? " is" : " are") + " being rendered now on this machine: wait for " +
           (running == 1 ? "it" : "them") + ", and " + rest;
  return rest;
}

std::string shardCountConflict(const std::string& path, int count) {
  for (int other : shardCountsIn(path))
    if (other != count)
      return "holds the shards of a run in " + std::to_string(other) + " (shards/shard-*-of-" + std::to_string(other) +
             ".json): shard it the same way, or give another folder";
  return "";
}

std::string shardsConflict(const std::string& path, const json& header, int count) {
  if (const std::string conflict = shardCountConflict(path, count); !conflict.empty()) return conflict;
  if (shardCountsIn(path).empty()) return "";
  // Each shard there was checked against those before it when it started: one stands for all.
  const SafeFolder dir(path);
  for (int i = 0; i < count; ++i) {
    const std::string name = shardManifestName(i, count);
    if (!hasShardManifest(dir, name)) continue;
    const std::string difference = identityDifference(readShardManifest(dir, i, count).manifest.header, header);
    return difference.empty() ? "" : "holds the shards of another dataset (" + name + ": " + difference + "): give another folder";
  }
  return "";
}

MergeResult mergeDatasetShards(const std::string& path, int count) {
  checkShardCount(count);
  const SafeFolder dir(path);  // opened once: every shard's manifest read, the merged one written
  std::optional<DatasetManifest> merged;
  MergeResult result;
  std::vector<ShardFrames> startedRanges;
  for (int i = 0; i < count; ++i) {
    const std::string name = shardManifestName(i, count);
    if (!hasShardManifest(dir, name)) {
      result.incompleteShards.push_back(i);
      continue;
    }
    const ShardManifest read = readShardManifest(dir, i, count);
    const DatasetManifest& shard = read.manifest;
    ++result.started;
    if (!merged) {
      merged = DatasetManifest{shard.header, {}};
      merged->header.erase("shard");
    } else if (const std::string difference = identityDifference(merged->header, shard.header); !difference.empty()) {
      // Said of this shard (identityDifference's later one): "the scene now reads" what it read.
      throw InputError(showPath(path + "/" + name) + ": from another dataset than the other shards (" + difference + ")");
    } else if (shard.header.value("frame_count", 0) != merged->header.value("frame_count", 0)) {
      // Each shard's range follows from its frame count: one count for all, or a forged one
      // would shrink a shard's range to what it holds.
      throw InputError(showPath(path + "/" + name) + ": frame_count: " + std::to_string(shard.header.value("frame_count", 0)) +
                       ", where the other shards say " + std::to_string(merged->header.value("frame_count", 0)));
    }
    const int first = read.first, end = read.end;
    startedRanges.push_back({first, end});
    int finished = 0;
    for (const auto& [index, frame] : shard.frames)
      if (index >= first && index < end) merged->frames[index] = frame, ++finished;
    if (!shard.header.value("complete", false) || finished != end - first) result.incompleteShards.push_back(i);
  }
  if (!merged) throw InputError(showPath(path) + ": no shard of " + std::to_string(count) + " has started (no shards/shard-*-of-" +
                                std::to_string(count) + ".json)");
  if (dir.entry(kManifestName) != EntryKind::Missing) {
    const DatasetManifest existing = readDatasetManifest(dir);
    if (const std::string difference = identityDifference(existing.header, merged->header); !difference.empty())
      throw InputError(showPath(path) + ": its " + std::string(kManifestName) + " is from another dataset than the shards (" +
                       difference + ")");
    if (existing.header.value("frame_count", 0) != merged->header.value("frame_count", 0))
      throw InputError(showPath(path) + ": its " + std::string(kManifestName) + " counts " +
                       std::to_string(existing.header.value("frame_count", 0)) + " frames, the shards " +
                       std::to_string(merged->header.value("frame_count", 0)));
    // Frames an earlier merge (or an unsharded run, which resumes a merged folder) finished stay
    // listed. In a started shard's range, a frame its manifest does not list stays only while its
    // files still hash to the record: a rerun shard drops a frame whose file it found damaged (or
    // a ground truth renders it again, other bytes), and the old record must not vouch for it.
    const auto inStartedShard = [&](int index) {
      return std::any_of(startedRanges.begin(), startedRanges.end(), [index](const ShardFrames& r) { return index >= r.first && index < r.end; });
    };
    const auto filesIntact = [&](const FrameRecord& frame) {
      for (const auto& [camera, cameraFrame] : frame.cameras)
        for (const auto& [kind, file] : cameraFrame.files)
          if (!stillAsRecorded(dir, file)) return false;
      return true;
    };
    for (const auto& [index, frame] : existing.frames)
      if (!merged->frames.count(index) && (!inStartedShard(index) || filesIntact(frame))) merged->frames.emplace(index, frame);
  }
  result.frames = merged->header.value("frame_count", 0);
  result.finished = static_cast<int>(merged->frames.size());
  merged->header["complete"] = result.finished == result.frames;
  if (result.finished == result.frames) {
    result.incompleteShards.clear();
    writeAnnotationFiles(dir, *merged);
    writeCalibrationBag(dir, *merged);
  }
  writeManifest(dir, *merged);
  // What killed shards left behind goes, from the folders of the files the dataset lists, shards/
  // and slurm/ — once no shard is at work (each holds a shared claim): a running one's temporaries
  // stay, and a later merge removes what is left then.
  if (dir.tryClaim(/*shared=*/false)) {
    std::set<std::string> folders{"shards", "slurm"};
    for (const FileRecord& file : manifestFiles(*merged)) folders.insert(std::filesystem::path(file.path).parent_path().generic_string());
    removeAtomicTemporaries(path, withParentFolders(folders));
  }
  return result;
}

}  // namespace omnicam
