#include "dataset_runner.h"

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <thread>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "annotation_files.h"
#include "atomic_file.h"
#include "calibration_bag.h"
#include "dataset_plan.h"
#include "dataset_shards.h"
#include "errors.h"
#include "frame_scheduler.h"
#include "manifest.h"
#include "markup.h"
#include "memory_budget.h"
#include "render_settings.h"
#include "safe_files.h"
#include "scene_loader.h"
#include "sha256.h"

namespace omnicam {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::set<std::string> cameraNames(const DatasetManifest& manifest) {
  std::set<std::string> names;
  for (const json& camera : manifest.header.at("cameras")) names.insert(camera.at("name").get<std::string>());
  return names;
}

// Overwriting: removes the files `old` lists in the dataset layout that still hold what it says
// was written (regular files with its SHA-256), then its camera folders that this leaves empty.
// Nothing else: a folder named like a camera may hold the user's own files, and a manifest is
// anyone's to edit, so a file it lists that omnicam did not write stays.
void removeDatasetFiles(const SafeFolder& dir, const DatasetManifest& old) {
  const std::set<std::string> cameras = cameraNames(old);
  for (const FileRecord& file : manifestFiles(old))
    if (isLayoutFile(file.path, cameras) && stillAsRecorded(dir, file))
      dir.removeFile(file.path);
  for (const std::string& camera : cameras) {
    for (const std::string& folder : cameraFolderNames()) dir.removeEmptyFolder(camera + "/" + folder);
    dir.removeEmptyFolder(camera);
  }
  removeShardManifestsOf(dir, old.header);
}

DatasetManifest readPreviousManifest(const std::string& dir, const std::string& name) {
  try {
    return readDatasetManifest(dir, name);
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) +
                     " (omnicam resumes or replaces a dataset only by its readable manifest; move the folder away to start afresh)");
  }
}

// What the folder holds before the run: nothing (new or empty), this dataset (resumed: its
// manifest), or something else — refused, except another dataset when overwriting (replaced: its
// files go once every check of the run has passed, so that a run refused removes nothing). A
// shard reads its own manifest, and the merged one if there is one.
struct FolderTakeover {
  std::optional<DatasetManifest> resumed;
  std::optional<DatasetManifest> replaced;
};
FolderTakeover takeOverFolder(const DatasetRunOptions& options, const json& header, const std::string& manifestName) {
  // The folder is one already (runDatasetHere opened it).
  std::error_code ec;
  if (!fs::exists(options.dir, ec) || fs::is_empty(options.dir, ec)) return {};
  const SafeFolder dir(options.dir);
  std::vector<std::string> names{kManifestName};
  if (manifestName != kManifestName) names.push_back(manifestName);
  std::optional<DatasetManifest> previous;
  for (const std::string& name : names) {
    if (dir.entry(name) == EntryKind::Missing) continue;
    previous = readPreviousManifest(options.dir, name);
    const std::string difference = identityDifference(previous->header, header);
    if (!difference.empty() && !options.overwrite)
      throw OtherDatasetError(showPath(options.dir) + ": holds another dataset (" + difference + ")");
  }
  // The shards of a dataset fill the folder: a shard of the same dataset and count joins them,
  // in a merged folder too (its shards/ stays).
  const bool shard = manifestName != kManifestName;
  if (shard && dir.entry("shards") == EntryKind::Folder)
    if (const std::string conflict = shardsConflict(options.dir, header, options.shardCount); !conflict.empty())
      throw InputError(showPath(options.dir) + ": " + conflict);
  if (!previous && dir.entry("shards") == EntryKind::Folder) {
    if (shard) return {};
    throw InputError(showPath(options.dir) + ": holds the shards of a dataset, not merged (shards/): " +
                     unmergedShardsNextStep(options.dir));
  }
  if (!previous) {
    throw InputError(showPath(options.dir) + ": folder is not empty and has no " + kManifestName +
                     ": omnicam writes a dataset only into an empty folder or its own dataset's (and replaces only files a "
                     "dataset's manifest lists)");
  }
  if (!options.overwrite) return {previous, std::nullopt};
  return {std::nullopt, previous};
}

// The earlier run's frames in [first, end) whose robot pose is the spec's and whose files are
// exactly the ones this run writes, each still a regular file hashing to the manifest's SHA-256
// (a link or anything else is not intact: the frame is rendered again, and the rename replaces
// the entry without writing through it).
std::map<int, FrameRecord> intactFrames(const SafeFolder& dir, const DatasetManifest& previous,
                                        const DatasetPlan& plan) {
  std::map<int, FrameRecord> kept;
  const std::vector<OutputKind> kinds = plan.outputs().fileKinds();
  const std::vector<CameraSetup>& setups = plan.setups();
  for (const auto& [index, frame] : previous.frames) {
    if (index < plan.range().first || index >= plan.range().end || frame.cameras.size() != setups.size()) continue;
    const RobotPose& want = plan.poses()[index];
    if (frame.robot.x != want.x || frame.robot.y != want.y || frame.robot.yawDeg != want.yawDeg ||
        !(frame.velocity == plan.velocities()[index]) || frame.robotTiltDeg != plan.robotTilt(index))
      continue;
    bool intact = true;
    for (size_t c = 0; c < setups.size(); ++c) {
      const CameraSetup& setup = setups[c];
      const auto camera = frame.cameras.find(setup.camera->name);
      intact = intact && camera != frame.cameras.end() && camera->second.files.size() == kinds.size() &&
               camera->second.rig == (plan.vibrates() ? std::optional<RigSpec>(plan.frameRig(index, c)) : std::nullopt);
      for (size_t k = 0; intact && k < kinds.size(); ++k) {
        const FileRecord* file = camera->second.file(kinds[k]);
        intact = file && file->path == plan.outputs().framePath(setup.camera->name, kinds[k], index) && stillAsRecorded(dir, *file);
      }
    }
    if (intact) kept[index] = frame;
  }
  return kept;
}

// shards/ claimed by this process alone, waiting while another shard holds it (a few milliseconds:
// its check and first manifest); nullopt when the run is asked to stop meanwhile.
std::optional<FileDescriptor> claimShardsFolder(const SafeFolder& folder, const DatasetRunOptions& options) {
  for (bool told = false;; told = true) {
    if (std::optional<FileDescriptor> claim = folder.tryClaimAlone("shards")) return claim;
    if (!told && options.onWaitForShards) options.onWaitForShards();
    if (options.stopRequested && options.stopRequested->load()) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

// runDataset's work, on whatever threads the caller's arena gives it.
DatasetRunResult runDatasetHere(const DatasetSpec& spec, const DatasetRunOptions& options) {
  const DatasetPlan plan(spec, options);
  // At least one frame must fit, before the folder is touched.
  requireMemory(plan.frameBytes(), "one frame of this dataset");
  DatasetRunResult result;
  result.frames = plan.range().end - plan.range().first;
  result.notes = plan.notes();
  DatasetManifest manifest;
  manifest.header = plan.header();

  // The folder is opened (made when new) once, and everything below is written through its
  // descriptor. It is claimed first: one run at a time, or the shards of one together (each
  // writes its own manifest), so two runs never take the same folder over at once.
  std::error_code ec;
  if (fs::exists(options.dir, ec) && !fs::is_directory(options.dir, ec))
    throw InputError(showPath(options.dir) + ": exists and is not a folder");
  const SafeFolder folder(options.dir, true);
  if (!folder.tryClaim(plan.range().sharded))
    throw InputError(showPath(options.dir) + ": another omnicam run is writing " +
                     (plan.range().sharded ? "a whole dataset (or merging its shards)" : "a dataset") +
                     " there now: wait for it to end, or give another folder");
  // The folder: new, this dataset (resume), or something else (refused unless overwriting a
  // dataset). Everything in it is checked before anything is written: a planted link or a file
  // where a folder goes ends the run here.
  FolderTakeover takeover = takeOverFolder(options, manifest.header, plan.range().manifestName);
  for (const std::string& sub : plan.folders()) folder.checkFolders(sub);
  // Shards share the folder (shared claims), so two could pass that check at once, each before the
  // other's manifest is there: a shard checks again holding shards/ alone, until its manifest is
  // in it. And one shard is one run's: the same shard twice would render the same frames and each
  // replace the other's manifest.
  std::optional<HeldName> shardHeld;
  FileDescriptor shardsClaim;
  if (plan.range().sharded) {
    shardHeld = holdShard(options.dir, options.shardIndex, options.shardCount);
    if (!shardHeld)
      throw InputError(showPath(options.dir) + ": shard " + std::to_string(options.shardIndex) + "/" +
                       std::to_string(options.shardCount) + " is being rendered there now by another run on this machine: wait for it to end");
    std::optional<FileDescriptor> claim = claimShardsFolder(folder, options);
    if (!claim) {  // asked to stop while another shard held it: nothing written
      result.stopped = result.stoppedWaiting = true;
      return result;
    }
    shardsClaim = std::move(*claim);
    takeover = takeOverFolder(options, manifest.header, plan.range().manifestName);
    if (takeover.resumed) shardsClaim = FileDescriptor();  // its manifest is there already: the next shard's check sees it
  }
  // Every check has passed: the dataset overwritten goes now.
  if (takeover.replaced) removeDatasetFiles(folder, *takeover.replaced);
  // The folder is new, empty or a dataset now. A shard never removes temporaries (another shard
  // may be writing them; the merge does).
  if (!plan.range().sharded) {
    std::set<std::string> folders(plan.folders().begin(), plan.folders().end());
    folders.insert("slurm");  // sbatch's log of a submission (cluster/slurm_backend.cpp)
    removeAtomicTemporaries(options.dir, withParentFolders(folders));
  }
  if (takeover.resumed) manifest.frames = intactFrames(folder, *takeover.resumed, plan);
  result.kept = static_cast<int>(manifest.frames.size());
  // The manifest comes first: from its first file on, the folder is recognisably a dataset.
  writeManifest(folder, manifest, plan.range().manifestName);
  shardsClaim = FileDescriptor();  // the shard is in shards/ now: the next one's check sees it
  for (const std::string& sub : plan.folders()) folder.makeFolders(sub);
  for (const StaticFile& file : plan.statics()) folder.writeFile(file.relative, file.text, Durability::Unsynced);

  std::vector<int> todo;
  for (int f = plan.range().first; f < plan.range().end; ++f)
    if (!manifest.frames.count(f)) todo.push_back(f);
  if (options.onNotes) options.onNotes(result.notes);
  if (options.onStart) options.onStart(result.kept, result.frames);
  result.rendered = renderFrames(plan, folder, options, todo, manifest, result.kept, result.frames);
  result.stopped = result.kept + result.rendered < result.frames;
  manifest.header["complete"] = !result.stopped;
  // The annotations gathered per camera, once every frame is there (a shard's: by the merge).
  if (!result.stopped && !plan.range().sharded) {
    writeAnnotationFiles(folder, manifest);
    writeCalibrationBag(folder, manifest);
  }
  writeManifest(folder, manifest, plan.range().manifestName);
  return result;
}

}  // namespace

DatasetRunResult runDataset(const DatasetSpec& spec, const DatasetRunOptions& options) {
  checkThreads(options.threads, "threads");
  if (options.threads <= 0) return runDatasetHere(spec, options);
  // Exactly `threads` TBB threads (frames, rows and encoders), also beyond the cores this process
  // may use: the limit raises TBB's worker pool, the arena asks for it (either alone caps at the
  // core count). Both are released when the run ends.
  const tbb::global_control threadLimit(tbb::global_control::max_allowed_parallelism, options.threads);
  tbb::task_arena arena(options.threads);
  DatasetRunResult result;
  arena.execute([&] { result = runDatasetHere(spec, options); });
  return result;
}

void checkShardsMayJoin(const std::string& dir, const json& header, int count) {
  DatasetRunOptions options;
  options.dir = dir;
  options.shardCount = count;
  (void)takeOverFolder(options, header, shardManifestName(0, count));
}

}  // namespace omnicam
