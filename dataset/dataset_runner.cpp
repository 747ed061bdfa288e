#include "dataset_runner.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "atomic_file.h"
#include "errors.h"
#include "dataset_shards.h"
#include "fast_renderer.h"
#include "frame_outputs.h"
#include "camera_rays.h"
#include "coco.h"
#include "coco_files.h"
#include "image.h"
#include "intrinsics_files.h"
#include "make_camera.h"
#include "manifest.h"
#include "number_format.h"
#include "pose_sampler.h"
#include "safe_files.h"
#include "scene_ids.h"
#include "scene_loader.h"
#include "sha256.h"
#include "sidecar.h"

namespace omnicam {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The manifest is rewritten at most this often while frames complete (and always after the
// first window of frames and at the end).
constexpr double kManifestIntervalSeconds = 1.0;
// Frames the fast engine renders at once: enough to keep every core busy between the serial
// parts (writing, the manifest), few enough that a stop request is honoured quickly.
constexpr int kConcurrentFrames = 8;

struct CameraSetup {
  const DatasetCamera* camera;
  RigSpec rig;
  std::shared_ptr<const Camera> model;  // the rig's camera (make_camera.h), built once per run
};

// Folders of a camera the dataset layout has (docs/dataset-format.md).
constexpr const char* kCameraFolders[] = {"rgb", "depth", "instance", "semantic", "normal", "landmarks", "coco", "intrinsics"};

// TUM RGB-D trajectory format: "timestamp tx ty tz qx qy qz qw", the camera frame (X forward,
// Y right, Z down at F'; the intrinsics files' frame) in the world.
std::string posesTum(const std::vector<RobotPose>& robotPoses, const CameraSetup& setup, double interval) {
  std::ostringstream out;
  out << "# omnicam dataset camera \"" << setup.camera->name << "\": timestamp tx ty tz qx qy qz qw\n"
      << "# pose of the camera frame in the world (world_from_camera): origin at the mirror's effective\n"
      << "# viewpoint F', X forward, Y right, Z down (the frame of intrinsics/*.yaml); world +Z up, metres\n";
  for (size_t i = 0; i < robotPoses.size(); ++i) {
    const Rigid worldFromCam = worldFromCamera(setup.rig, cameraPose(*setup.camera, robotPoses[i]));
    const Eigen::Quaterniond q(worldFromCam.linear());
    const Vec3 t = worldFromCam.translation();
    out << roundTrip(static_cast<double>(i) * interval) << ' ' << roundTrip(t.x()) << ' ' << roundTrip(t.y()) << ' '
        << roundTrip(t.z()) << ' ' << roundTrip(q.x()) << ' ' << roundTrip(q.y()) << ' ' << roundTrip(q.z()) << ' '
        << roundTrip(q.w()) << '\n';
  }
  return out.str();
}

// A camera's files that stay the same from frame to frame: intrinsics and poses.
struct StaticFile {
  std::string key, relative, text;
};

std::vector<StaticFile> staticFiles(const CameraSetup& setup, const std::vector<RobotPose>& poses, double interval) {
  const std::string& name = setup.camera->name;
  const Camera& camera = *setup.model;
  std::vector<StaticFile> files = {
      {"intrinsics_opencv", name + "/intrinsics/opencv.yaml", openCvIntrinsicsYaml(camera)},
      {"intrinsics_kalibr", name + "/intrinsics/kalibr.yaml", kalibrIntrinsicsYaml(name, camera)},
      {"intrinsics_camodocal", name + "/intrinsics/camodocal.yaml", camodocalIntrinsicsYaml(name, camera)},
      {"poses_tum", name + "/poses.tum", posesTum(poses, setup, interval)}};
  // A physical rig's exact rays, which no central model in the files above states exactly.
  if (!setup.rig.ideal()) {
    const CameraRayTable table = cameraRayTable(camera);
    const std::vector<unsigned char> exr = encodeDataExr("rays.exr", table.width, table.height, kCameraRayChannels, table.values.data());
    files.push_back({"rays", name + "/intrinsics/rays.exr", std::string(exr.begin(), exr.end())});
  }
  return files;
}

// Whether `relative` is a file of the dataset layout for one of `cameras`: all that overwriting
// may remove, whatever else a manifest lists.
bool isLayoutFile(const std::string& relative, const std::set<std::string>& cameras) {
  static const std::regex layout(
      R"(([^/]+)/((rgb|depth|instance|semantic|normal|landmarks)/\d{6}\.(png|exr|json)|intrinsics/((opencv|kalibr|camodocal)\.yaml|rays\.exr)|poses\.tum))");
  std::smatch m;
  return std::regex_match(relative, m, layout) && cameras.count(m[1].str());
}

std::set<std::string> cameraNames(const DatasetManifest& manifest) {
  std::set<std::string> names;
  for (const json& camera : manifest.header.at("cameras")) names.insert(camera.at("name").get<std::string>());
  return names;
}

// Overwriting: removes the files `old` lists in the dataset layout (regular files only), then
// its camera folders that this leaves empty. Nothing else: a folder named like a camera may hold
// the user's own files, and they stay.
void removeDatasetFiles(const std::string& dir, const DatasetManifest& old) {
  const std::set<std::string> cameras = cameraNames(old);
  for (const FileRecord& file : manifestFiles(old))
    if (isLayoutFile(file.path, cameras)) removeFileInside(dir, file.path);
  for (const std::string& camera : cameras) {
    for (const char* kind : kCameraFolders) removeEmptyFolderInside(dir, camera + "/" + kind);
    removeEmptyFolderInside(dir, camera);
  }
}

DatasetManifest readPreviousManifest(const std::string& dir, const std::string& name) {
  try {
    return readDatasetManifest(dir, name);
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) +
                     " (omnicam resumes or replaces a dataset only by its readable manifest; move the folder away to start afresh)");
  }
}

// What the folder holds before the run: nothing (new or empty: nullopt), this dataset (resumed:
// its manifest), or something else — refused, except another dataset when overwriting, whose
// files are then removed. A shard reads its own manifest, and the merged one if there is one.
std::optional<DatasetManifest> takeOverFolder(const DatasetRunOptions& options, const json& header,
                                              const std::string& manifestName) {
  const std::string& dir = options.dir;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw InputError(showPath(dir) + ": exists and is not a folder");
  if (!fs::exists(dir, ec) || fs::is_empty(dir, ec)) return std::nullopt;
  std::vector<std::string> names{kManifestName};
  if (manifestName != kManifestName) names.push_back(manifestName);
  std::optional<DatasetManifest> previous;
  for (const std::string& name : names) {
    if (entryInside(dir, name) == EntryKind::Missing) continue;
    previous = readPreviousManifest(dir, name);
    if (datasetIdentity(previous->header) != datasetIdentity(header) && !options.overwrite) {
      const json sha = previous->header.value("spec_sha256", json());
      throw OtherDatasetError(showPath(dir) + ": holds a dataset made from a different spec, scene or engine (spec_sha256 " +
                              (sha.is_string() ? quote(sha.get<std::string>()) : std::string("?")) + ")");
    }
  }
  if (!previous) {
    // Other shards of a dataset fill the folder ("shards/" marks it as theirs).
    if (manifestName != kManifestName && entryInside(dir, "shards") == EntryKind::Folder) return std::nullopt;
    throw InputError(showPath(dir) + ": folder is not empty and has no " + kManifestName +
                     ": omnicam writes a dataset only into an empty folder or its own dataset's (and replaces only files a "
                     "dataset's manifest lists)");
  }
  if (!options.overwrite) return previous;
  removeDatasetFiles(dir, *previous);
  return std::nullopt;
}

// The earlier run's frames in [first, end) whose robot pose is the spec's and whose files are
// exactly the ones this run writes, each still a regular file hashing to the manifest's SHA-256
// (a link or anything else is not intact: the frame is rendered again, and the rename replaces
// the entry without writing through it).
std::map<int, FrameRecord> intactFrames(const std::string& dir, const DatasetManifest& previous,
                                        const std::vector<RobotPose>& poses, const std::vector<CameraSetup>& setups,
                                        const FrameOutputPlan& plan, int first, int end) {
  std::map<int, FrameRecord> kept;
  const std::vector<std::string> kinds = frameFileKinds(plan);
  for (const auto& [index, frame] : previous.frames) {
    if (index < first || index >= end || frame.cameras.size() != setups.size()) continue;
    const RobotPose& want = poses[index];
    if (frame.robot.x != want.x || frame.robot.y != want.y || frame.robot.yawDeg != want.yawDeg) continue;
    bool intact = true;
    for (const CameraSetup& setup : setups) {
      const auto camera = frame.cameras.find(setup.camera->name);
      intact = intact && camera != frame.cameras.end() && camera->second.files.size() == kinds.size();
      for (size_t k = 0; intact && k < kinds.size(); ++k) {
        const auto file = camera->second.files.find(kinds[k]);
        intact = file != camera->second.files.end() &&
                 file->second.path == frameFilePath(setup.camera->name, kinds[k], index, plan) &&
                 sha256Inside(dir, file->second.path, kMaxDatasetFileBytes).sha256 == file->second.sha256;
      }
    }
    if (intact) kept[index] = frame;
  }
  return kept;
}

// Inside a cancelled parallel_for (a neighbouring frame's write failed) the engine's and the
// encoders' nested loops end early without an error, so what this frame holds may be
// incomplete: nothing of it is written. The neighbour's error ends the run.
void stopIfCancelled() {
  if (tbb::is_current_task_group_canceling()) throw std::runtime_error("frame cancelled");
}

// The cameras of the spec with their rigs (the spec's size applied), each checked.
std::vector<CameraSetup> cameraSetups(const DatasetSpec& spec, const Scene& scene) {
  std::vector<CameraSetup> setups;
  for (const DatasetCamera& camera : spec.cameras) {
    CameraSetup setup{&camera, camera.rig ? rigFromJson(*camera.rig, spec.file, "cameras." + camera.name + ".rig") : scene.rig, {}};
    if (spec.size) setup.rig = setup.rig.resized(*spec.size);
    checkRenderSettings({setup.rig, spec.spp, spec.shading}, settingNames(spec));
    setup.model = makeCamera(setup.rig);
    setups.push_back(setup);
  }
  return setups;
}

// The frames [first, end) one run renders, listed in manifestName.
struct FrameRange {
  bool sharded = false;
  int first = 0, end = 0;
  std::string manifestName;
};

FrameRange frameRange(const DatasetRunOptions& options, int totalFrames) {
  FrameRange range;
  range.sharded = options.shardCount > 0;
  const int shardCount = std::max(1, options.shardCount);
  if (options.shardCount < 0 || options.shardCount > kMaxShards || options.shardIndex < 0 || options.shardIndex >= shardCount)
    throw InputError("shard " + std::to_string(options.shardIndex) + " of " + std::to_string(options.shardCount) +
                     ": must be shard I of N with 0 <= I < N <= " + std::to_string(kMaxShards));
  if (range.sharded && options.overwrite) throw InputError(showPath(options.dir) + ": a shard never overwrites (shards share the folder)");
  range.first = static_cast<int>(static_cast<int64_t>(totalFrames) * options.shardIndex / shardCount);
  range.end = static_cast<int>(static_cast<int64_t>(totalFrames) * (options.shardIndex + 1) / shardCount);
  range.manifestName = range.sharded ? shardManifestName(options.shardIndex, options.shardCount) : kManifestName;
  return range;
}

// Which files each frame gets: AOVs only from an engine that renders them; the others are listed
// in `notWritten` with the reason, and in `notes` for the user.
FrameOutputPlan outputPlan(const DatasetSpec& spec, const Engine& engine, const Scene& scene, json& notWritten,
                           std::vector<std::string>& notes) {
  FrameOutputPlan plan;
  plan.rgbFormat = spec.outputs.rgb;
  plan.landmarks = spec.outputs.landmarks;  // geometry: any engine
  notWritten = json::object();
  if (engine.hasAovs()) {
    plan.depth = spec.outputs.depth, plan.instance = spec.outputs.instance;
    plan.semantic = spec.outputs.semantic, plan.normal = spec.outputs.normal;
  } else {
    const std::pair<const char*, bool> aovs[] = {{"depth", spec.outputs.depth}, {"instance", spec.outputs.instance},
                                                 {"semantic", spec.outputs.semantic}, {"normal", spec.outputs.normal}};
    for (const auto& [kind, wanted] : aovs)
      if (wanted) notWritten[kind] = "the " + spec.engine + " engine renders RGB only; render the same spec with engine fast for AOVs";
    if (!notWritten.empty())
      notes.push_back("engine " + spec.engine + " writes RGB only: depth, instance, semantic and normal outputs are not written (see manifest outputs.not_written)");
  }
  if (spec.outputs.coco) {
    if (!engine.hasAovs()) {
      notWritten["coco"] = "the " + spec.engine + " engine renders RGB only (COCO annotations come from the instance AOV); render the same spec with engine fast";
      notes.push_back("engine " + spec.engine + " writes RGB only: the coco output is not written");
    } else {
      plan.coco = true;
      plan.cocoClasses = cocoClassIds(idTables(scene), spec.outputs.cocoClasses, showPath(spec.file) + ": outputs.coco.classes");
    }
  }
  if ((plan.instance || plan.semantic || plan.coco) && scene.objects.size() > kMaxInstances)
    throw InputError(showPath(spec.file) + ": outputs.instance: scene has " + std::to_string(scene.objects.size()) +
                     " objects; instance ids are 16-bit (at most " + std::to_string(kMaxInstances) + ")");
  return plan;
}

// Instance ids 1, 2, ... in scene order and class ids 1, 2, ... in name order; 0 = none.
// The manifest's header (docs/dataset-format.md) but for its cameras.
json manifestHeader(const DatasetSpec& spec, const Scene& scene, const Engine& engine, const FrameOutputPlan& plan,
                    const json& notWritten, const IdTables& ids, int totalFrames, const DatasetRunOptions& options,
                    const FrameRange& range) {
  json header;
  header["format"] = kManifestFormat;
  header["spec"] = spec.json;
  header["spec_file"] = spec.file;
  header["spec_sha256"] = spec.sha256;
  header["tool"] = {{"name", "omnicam"}, {"version", fastRendererVersion()}};
  header["engine"] = {{"name", engine.name()}, {"version", engine.version()}, {"mode", engine.mode()},
                      {"mode_options", engine.modeOptions()}};
  header["scene"] = {{"path", scene.path}, {"name", scene.name}, {"sha256", scene.sha256}};
  header["settings"] = {{"spp", spec.spp}, {"shading", shadingName(spec.shading)},
                        {"frame_interval_s", spec.frameIntervalSeconds},
                        {"aov_sampling", "point-sampled at pixel centres (i + 0.5, j + 0.5)"},
                        {"depth", "metres along the viewing ray from the effective viewpoint F'; 0 = no hit or beyond the rim"},
                        {"normal", "world frame, unit, facing the camera; 0 = no hit"}};
  header["outputs"] = {{"written", frameFileKinds(plan)}, {"not_written", notWritten}};
  if (plan.coco) {
    header["outputs"]["coco_classes"] = plan.cocoClasses;
    json landmarks = json::array();
    for (const Landmark& l : scene.landmarks) landmarks.push_back(l.name);
    header["outputs"]["coco_keypoints"] = landmarks;
  }
  header["classes"] = ids.classes;
  header["instances"] = ids.instances;
  header["frame_count"] = totalFrames;
  if (range.sharded)
    header["shard"] = {{"index", options.shardIndex}, {"count", options.shardCount}, {"first_frame", range.first},
                       {"end_frame", range.end}};
  header["complete"] = false;
  return header;
}

// The header's cameras, each with its static files (intrinsics and poses) and their hashes; the
// files themselves go to `statics`.
json manifestCameras(const std::vector<CameraSetup>& setups, const std::vector<RobotPose>& poses, double interval,
                     std::vector<StaticFile>& statics) {
  json cameras = json::array();
  for (const CameraSetup& setup : setups) {
    json files = json::object();
    for (StaticFile& file : staticFiles(setup, poses, interval)) {
      files[file.key] = {{"path", file.relative}, {"sha256", sha256OfBytes(file.text)}};
      statics.push_back(std::move(file));
    }
    cameras.push_back({{"name", setup.camera->name},
                       {"rig", rigToJson(setup.rig)},
                       {"mount", {{"x", setup.camera->mountX}, {"y", setup.camera->mountY}, {"yaw_deg", setup.camera->mountYawDeg}}},
                       {"intrinsics", setup.model->describe()},
                       {"files", files}});
  }
  return cameras;
}

// The folders a run writes into: shards/ for a shard, and each camera's folder of every kind.
std::vector<std::string> datasetFolders(const std::vector<CameraSetup>& setups, const FrameOutputPlan& plan, bool sharded) {
  const std::vector<std::string> written = frameFileKinds(plan);
  std::vector<std::string> folders;
  if (sharded) folders.push_back("shards");
  for (const CameraSetup& setup : setups)
    for (const char* kind : kCameraFolders)
      if (std::string(kind) == "intrinsics" || std::find(written.begin(), written.end(), kind) != written.end())
        folders.push_back(setup.camera->name + "/" + kind);
  return folders;
}

// What rendering frames needs, fixed for the run.
struct FrameJob {
  const DatasetSpec& spec;
  const DatasetRunOptions& options;
  const Scene& scene;
  const std::vector<CameraSetup>& setups;
  const std::vector<RobotPose>& poses;
  Engine& engine;
  const FrameOutputPlan& plan;
  const std::vector<uint16_t>& classOfInstance;
  const RayScene* rays;
};

// Frame `index`: every camera's files, encoded in memory, hashed and written. `rgb[c]`, if not
// empty, holds camera c's image already rendered (a batching engine); `aovs` is reused memory.
FrameRecord renderFrame(const FrameJob& job, int index, std::vector<ImageRGBA*> rgb, AovFrame& aovs) {
  const DatasetSpec& spec = job.spec;
  FrameRecord record{index, static_cast<double>(index) * spec.frameIntervalSeconds, job.poses[index], {}};
  for (size_t c = 0; c < job.setups.size(); ++c) {
    const CameraSetup& setup = job.setups[c];
    const RenderSettings settings{setup.rig, spec.spp, spec.shading};
    const RobotPose pose = cameraPose(*setup.camera, job.poses[index]);
    ImageRGBA image = rgb[c] ? std::move(*rgb[c])
                      : job.plan.anyAov() ? job.engine.render(pose, settings, aovs)
                                          : job.engine.render(pose, settings);
    // Seeded by frame and camera: a resumed run records the same noise.
    if (spec.recording) image = recordFrame(*spec.recording, image, static_cast<uint64_t>(index) * job.setups.size() + c);
    std::vector<EncodedFile> files = encodeFrameOutputs(job.scene, job.rays, settings, setup.camera->name, index, pose, image,
                                                        job.plan.anyAov() ? &aovs : nullptr, job.plan, job.classOfInstance);
    stopIfCancelled();
    CameraFrame cameraFrame{pose, {}};
    for (EncodedFile& file : files) {
      writeFileInside(job.options.dir, file.relativePath, file.bytes, Durability::Unsynced);
      cameraFrame.files[file.kind] = {file.relativePath, sha256OfBytes(file.bytes)};
    }
    record.cameras[setup.camera->name] = std::move(cameraFrame);
  }
  return record;
}

// Renders the frames `todo` window by window, listing each window's frames in the manifest (the
// first at once, then at most once a second) until done or stopped. Frames rendered: the count.
int renderFrames(const FrameJob& job, const std::vector<int>& todo, DatasetManifest& manifest,
                 const std::string& manifestName, int done, int total) {
  const DatasetRunOptions& options = job.options;
  auto stop = [&] { return options.stopRequested && options.stopRequested->load(); };
  // A batching engine (Blender) renders a camera's poses of a batch in one session; a concurrent
  // one (fast, exact) renders a window of frames at once, every frame itself in parallel too.
  const size_t batch = job.engine.batches() ? kFramesPerBatch : job.engine.concurrent() ? kConcurrentFrames : 1;
  std::vector<AovFrame> aovSlots(std::min(batch, todo.size()));
  auto lastManifest = std::chrono::steady_clock::now();
  int rendered = 0;
  for (size_t start = 0; start < todo.size() && !stop(); start += batch) {
    const size_t end = std::min(todo.size(), start + batch);
    std::vector<std::vector<ImageRGBA>> rgb(job.setups.size());
    if (job.engine.batches()) {
      for (size_t c = 0; c < job.setups.size(); ++c) {
        std::vector<RobotPose> batchPoses;
        for (size_t k = start; k < end; ++k) batchPoses.push_back(cameraPose(*job.setups[c].camera, job.poses[todo[k]]));
        rgb[c] = job.engine.renderMany(batchPoses, {job.setups[c].rig, job.spec.spp, job.spec.shading});
      }
    }
    std::vector<FrameRecord> records(end - start);
    auto renderOne = [&](size_t k) {
      std::vector<ImageRGBA*> given(job.setups.size(), nullptr);
      for (size_t c = 0; c < job.setups.size(); ++c)
        if (!rgb[c].empty()) given[c] = &rgb[c][k];
      records[k] = renderFrame(job, todo[start + k], given, aovSlots[k]);
    };
    if (job.engine.concurrent()) {
      tbb::parallel_for(size_t{0}, end - start, renderOne);
    } else {
      for (size_t k = 0; k < end - start; ++k) renderOne(k);
    }
    for (FrameRecord& record : records) {
      manifest.frames[record.index] = std::move(record);
      ++rendered;
      if (options.onFrame) options.onFrame(done + rendered, total);
    }
    // The first finished window is listed at once, so that a run stopped early, however fast
    // the machine, leaves frames to resume from and a --status that shows them.
    const auto now = std::chrono::steady_clock::now();
    if (start == 0 || std::chrono::duration<double>(now - lastManifest).count() >= kManifestIntervalSeconds) {
      writeManifest(options.dir, manifest, manifestName);
      lastManifest = now;
    }
  }
  return rendered;
}

// runDataset's work, on whatever threads the caller's arena gives it.
DatasetRunResult runDatasetHere(const DatasetSpec& spec, const DatasetRunOptions& options) {
  const Scene scene = loadScene(spec.scene, {spec.allowOutsideFiles});
  const std::vector<CameraSetup> setups = cameraSetups(spec, scene);
  double topHeight = 0.0;
  for (const CameraSetup& setup : setups) topHeight = std::max(topHeight, setup.rig.height);
  const std::vector<RobotPose> poses = datasetPoses(spec, scene, topHeight);
  for (const RobotPose& robot : poses)
    for (const CameraSetup& setup : setups) checkPose(cameraPose(*setup.camera, robot), showPath(spec.file) + ": poses");
  const auto mode = parseMode(spec.mode, spec.faces, spec.faceSize, spec.polygons, showPath(spec.file) + ": mode");
  const auto engine =
      makeEngine(spec.engine, scene, spec.timeoutSeconds, mode.get(), showPath(spec.file) + ": engine", options.threads);
  for (const CameraSetup& setup : setups) {
    try {
      engine->checkCamera(setup.rig);
    } catch (const InputError& e) {
      throw InputError(showPath(spec.file) + ": camera " + quote(setup.camera->name) + ": " + e.what());
    }
  }

  DatasetRunResult result;
  const int totalFrames = static_cast<int>(poses.size());
  const FrameRange range = frameRange(options, totalFrames);
  result.frames = range.end - range.first;
  json notWritten;
  const FrameOutputPlan plan = outputPlan(spec, *engine, scene, notWritten, result.notes);
  const IdTables ids = idTables(scene);
  DatasetManifest manifest;
  manifest.header = manifestHeader(spec, scene, *engine, plan, notWritten, ids, totalFrames, options, range);
  std::vector<StaticFile> statics;
  manifest.header["cameras"] = manifestCameras(setups, poses, spec.frameIntervalSeconds, statics);
  checkManifestHeaderSize(manifest.header, spec.file);

  // The folder: new, this dataset (resume), or something else (refused unless overwriting a
  // dataset). Everything in it is checked before anything is written: a planted link or a file
  // where a folder goes ends the run here.
  const std::vector<std::string> folders = datasetFolders(setups, plan, range.sharded);
  const std::optional<DatasetManifest> previous = takeOverFolder(options, manifest.header, range.manifestName);
  for (const std::string& folder : folders) checkFoldersInside(options.dir, folder);
  // The folder is new, empty or a dataset now. A shard never removes temporaries (another shard
  // may be writing them; the merge does).
  if (!range.sharded) removeAtomicTemporaries(options.dir);
  if (previous) manifest.frames = intactFrames(options.dir, *previous, poses, setups, plan, range.first, range.end);
  result.kept = static_cast<int>(manifest.frames.size());
  // The manifest comes first: from its first file on, the folder is recognisably a dataset.
  writeManifest(options.dir, manifest, range.manifestName);
  for (const std::string& folder : folders) makeFoldersInside(options.dir, folder);
  for (const StaticFile& file : statics) writeFileInside(options.dir, file.relative, file.text, Durability::Unsynced);

  std::unique_ptr<RayScene> rays;
  if (plan.landmarks || (plan.coco && !scene.landmarks.empty())) rays = std::make_unique<RayScene>(scene);
  std::vector<int> todo;
  for (int f = range.first; f < range.end; ++f)
    if (!manifest.frames.count(f)) todo.push_back(f);
  if (options.onStart) options.onStart(result.kept, result.frames);
  const FrameJob job{spec, options, scene, setups, poses, *engine, plan, ids.classOfInstance, rays.get()};
  result.rendered = renderFrames(job, todo, manifest, range.manifestName, result.kept, result.frames);
  result.stopped = result.kept + result.rendered < result.frames;
  manifest.header["complete"] = !result.stopped;
  // The whole dataset's COCO files, once every frame is there (a shard's: by the merge).
  if (!result.stopped && !range.sharded) writeCocoFiles(options.dir, manifest);
  writeManifest(options.dir, manifest, range.manifestName);
  return result;
}

}  // namespace

DatasetRunResult runDataset(const DatasetSpec& spec, const DatasetRunOptions& options) {
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

}  // namespace omnicam
