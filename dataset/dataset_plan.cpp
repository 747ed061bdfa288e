#include "dataset_plan.h"

#include <algorithm>
#include <filesystem>
#include <cctype>
#include <cmath>
#include <functional>
#include <sstream>

#include "camera_rays.h"
#include "dataset_folder.h"
#include "coco.h"
#include "dataset_shards.h"
#include "euroc_files.h"
#include "errors.h"
#include "fast_renderer.h"
#include "image.h"
#include "intrinsics_files.h"
#include "make_camera.h"
#include "memory_budget.h"
#include "manifest.h"
#include "multilayer_frame.h"
#include "number_format.h"
#include "pose_sampler.h"
#include "scene_bounds.h"
#include "scene_loader.h"
#include "sha256.h"
#include "path_tracing_record.h"
#include "sidecar.h"
#include "trajectory.h"

namespace omnicam {

using nlohmann::json;

namespace {

// TUM RGB-D trajectory format: "timestamp tx ty tz qx qy qz qw", the camera frame (X forward,
// Y right, Z down at F'; the intrinsics files' frame) in the world.
std::string posesTum(size_t frames, const CameraSetup& setup, double interval, const std::function<RigSpec(int)>& rigOfFrame,
                     const std::function<CameraPlacement(int)>& placementOfFrame) {
  std::ostringstream out;
  out << "# omnicam dataset camera \"" << setup.camera->name << "\": timestamp tx ty tz qx qy qz qw\n";
  out << std::visit(Overloaded{[](const MirrorRig&) {
                                 return "# pose of the camera frame in the world (world_from_camera): origin at the mirror's effective\n"
                                        "# viewpoint F', X forward, Y right, Z down (the frame of intrinsics/*.yaml; a physical rig's best\n"
                                        "# fit has its own, opencv.yaml's camera_from_rig); world +Z up, metres\n";
                               },
                               [](const LensCameraSpec&) {
                                 return "# pose of the camera frame in the world (world_from_camera): origin at the lens' centre of\n"
                                        "# projection, X right, Y down, Z along the optical axis (OpenCV's; intrinsics/*.yaml); world +Z up, metres\n";
                               }},
                    setup.rig.kind);
  for (size_t i = 0; i < frames; ++i) {
    const int frame = static_cast<int>(i);
    const Rigid worldFromCam = placementOfFrame(frame).worldFromCamera(rigOfFrame(frame));
    const Eigen::Quaterniond q(worldFromCam.linear());
    const Vec3 t = worldFromCam.translation();
    // The rounding residue of a right angle's cosine (6.1e-17) and a negative zero are written 0:
    // a quarter turn reads as one. Below 1e-12 (a rotation of 2e-12 rad, a position of 1 pm)
    // nothing is lost.
    const auto tidy = [](double value) { return roundTrip(std::abs(value) < 1e-12 ? 0.0 : value); };
    out << roundTrip(frameTimestampSeconds(frame, interval)) << ' ' << tidy(t.x()) << ' ' << tidy(t.y()) << ' ' << tidy(t.z())
        << ' ' << tidy(q.x()) << ' ' << tidy(q.y()) << ' ' << tidy(q.z()) << ' ' << tidy(q.w()) << '\n';
  }
  return out.str();
}

// A camera's files that stay the same from frame to frame: intrinsics and poses.
std::vector<StaticFile> staticFiles(const CameraSetup& setup, const std::vector<RobotPose>& poses, double interval,
                                    const std::function<RigSpec(int)>& rigOfFrame,
                                    const std::function<CameraPlacement(int)>& placementOfFrame, bool euroc) {
  const std::string& name = setup.camera->name;
  const Camera& camera = *setup.model;
  std::vector<StaticFile> files;
  for (IntrinsicsFile& file : intrinsicsFiles(name, camera))
    files.push_back({file.kind, name + "/intrinsics/" + file.fileName, std::move(file.text)});
  files.push_back({"poses_tum", name + "/poses.tum", posesTum(poses.size(), setup, interval, rigOfFrame, placementOfFrame)});
  if (euroc) {
    files.push_back({"euroc_data_csv", name + "/data.csv", eurocDataCsv(static_cast<int>(poses.size()), interval)});
    files.push_back({"euroc_sensor_yaml", name + "/sensor.yaml", eurocSensorYaml(*setup.camera, setup.rig, camera, interval)});
  }
  // A physical rig's exact rays, which no central model in the files above states exactly.
  if (!setup.rig.ideal()) {
    const CameraRayTable table = cameraRayTable(camera);
    const std::vector<unsigned char> exr = encodeDataExr("rays.exr", table.width, table.height, kCameraRayChannels, table.values.data());
    files.push_back({"rays", name + "/intrinsics/rays.exr", std::string(exr.begin(), exr.end())});
  }
  return files;
}

// The cameras of the spec with their rigs (the spec's size applied), each checked. The size is
// every camera's width: a lens camera of another width is scaled with its intrinsics, which its
// rig (the spec's or the scene's) does not show: told in `notes`.
std::vector<CameraSetup> cameraSetups(const DatasetSpec& spec, const Scene& scene, std::vector<std::string>& notes) {
  std::vector<CameraSetup> setups;
  for (const DatasetCamera& camera : spec.cameras) {
    CameraSetup setup{&camera, camera.rig ? rigFromJson(*camera.rig, spec.file, "cameras." + camera.name + ".rig") : scene.rig, {}};
    if (spec.size) {
      const RigSpec given = setup.rig;
      setup.rig = setup.rig.resized(*spec.size, showPath(spec.file) + ": size: camera " + quote(camera.name));
      // A size the camera's own rig gives, overridden: said (the scene's rig's size is what
      // `size` is there to set).
      const bool ownSize = camera.rig && !std::holds_alternative<LensCameraSpec>(given.kind) && camera.rig->contains("image") &&
                           (*camera.rig)["image"].is_object() && (*camera.rig)["image"].contains("size");
      if (ownSize && given.imageWidth() != *spec.size)
        notes.push_back(showPath(spec.file) + ": size: camera " + quote(camera.name) + ", whose rig gives " + std::to_string(given.imageWidth()) +
                        " px, renders at " + std::to_string(setup.rig.imageWidth()) + " px (size is every camera's width)");
      if (std::holds_alternative<LensCameraSpec>(given.kind) && given.imageWidth() != *spec.size)
        notes.push_back(showPath(spec.file) + ": size: camera " + quote(camera.name) + ", a lens camera of " + given.imageSizeText() +
                        ", renders at " + setup.rig.imageSizeText() + " with its intrinsics scaled (size is every camera's width)");
    }
    checkRenderSettings(spec.request.settings(setup.rig), settingNames(spec));
    setup.model = makeCamera(setup.rig);
    setups.push_back(setup);
  }
  return setups;
}

FrameRange frameRange(const DatasetRunOptions& options, int totalFrames) {
  FrameRange range;
  range.sharded = options.shardCount > 0;
  const int shardCount = std::max(1, options.shardCount);
  if (options.shardCount < 0 || options.shardCount > kMaxShards || options.shardIndex < 0 || options.shardIndex >= shardCount)
    throw InputError("shard " + std::to_string(options.shardIndex) + " of " + std::to_string(options.shardCount) +
                     ": must be shard I of N with 0 <= I < N <= " + std::to_string(kMaxShards));
  if (range.sharded && options.overwrite) throw InputError(showPath(options.dir) + ": a shard never overwrites (shards share the folder)");
  // A shard without a frame would hold a task (a Slurm array's, a machine's) for nothing.
  if (range.sharded && shardCount > totalFrames)
    throw InputError("shard count " + std::to_string(shardCount) + ": more than the dataset's " + std::to_string(totalFrames) + " frame" +
                     (totalFrames == 1 ? "" : "s") + " (a shard would render none): give at most " + std::to_string(totalFrames));
  const ShardFrames frames = shardFrames(totalFrames, options.shardIndex, shardCount);
  range.first = frames.first;
  range.end = frames.end;
  range.manifestName = range.sharded ? shardManifestName(options.shardIndex, options.shardCount) : kManifestName;
  return range;
}

// Which outputs each frame gets: AOVs only from an engine that renders them; the others are
// listed in `notWritten` with the reason, and in `notes` for the user.
FrameOutputPlan outputPlan(const DatasetSpec& spec, const Engine& engine, const Scene& scene, json& notWritten,
                           std::vector<std::string>& notes) {
  FrameOutputPlan plan;
  plan.layout = spec.layout;
  plan.compression = spec.multilayerCompression;
  plan.rgbFormat = spec.outputs.rgb;  // the files layout's; multilayer colour is in the frame file
  if (spec.euroc) plan.eurocIntervalS = spec.frameIntervalSeconds;
  notWritten = json::object();
  for (OutputKind kind : spec.outputs.wanted) {
    if (!needsAovs(kind) || engine.capabilities().aovs) {
      plan.outputs.insert(kind);
    } else {
      const std::string note = outputRow(kind).aovNote;
      notWritten[outputName(kind)] = "the " + spec.request.engine + " engine renders RGB only" +
                                     (note.empty() ? "; render the same spec with engine fast for AOVs"
                                                   : " (" + note + "); render the same spec with engine fast");
    }
  }
  if (!notWritten.empty()) {
    std::string kinds;
    for (auto it = notWritten.begin(); it != notWritten.end(); ++it) kinds += (kinds.empty() ? "" : ", ") + it.key();
    notes.push_back("engine " + spec.request.engine + " writes RGB only: " + kinds + " not written (see manifest outputs.not_written)");
  }
  const bool aovs = std::any_of(plan.outputs.begin(), plan.outputs.end(), [](OutputKind kind) { return needsAovs(kind); });
  if (aovs && engine.capabilities().mode != OmniMode::Exact)
    notes.push_back(std::string("mode ") + omniModeName(engine.capabilities().mode) +
                    " draws the thesis' method: its colour is approximate, its AOVs and annotations are the exact "
                    "camera's, so they need not sit on the drawn objects (docs/render-settings.md)");
  bool instanceIds = false;
  for (OutputKind kind : plan.outputs) {
    const OutputKindRow& row = outputRow(kind);
    if (row.classFilter)
      plan.cocoClasses = cocoClassIds(idTables(scene), spec.outputs.cocoClasses,
                                      showPath(spec.file) + ": outputs." + row.name + ".classes");
    instanceIds = instanceIds || row.instanceIds;
  }
  if (instanceIds && scene.objects.size() > kMaxInstances)
    throw InputError(showPath(spec.file) + ": outputs.instance: scene has " + std::to_string(scene.objects.size()) +
                     " objects; instance ids are 16-bit (at most " + std::to_string(kMaxInstances) + ")");
  return plan;
}

// Poses where the robot stands outside everything the scene holds (a random region or a list
// beyond the arena): frames that see the scene from outside, if at all. Said, not refused: a view
// from outside may be what is wanted.
void notePosesOutsideTheScene(const DatasetSpec& spec, const Scene& scene, const std::vector<RobotPose>& poses,
                              std::vector<std::string>& notes) {
  const std::optional<FloorRect> extent = sceneFloorExtent(scene);
  if (!extent) return;
  int outside = 0, first = -1;
  for (size_t frame = 0; frame < poses.size(); ++frame)
    if (!extent->contains(poses[frame].x, poses[frame].y)) {
      if (outside++ == 0) first = static_cast<int>(frame);
    }
  if (outside == 0) return;
  const RobotPose& p = poses[static_cast<size_t>(first)];
  notes.push_back(showPath(spec.file) + ": poses: " + std::to_string(outside) + " of " + std::to_string(poses.size()) +
                  " frames stand outside the scene's objects (x " + shortNumber(extent->xMin) + " to " + shortNumber(extent->xMax) +
                  " m, y " + shortNumber(extent->yMin) + " to " + shortNumber(extent->yMax) + " m; the first, frame " +
                  std::to_string(first) + ", at (" + shortNumber(p.x) + ", " + shortNumber(p.y) +
                  ")): they see the scene from outside, if at all");
}

// A camera on a moving robot whose frame (exposure and readout) outlasts the frame interval, as
// no real camera's can: each frame is still rendered whole, the robot driving on along its arc
// past the next frame's pose. Said, not refused: a long exposure may be what is studied.
void noteFramesLongerThanTheInterval(const DatasetSpec& spec, const std::vector<CameraSetup>& setups,
                                     const std::vector<BodyVelocity>& velocities, std::vector<std::string>& notes) {
  if (velocities.size() < 2 || std::all_of(velocities.begin(), velocities.end(), [](const BodyVelocity& v) { return v.still(); }))
    return;
  for (const CameraSetup& setup : setups) {
    const double duration = frameDuration(setup.rig.shutter, setup.rig.imageWidth(), setup.rig.imageHeight());
    if (duration > spec.frameIntervalSeconds)
      notes.push_back("camera " + quote(setup.camera->name) + ": a frame's exposure and readout (" + shortNumber(duration) +
                      " s) outlast frame_interval_s (" + shortNumber(spec.frameIntervalSeconds) +
                      " s): each frame is rendered whole, the robot driving on past the next frame's pose (docs/motion.md)");
  }
}

// Instance ids 1, 2, ... in scene order and class ids 1, 2, ... in name order; 0 = none.
// The manifest's header (docs/dataset-format.md) but for its cameras.
json manifestHeader(const DatasetSpec& spec, const Scene& scene, const Engine& engine, const FrameOutputPlan& plan,
                    const json& notWritten, const IdTables& ids, int totalFrames, const DatasetRunOptions& options,
                    const FrameRange& range) {
  json header;
  header["format"] = kManifestFormat;
  header["spec"] = spec.json;
  // Names, not paths from the working directory: a run from another folder, or a shard on
  // another machine, writes the same manifest and COCO info.
  header["spec_file"] = std::filesystem::path(spec.file).filename().string();
  header["spec_sha256"] = spec.sha256;
  header["tool"] = {{"name", "omnicam"}, {"version", fastRendererVersion()}};
  header["engine"] = {{"name", engine.name()}, {"version", engine.version()}, {"mode", engine.mode()},
                      {"mode_options", engine.modeOptions()}};
  header["scene"] = {{"path", spec.json.value("scene", scene.path)}, {"name", scene.name}, {"sha256", scene.sha256},
                     {"inputs", sceneInputsToJson(scene.inputDigests)}};
  header["settings"] = {{"spp", spec.request.spp}, {"shading", shadingName(spec.request.shading)},
                        {"frame_interval_s", spec.frameIntervalSeconds},
                        {"aov_sampling", "point-sampled at pixel centres (i + 0.5, j + 0.5)"},
                        {"time", "timestamps and poses are each frame's exposure start; with a velocity, AOVs and landmark "
                                 "annotations are taken at each pixel centre's own time (global shutter: mid-exposure; rolling: "
                                 "its line's mid-exposure; docs/motion.md)"},
                        {"depth", "metres along the viewing ray from where it leaves the camera (the effective viewpoint F' of a central "
                                  "rig, the mirror point of a physical one, a lens camera's centre of projection); 0 = no hit or beyond the rim"},
                        {"normal", "world frame, unit, facing the camera; 0 = no hit"}};
  if (const json sampling = randomSamplingRecord(engine.name(), spec.request); !sampling.is_null())
    header["settings"]["path_tracing"] = sampling;
  json written = json::array(), channels = json::object();
  for (OutputKind kind : plan.outputList()) {
    written.push_back(outputName(kind));
    if (plan.layout == DatasetLayout::Multilayer && !isAnnotation(kind)) channels[outputName(kind)] = outputRow(kind).layerChannels;
  }
  header["outputs"] = {{"layout", layoutName(plan.layout)}, {"written", written}, {"not_written", notWritten}};
  if (plan.layout == DatasetLayout::Multilayer) {
    header["outputs"]["channels"] = channels;
    header["outputs"]["compression"] = compressionName(plan.compression);
  }
  for (OutputKind kind : plan.outputs) {
    if (!outputRow(kind).classFilter) continue;  // COCO: its classes, and its keypoints (the landmarks)
    header["outputs"][std::string(outputName(kind)) + "_classes"] = plan.cocoClasses;
    json landmarks = json::array();
    for (const Landmark& l : scene.landmarks) landmarks.push_back(l.name);
    header["outputs"][std::string(outputName(kind)) + "_keypoints"] = landmarks;
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
json manifestCameras(const DatasetPlan& plan, std::vector<StaticFile>& statics) {
  json cameras = json::array();
  for (size_t c = 0; c < plan.setups().size(); ++c) {
    const CameraSetup& setup = plan.setups()[c];
    json files = json::object();
    const auto rigOfFrame = [&](int frame) { return plan.frameRig(frame, c); };
    const auto placementOfFrame = [&](int frame) { return plan.placement(frame, c); };
    for (StaticFile& file :
         staticFiles(setup, plan.poses(), plan.spec().frameIntervalSeconds, rigOfFrame, placementOfFrame, plan.spec().euroc)) {
      files[file.key] = {{"path", file.relative}, {"sha256", sha256OfBytes(file.text)}};
      statics.push_back(std::move(file));
    }
    cameras.push_back({{"name", setup.camera->name},
                       {"rig", rigToJson(setup.rig)},
                       {"mount", {{"x", setup.camera->mount.x}, {"y", setup.camera->mount.y}, {"yaw_deg", setup.camera->mount.yawDeg}}},
                       {"intrinsics", setup.model->describe()},
                       {"files", files}});
  }
  return cameras;
}

// The folders a run writes into: shards/ for a shard, and each camera's folder of every kind.
std::vector<std::string> datasetFolders(const std::vector<CameraSetup>& setups, const FrameOutputPlan& plan, bool sharded) {
  std::vector<std::string> folders;
  if (sharded) folders.push_back("shards");
  for (const CameraSetup& setup : setups) {
    for (OutputKind kind : plan.fileKinds()) folders.push_back(plan.frameFolder(setup.camera->name, kind));
    folders.push_back(setup.camera->name + "/intrinsics");
  }
  return folders;
}

// Each frame's robot velocity: still, the spec's, or the one that drives the frame's pose to the
// next one's in the frame interval (the last frame keeps the one before it).
std::vector<BodyVelocity> frameVelocities(const DatasetSpec& spec, const std::vector<RobotPose>& poses) {
  std::vector<BodyVelocity> out(poses.size(), spec.motion == MotionSource::Constant ? spec.velocity : BodyVelocity{});
  if (spec.motion != MotionSource::BetweenPoses) return out;
  for (size_t i = 0; i + 1 < poses.size(); ++i) {
    out[i] = velocityBetween(poses[i], poses[i + 1], spec.frameIntervalSeconds);
    SettingNames names;
    names.velocity = showPath(spec.file) + ": motion.between_poses: frame " + std::to_string(i);
    checkPlacement(CameraPlacement(poses[i], out[i]), names);
  }
  if (poses.size() > 1) out.back() = out[poses.size() - 2];
  return out;
}

// Frames every frame_interval_s along timed waypoints (trajectory.h), from the first waypoint's
// time on: each frame's pose and the velocity it is driven at.
void sampleTimedWaypoints(const DatasetSpec& spec, const std::vector<RobotPose>& waypoints, std::vector<RobotPose>& poses,
                          std::vector<BodyVelocity>& velocities) {
  const PathTiming& timing = spec.timing;
  if (timing.kind == PathTiming::Kind::Timestamps && timing.timestamps.size() != waypoints.size())
    throw InputError(showPath(spec.file) + ": poses.timestamps_s: has " + std::to_string(timing.timestamps.size()) +
                     " timestamps for the " + std::to_string(waypoints.size()) + " waypoints of path " + quote(spec.pathName));
  const Trajectory trajectory = timing.kind == PathTiming::Kind::Speed
                                    ? Trajectory::atSpeed(waypoints, timing.speed, timing.yawRateDegPerS)
                                    : Trajectory(waypoints, timing.timestamps);
  // A frame exactly at the last waypoint counts, whatever the rounding of the division.
  const double span = (trajectory.end() - trajectory.start()) / spec.frameIntervalSeconds;
  const double count = std::floor(span * (1.0 + 1e-12)) + 1.0;
  const double capped = spec.pathFrames ? std::min<double>(count, spec.pathFrames) : count;
  checkFrameCount(spec, static_cast<size_t>(std::min(capped, 1e15)), "poses (timed waypoints, one frame every frame_interval_s)");
  for (int i = 0; i < static_cast<int>(capped); ++i) {
    const double t = trajectory.start() + frameTimestampSeconds(i, spec.frameIntervalSeconds);
    poses.push_back(trajectory.poseAt(t));
    velocities.push_back(trajectory.velocityAt(t));
    SettingNames names;
    names.velocity = showPath(spec.file) + ": poses.timestamps_s: frame " + std::to_string(i);
    checkPlacement(CameraPlacement(poses.back(), velocities.back()), names);
  }
}

// InputError unless the engine renders every camera (its rig, "camera NAME: …") and every
// frame's motion ("motion: camera NAME: …"), by its capabilities (engine_capabilities.h).
void checkEngineRendersPlan(const DatasetPlan& plan) {
  const std::string file = showPath(plan.spec().file);
  const EngineKind engine = plan.engine().kind();
  // Motion that no camera's shutter sees would change no frame: refused, not ignored.
  bool robotMoves = false;
  for (int frame = 0; frame < static_cast<int>(plan.poses().size()) && !robotMoves; ++frame)
    robotMoves = !plan.placement(frame, 0).still();
  if (plan.spec().motion != MotionSource::Still && robotMoves &&
      std::all_of(plan.setups().begin(), plan.setups().end(), [](const CameraSetup& s) { return s.rig.shutter.instantaneous(); }))
    throw InputError(file + ": motion: every camera's shutter is an instant (no rig.shutter with an exposure_s or a rolling "
                            "readout), so a moving robot renders as a still one: give a rig a shutter (docs/motion.md) or leave motion out");
  for (const CameraSetup& setup : plan.setups()) {
    try {
      checkEngineRenders(engine, setup.rig, CameraPlacement{});
    } catch (const InputError& e) {
      throw InputError(file + ": camera " + quote(setup.camera->name) + ": " + e.what());
    }
  }
  // The field the frames' motion comes from: "motion", or waypoints timed along the poses.
  const PathTiming::Kind timed = plan.spec().timing.kind;
  const std::string motionField = plan.spec().motion != MotionSource::Still ? "motion"
                                  : timed == PathTiming::Kind::Timestamps ? "poses.timestamps_s"
                                                                          : "poses.speed_m_s";
  for (size_t c = 0; c < plan.setups().size(); ++c)
    for (int frame = 0; frame < static_cast<int>(plan.poses().size()); ++frame) {
      try {
        checkEngineRenders(engine, plan.setups()[c].rig, plan.placement(frame, c));
      } catch (const InputError& e) {
        throw InputError(file + ": " + motionField + ": camera " + quote(plan.setups()[c].camera->name) + ": " + e.what());
      }
      if (plan.spec().request.adaptiveSpp > 0 && moving(plan.placement(frame, c), plan.setups()[c].rig))
        throw InputError(file + ": adaptive_spp: not with moving frames (camera " + quote(plan.setups()[c].camera->name) +
                         ", frame " + std::to_string(frame) + ": its shutter is open while the robot moves)");
    }
}

// InputError unless every frame's shaken rig is one the scene format accepts (the manifest
// records it in that format) and the engine renders.
void checkVibratedRigs(const DatasetPlan& plan) {
  // A lens camera's centre of projection is its viewpoint: there is no camera below a mirror to move.
  if (plan.spec().vibration.cameraOffsetMm != std::array<double, 3>{})
    for (const CameraSetup& setup : plan.setups())
      std::visit(Overloaded{[](const MirrorRig&) {},
                            [&](const LensCameraSpec&) {
                              throw InputError(showPath(plan.spec().file) + ": vibration.camera_offset_mm: camera " +
                                               quote(setup.camera->name) +
                                               " is a lens camera (rig.lens), whose centre of projection is its viewpoint: "
                                               "shake it with camera_rotation_deg and rig_tilt_deg");
                            }},
                 setup.rig.kind);
  for (int frame = 0; frame < static_cast<int>(plan.poses().size()); ++frame)
    for (size_t c = 0; c < plan.setups().size(); ++c) {
      const RigSpec rig = plan.frameRig(frame, c);
      try {
        (void)rigFromJson(rigToJson(rig), plan.spec().file, "rig");
        checkEngineRenders(plan.engine().kind(), rig, CameraPlacement{});
      } catch (const InputError& e) {
        throw InputError(showPath(plan.spec().file) + ": vibration: frame " + std::to_string(frame) + ", camera " +
                         quote(plan.setups()[c].camera->name) + ": the shaken rig is refused (" + e.what() +
                         "); lower the amplitudes or move the camera's nominal pose");
      }
    }
}

}  // namespace

RigSpec DatasetPlan::frameRig(int frame, size_t camera) const {
  return vibratedRig(setups_[camera].rig, spec_.vibration, static_cast<uint64_t>(frame), camera);
}

RobotTilt DatasetPlan::robotTilt(int frame) const {
  return vibratedRobotTilt(spec_.robotTiltDeg, spec_.vibration, static_cast<uint64_t>(frame));
}

CameraPlacement DatasetPlan::placement(int frame, size_t camera) const {
  return {poses_[static_cast<size_t>(frame)], velocities_[static_cast<size_t>(frame)], setups_[camera].camera->mount, robotTilt(frame)};
}

namespace {

// The spec's scene; a missing file is the spec's mistake, named by its field with where it was
// looked for (a relative path is the spec's folder's, not the working directory's).
Scene loadSpecScene(const DatasetSpec& spec) {
  std::error_code ec;
  if (!std::filesystem::exists(spec.scene, ec)) {
    const std::string given = spec.json.value("scene", spec.scene);
    throw InputError(showPath(spec.file) + ": scene: no such file " + showPath(spec.scene) +
                     (std::filesystem::path(given).is_absolute() ? "" : " (" + quote(given) + " is relative to the spec's folder)") +
                     bundledSceneHint(given));
  }
  if (std::filesystem::is_directory(spec.scene, ec))
    throw InputError(showPath(spec.file) + ": scene: " + showPath(spec.scene) + " is a folder, not a scene file");
  return loadScene(spec.scene, {spec.allowOutsideFiles});
}

}  // namespace

DatasetPlan::DatasetPlan(const DatasetSpec& spec, const DatasetRunOptions& options)
    : spec_(spec), scene_(loadSpecScene(spec)) {
  setups_ = cameraSetups(spec, scene_, notes_);
  double topHeight = 0.0;
  for (const CameraSetup& setup : setups_) topHeight = std::max(topHeight, setup.rig.height);
  if (spec.timing.kind == PathTiming::Kind::None) {
    poses_ = datasetPoses(spec, scene_, topHeight);
    velocities_ = frameVelocities(spec, poses_);
  } else {
    sampleTimedWaypoints(spec, datasetPoses(spec, scene_, topHeight), poses_, velocities_);
  }
  notePosesOutsideTheScene(spec, scene_, poses_, notes_);
  if (spec.calibration) startCalibrationSequence();
  SettingNames names;
  for (int frame = 0; frame < static_cast<int>(poses_.size()); ++frame)
    for (size_t c = 0; c < setups_.size(); ++c) {
      names.pose = showPath(spec.file) + ": poses: frame " + std::to_string(frame) + ", camera " + quote(setups_[c].camera->name);
      checkPlacement(placement(frame, c), names);
    }
  request_ = spec.request;
  request_.threads = options.threads;
  engine_ = makeEngine(request_, scene_);
  checkEngineRendersPlan(*this);
  if (vibrates()) checkVibratedRigs(*this);
  const int totalFrames = static_cast<int>(poses_.size());
  range_ = frameRange(options, totalFrames);
  json notWritten;
  outputs_ = outputPlan(spec, *engine_, scene_, notWritten, notes_);
  noteFramesLongerThanTheInterval(spec, setups_, velocities_, notes_);
  ids_ = idTables(scene_);
  header_ = manifestHeader(spec, scene_, *engine_, outputs_, notWritten, ids_, totalFrames, options, range_);
  header_["cameras"] = manifestCameras(*this, statics_);
  if (movesTarget()) addCalibrationFiles();
  checkManifestHeaderSize(header_, spec.file);
  folders_ = datasetFolders(setups_, outputs_, range_.sharded);
  if (movesTarget())
    for (const CameraSetup& setup : setups_) folders_.push_back(setup.camera->name + "/calibration");
  if (outputs_.needsLandmarkAnnotations(!scene_.landmarks.empty())) rays_ = std::make_unique<RayScene>(scene_);
}

int64_t DatasetPlan::frameBytes() const {
  int64_t bytes = 0;
  for (const CameraSetup& setup : setups_)
    bytes += FastRenderer::frameBytes(setup.rig.imageWidth(), setup.rig.imageHeight(), spec_.request.spp, setup.model->central(),
                                      spec_.request.denoise && spec_.request.shading == Shading::Path);
  // A calibration sequence's frame renders in a world of its own (frameWorld): the scene's copy,
  // its engine's ray scene and, with landmark annotations, a second one for the landmarks' rays.
  if (movesTarget()) bytes += frameWorldBytes(scene_, rays_ ? 2 : 1);
  return bytes;
}

}  // namespace omnicam
