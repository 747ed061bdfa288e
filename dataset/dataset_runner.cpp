#include "dataset_runner.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "atomic_file.h"
#include "errors.h"
#include "frame_outputs.h"
#include "intrinsics_files.h"
#include "manifest.h"
#include "number_format.h"
#include "pose_sampler.h"
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
};


std::string fileSha256(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return sha256OfBytes(bytes.str());
}

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

bool folderIsEmpty(const fs::path& dir) {
  std::error_code ec;
  return fs::is_empty(dir, ec);
}

void writeDatasetFile(const fs::path& dir, const std::string& relative, const std::string& bytes) {
  writeBytesAtomically((dir / relative).string(), bytes, Durability::Unsynced);
}

}  // namespace

namespace {

// runDataset's work, on whatever threads the caller's arena gives it.
DatasetRunResult runDatasetHere(const DatasetSpec& spec, const DatasetRunOptions& options) {
  const fs::path dir(options.dir);
  const Scene scene = loadScene(spec.scene, {spec.allowOutsideFiles});
  std::vector<CameraSetup> setups;
  double topHeight = 0.0;
  for (const DatasetCamera& camera : spec.cameras) {
    CameraSetup setup{&camera, camera.rig ? rigFromJson(*camera.rig, spec.file, "cameras." + camera.name + ".rig") : scene.rig};
    if (spec.size) setup.rig.imageSize = *spec.size;
    RenderSettings check{setup.rig, spec.spp, spec.shading};
    checkRenderSettings(check);
    topHeight = std::max(topHeight, setup.rig.height);
    setups.push_back(setup);
  }
  const std::vector<RobotPose> poses = datasetPoses(spec, scene, topHeight);
  for (const RobotPose& robot : poses)
    for (const CameraSetup& setup : setups) checkPose(cameraPose(*setup.camera, robot), showPath(spec.file) + ": poses");
  const auto mode = parseMode(spec.mode, spec.faces, spec.faceSize, spec.polygons, showPath(spec.file) + ": mode");
  const auto engine =
      makeEngine(spec.engine, scene, spec.timeoutSeconds, mode.get(), showPath(spec.file) + ": engine", options.threads);

  DatasetRunResult result;
  const int totalFrames = static_cast<int>(poses.size());
  const bool sharded = options.shardCount > 0;
  const int shardCount = std::max(1, options.shardCount);
  if (options.shardCount < 0 || options.shardIndex < 0 || options.shardIndex >= shardCount)
    throw InputError("--shard: must be I/N with 0 <= I < N");
  if (sharded && options.overwrite) throw InputError("--overwrite: not with --shard (remove the folder, then render the shards)");
  const int firstFrame = static_cast<int>(static_cast<int64_t>(totalFrames) * options.shardIndex / shardCount);
  const int endFrame = static_cast<int>(static_cast<int64_t>(totalFrames) * (options.shardIndex + 1) / shardCount);
  const std::string manifestName = sharded ? shardManifestName(options.shardIndex, options.shardCount) : kManifestName;
  result.frames = endFrame - firstFrame;
  FrameOutputPlan plan;
  plan.rgbFormat = spec.outputs.rgb;
  plan.landmarks = spec.outputs.landmarks;  // geometry: any engine
  json notWritten = json::object();
  if (engine->hasAovs()) {
    plan.depth = spec.outputs.depth, plan.instance = spec.outputs.instance;
    plan.semantic = spec.outputs.semantic, plan.normal = spec.outputs.normal;
  } else {
    const std::pair<const char*, bool> aovs[] = {{"depth", spec.outputs.depth}, {"instance", spec.outputs.instance},
                                                 {"semantic", spec.outputs.semantic}, {"normal", spec.outputs.normal}};
    for (const auto& [kind, wanted] : aovs)
      if (wanted) notWritten[kind] = "the " + spec.engine + " engine renders RGB only; render the same spec with engine fast for AOVs";
    if (!notWritten.empty())
      result.notes.push_back("engine " + spec.engine + " writes RGB only: depth, instance, semantic and normal outputs are not written (see manifest outputs.not_written)");
  }
  if ((plan.instance || plan.semantic) && scene.objects.size() > kMaxInstances)
    throw InputError(showPath(spec.file) + ": outputs.instance: scene has " + std::to_string(scene.objects.size()) +
                     " objects; instance ids are 16-bit (at most " + std::to_string(kMaxInstances) + ")");

  // Class ids: 1, 2, ... in name order; 0 = no class (or nothing hit).
  std::map<std::string, uint16_t> classIds;
  for (const SceneObject& object : scene.objects)
    if (const std::string& c = semanticClassOf(scene, object); !c.empty()) classIds[c] = 0;
  uint16_t nextClass = 1;
  json classes = json::array({{{"id", 0}, {"name", nullptr}}});
  for (auto& [name, id] : classIds) {
    id = nextClass++;
    classes.push_back({{"id", id}, {"name", name}});
  }
  std::vector<uint16_t> classOfInstance(scene.objects.size() + 1, 0);
  json instances = json::array({{{"id", 0}, {"name", nullptr}, {"class_id", 0}}});
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const std::string& c = semanticClassOf(scene, scene.objects[i]);
    classOfInstance[i + 1] = c.empty() ? 0 : classIds.at(c);
    instances.push_back({{"id", i + 1}, {"name", scene.objects[i].name},
                         {"class", c.empty() ? json(nullptr) : json(c)}, {"class_id", classOfInstance[i + 1]}});
  }

  json written = json::array({"rgb"});
  for (const auto& [kind, on] : {std::pair<const char*, bool>{"depth", plan.depth}, {"instance", plan.instance},
                                 {"semantic", plan.semantic}, {"normal", plan.normal}, {"landmarks", plan.landmarks}})
    if (on) written.push_back(kind);

  DatasetManifest manifest;
  json& header = manifest.header;
  header["format"] = kManifestFormat;
  header["spec"] = spec.json;
  header["spec_file"] = spec.file;
  header["spec_sha256"] = spec.sha256;
  header["tool"] = {{"name", "omnicam"}, {"version", fastRendererVersion()}};
  header["engine"] = {{"name", engine->name()}, {"version", engine->version()}, {"mode", engine->mode()},
                      {"mode_options", engine->modeOptions()}};
  header["scene"] = {{"path", scene.path}, {"name", scene.name}, {"sha256", scene.sha256}};
  header["settings"] = {{"spp", spec.spp}, {"shading", shadingName(spec.shading)},
                        {"frame_interval_s", spec.frameIntervalSeconds},
                        {"aov_sampling", "point-sampled at pixel centres (i + 0.5, j + 0.5)"},
                        {"depth", "metres along the viewing ray from the effective viewpoint F'; 0 = no hit or beyond the rim"},
                        {"normal", "world frame, unit, facing the camera; 0 = no hit"}};
  header["outputs"] = {{"written", written}, {"not_written", notWritten}};
  header["classes"] = classes;
  header["instances"] = instances;
  header["frame_count"] = totalFrames;
  if (sharded)
    header["shard"] = {{"index", options.shardIndex}, {"count", options.shardCount}, {"first_frame", firstFrame},
                       {"end_frame", endFrame}};
  header["complete"] = false;

  // The folder: new, this dataset (resume), or something else (refused unless --overwrite).
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw InputError("-o: " + showPath(options.dir) + ": exists and is not a folder");
  std::optional<DatasetManifest> previous;
  auto readPrevious = [&](const std::string& name) -> std::optional<DatasetManifest> {
    if (!fs::exists(dir / name, ec)) return std::nullopt;
    std::optional<DatasetManifest> found;
    try {
      found = readManifest(options.dir, name);
    } catch (const InputError& e) {
      if (!options.overwrite) throw InputError(std::string(e.what()) + " (use --overwrite to start afresh)");
    }
    if (found && datasetIdentity(found->header) != datasetIdentity(header) && !options.overwrite)
      throw InputError("-o: " + showPath(options.dir) + ": holds a dataset made from a different spec, scene or engine (spec_sha256 " +
                       found->header.value("spec_sha256", std::string("?")) + "); use --overwrite to replace it");
    return found;
  };
  if (fs::exists(dir / kManifestName, ec)) {
    previous = readPrevious(kManifestName);
    // A shard of a merged dataset keeps what the merged manifest lists, unless its own says more.
    if (sharded && fs::exists(dir / manifestName, ec)) previous = readPrevious(manifestName);
  } else if (sharded && fs::exists(dir / manifestName, ec)) {
    previous = readPrevious(manifestName);
  } else if (fs::exists(dir, ec) && !folderIsEmpty(dir) && !options.overwrite &&
             !(sharded && fs::is_directory(dir / "shards", ec))) {
    throw InputError("-o: " + showPath(options.dir) + ": folder is not empty and has no " + kManifestName + "; use --overwrite");
  }
  if (options.overwrite && fs::exists(dir, ec)) {
    // Only what a dataset owns: the manifest and the camera folders (old and new names).
    std::set<std::string> cameraFolders;
    for (const CameraSetup& s : setups) cameraFolders.insert(s.camera->name);
    // An old manifest's names are only trusted as far as the spec's rule goes: never "../x".
    if (previous)
      for (const json& c : previous->header.at("cameras"))
        if (const std::string name = c.at("name").get<std::string>(); isCameraFolderName(name)) cameraFolders.insert(name);
    for (const std::string& name : cameraFolders) fs::remove_all(dir / name, ec);
    fs::remove(dir / kManifestName, ec);
    previous.reset();
  }
  // Shards share the folder: "shards/" marks it as theirs before anything else is written, and a
  // shard never removes temporaries (another shard may be writing them; the merge does).
  fs::create_directories(sharded ? dir / "shards" : dir, ec);
  if (ec) throw OutputError("-o: " + showPath(options.dir) + ": cannot create folder (" + ec.message() + ")");
  if (!sharded) removeAtomicTemporaries(dir.string());

  // Static files per camera: intrinsics and poses.
  json cameras = json::array();
  for (const CameraSetup& setup : setups) {
    const std::string& name = setup.camera->name;
    for (const char* kind : {"rgb", "depth", "instance", "semantic", "normal", "landmarks", "intrinsics"}) {
      const bool wanted = std::string(kind) == "rgb" || std::string(kind) == "intrinsics" ||
                          std::find(written.begin(), written.end(), kind) != written.end();
      if (wanted) fs::create_directories(dir / name / kind, ec);
      if (ec) throw OutputError("-o: " + showPath((dir / name / kind).string()) + ": cannot create folder (" + ec.message() + ")");
    }
    const OmniCamera omni = setup.rig.camera();
    const std::pair<std::string, std::string> statics[] = {
        {"intrinsics_opencv", openCvIntrinsicsYaml(omni)},
        {"intrinsics_kalibr", kalibrIntrinsicsYaml(name, omni)},
        {"intrinsics_camodocal", camodocalIntrinsicsYaml(name, omni)},
        {"poses_tum", posesTum(poses, setup, spec.frameIntervalSeconds)}};
    json files = json::object();
    for (const auto& [key, text] : statics) {
      const std::string relative = key == "poses_tum" ? name + "/poses.tum"
                                                      : name + "/intrinsics/" + key.substr(std::string("intrinsics_").size()) + ".yaml";
      writeDatasetFile(dir, relative, text);
      files[key] = {{"path", relative}, {"sha256", sha256OfBytes(text)}};
    }
    cameras.push_back({{"name", name},
                       {"rig", rigToJson(setup.rig)},
                       {"mount", {{"x", setup.camera->mountX}, {"y", setup.camera->mountY}, {"yaw_deg", setup.camera->mountYawDeg}}},
                       {"intrinsics", intrinsicsToJson(omni)},
                       {"files", files}});
  }
  header["cameras"] = cameras;

  // Keep the earlier run's frames whose files all still hash right and whose poses match.
  if (previous) {
    for (auto& [index, frame] : previous->frames) {
      if (index < firstFrame || index >= endFrame || frame.cameras.size() != setups.size()) continue;
      const RobotPose& want = poses[index];
      if (frame.robot.x != want.x || frame.robot.y != want.y || frame.robot.yawDeg != want.yawDeg) continue;
      bool intact = true;
      for (const auto& [name, camera] : frame.cameras)
        for (const auto& [kind, file] : camera.files)
          if (intact && fileSha256(dir / file.path) != file.sha256) intact = false;
      if (intact) manifest.frames[index] = frame;
    }
  }
  result.kept = static_cast<int>(manifest.frames.size());
  writeManifest(options.dir, manifest, manifestName);

  std::unique_ptr<RayScene> rays;
  if (plan.landmarks) rays = std::make_unique<RayScene>(scene);
  std::vector<int> todo;
  for (int f = firstFrame; f < endFrame; ++f)
    if (!manifest.frames.count(f)) todo.push_back(f);
  int done = result.kept;
  if (options.onStart) options.onStart(result.kept, result.frames);
  auto lastManifest = std::chrono::steady_clock::now();
  auto stop = [&] { return options.stopRequested && options.stopRequested->load(); };
  // A batching engine (Blender) renders a camera's poses of a batch in one session; a concurrent
  // one (fast, exact) renders a window of frames at once, every frame itself in parallel too.
  const size_t batch = engine->batches() ? kFramesPerBatch : engine->concurrent() ? kConcurrentFrames : 1;
  std::vector<AovFrame> aovSlots;
  for (size_t start = 0; start < todo.size() && !stop(); start += batch) {
    const size_t end = std::min(todo.size(), start + batch);
    std::vector<std::vector<ImageRGBA>> rgb(setups.size());
    if (engine->batches()) {
      for (size_t c = 0; c < setups.size(); ++c) {
        std::vector<RobotPose> batchPoses;
        for (size_t k = start; k < end; ++k) batchPoses.push_back(cameraPose(*setups[c].camera, poses[todo[k]]));
        rgb[c] = engine->renderMany(batchPoses, {setups[c].rig, spec.spp, spec.shading});
      }
    }
    if (aovSlots.size() < end - start) aovSlots.resize(end - start);
    // Frame k of the batch: every camera's files, encoded in memory, hashed and written.
    std::vector<FrameRecord> records(end - start);
    auto renderFrame = [&](size_t k) {
      const int index = todo[start + k];
      FrameRecord& record = records[k];
      record = {index, static_cast<double>(index) * spec.frameIntervalSeconds, poses[index], {}};
      for (size_t c = 0; c < setups.size(); ++c) {
        const RenderSettings settings{setups[c].rig, spec.spp, spec.shading};
        const RobotPose pose = cameraPose(*setups[c].camera, poses[index]);
        AovFrame& aovs = aovSlots[k];  // the window's slot k: reused, so no fresh memory per frame
        ImageRGBA image = !rgb[c].empty() ? std::move(rgb[c][k])
                          : plan.anyAov() ? engine->render(pose, settings, aovs)
                                          : engine->render(pose, settings);
        // Seeded by frame and camera: a resumed run records the same noise.
        if (spec.recording) image = recordFrame(*spec.recording, image, static_cast<uint64_t>(index) * setups.size() + c);
        CameraFrame cameraFrame{pose, {}};
        for (EncodedFile& file : encodeFrameOutputs(scene, rays.get(), settings, setups[c].camera->name, index, pose,
                                                    image, plan.anyAov() ? &aovs : nullptr, plan, classOfInstance)) {
          writeDatasetFile(dir, file.relativePath, file.bytes);
          cameraFrame.files[file.kind] = {file.relativePath, sha256OfBytes(file.bytes)};
        }
        record.cameras[setups[c].camera->name] = std::move(cameraFrame);
      }
    };
    if (engine->concurrent()) {
      tbb::parallel_for(size_t{0}, end - start, renderFrame);
    } else {
      for (size_t k = 0; k < end - start; ++k) renderFrame(k);
    }
    for (size_t k = 0; k < end - start; ++k) {
      manifest.frames[records[k].index] = std::move(records[k]);
      ++result.rendered;
      ++done;
      if (options.onFrame) options.onFrame(done, result.frames);
    }
    // The first finished window is listed at once, so that a run stopped early, however fast
    // the machine, leaves frames to resume from and a --status that shows them.
    const auto now = std::chrono::steady_clock::now();
    if (start == 0 || std::chrono::duration<double>(now - lastManifest).count() >= kManifestIntervalSeconds) {
      writeManifest(options.dir, manifest, manifestName);
      lastManifest = now;
    }
  }
  result.stopped = done < result.frames;
  header["complete"] = !result.stopped;
  writeManifest(options.dir, manifest, manifestName);
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

DatasetStatus datasetStatus(const std::string& dir) {
  const DatasetManifest manifest = readManifest(dir);
  DatasetStatus status;
  status.frames = manifest.header.value("frame_count", 0);
  status.finished = static_cast<int>(manifest.frames.size());
  status.complete = manifest.header.value("complete", false) && status.finished == status.frames;
  return status;
}

DatasetVerifyResult verifyDataset(const std::string& dir, const std::string& manifestName) {
  const DatasetManifest manifest = readManifest(dir, manifestName);
  DatasetVerifyResult result;
  for (const FileRecord& file : manifestFiles(manifest)) {
    ++result.files;
    const fs::path path = fs::path(dir) / file.path;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
      result.problems.push_back(showPath(file.path) + ": missing");
      continue;
    }
    const std::string actual = fileSha256(path);
    if (actual != file.sha256) result.problems.push_back(showPath(file.path) + ": SHA-256 " + actual + " differs from the manifest's " + file.sha256);
  }
  // A shard is complete with its own range of frames.
  const json shard = manifest.header.value("shard", json());
  const int wanted = shard.is_object() ? shard.at("end_frame").get<int>() - shard.at("first_frame").get<int>()
                                       : manifest.header.value("frame_count", 0);
  if (static_cast<int>(manifest.frames.size()) != wanted || !manifest.header.value("complete", false))
    result.problems.push_back(manifestName + ": incomplete: " + std::to_string(manifest.frames.size()) + " of " +
                              std::to_string(wanted) + " frames finished (run the same command again to resume)");
  return result;
}

}  // namespace omnicam
