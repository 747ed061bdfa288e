// The calibration sequence's parts of a dataset plan (docs/calibration.md, "Calibration
// sequences"): the target and its pose in every frame, every camera's calibration files, a frame's
// own world with the target where the frame holds it, and what that world costs in memory.
#include <cctype>
#include <map>

#include "calibration_files.h"
#include "calibration_sequence.h"
#include "dataset_folder.h"
#include "dataset_plan.h"
#include "errors.h"
#include "intrinsics_files.h"
#include "manifest.h"
#include "memory_budget.h"
#include "rosbag_file.h"
#include "sha256.h"
#include "triangulate.h"

namespace omnicam {

using nlohmann::json;

namespace {

// A calibration sequence's bag: topics ROS accepts, a bag the dataset's reader reads back, memory
// to write it in, and the writer's Python modules, all before anything renders.
void checkRosbagOutputs(const DatasetPlan& plan, size_t frames) {
  const std::string file = showPath(plan.spec().file);
  int64_t bytes = 0, largestImage = 0;
  for (const CameraSetup& setup : plan.setups()) {
    const std::string& name = setup.camera->name;
    // A ROS graph name: a letter, then letters, digits and '_'.
    if (!std::isalpha(static_cast<unsigned char>(name[0])) ||
        name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") != std::string::npos)
      throw InputError(file + ": calibration.rosbag: camera " + quote(name) +
                       ": its topic /<camera>/image_raw needs a name ROS accepts (a letter, then letters, digits and '_')");
    const int64_t image = int64_t{setup.rig.imageWidth()} * setup.rig.imageHeight() * 3;
    bytes += static_cast<int64_t>(frames) * image;
    largestImage = std::max(largestImage, image);
  }
  // Each image's message adds a few hundred bytes of headers and index.
  if (bytes + static_cast<int64_t>(frames * plan.setups().size()) * 1024 > kMaxDatasetFileBytes)
    throw InputError(file + ": calibration.rosbag: the bag would hold " + std::to_string(bytes >> 20) +
                     " MiB of images (a dataset file is at most " + std::to_string(kMaxDatasetFileBytes >> 20) +
                     " MiB: fewer poses, cameras or a smaller size)");
  // Streamed (rosbag_file.h): an image at a time, its PNG decoded beside it and its copy in the
  // writer; the bag's size does not count.
  requireMemory(3 * largestImage, "writing the ROS bag");
  checkImageBagWriter();
}

}  // namespace

// A calibration sequence: the target the spec names, the board's pose of every frame, and the
// robot standing at its one pose in each of them.
void DatasetPlan::startCalibrationSequence() {
  const CalibrationSequenceSpec& cal = *spec_.calibration;
  const std::string file = showPath(spec_.file);
  calibration_.emplace();
  calibration_->target = findCalibrationTarget(scene_, cal.target);
  if (calibration_->target < 0) {
    std::string names;
    for (const CalibrationTarget& t : scene_.calibrationTargets) names += (names.empty() ? "" : ", ") + quote(t.name);
    throw InputError(file + ": calibration.target: the scene has no calibration target " + quote(cal.target) +
                     (names.empty() ? std::string(" (it has none)") : " (it has " + names + ")"));
  }
  const CalibrationTarget& target = scene_.calibrationTargets[static_cast<size_t>(calibration_->target)];
  // Every camera's calibration files include Kalibr's target.yaml: a target it cannot describe
  // is refused before anything renders.
  if (const std::string problem = kalibrTargetProblem(target.pattern); !problem.empty())
    throw InputError(file + ": calibration.target: " + quote(cal.target) + " (a target of " + showPath(spec_.scene) +
                     ") cannot be Kalibr's target.yaml: " + problem);
  const size_t corners = targetCorners(target.pattern).size();
  if (cal.random && static_cast<size_t>(cal.random->minSeenCorners) > corners)
    throw InputError(file + ": calibration.poses.random.min_seen_corners: the target " + quote(target.name) + " has only " +
                     std::to_string(corners) + " corners (got " + std::to_string(cal.random->minSeenCorners) + ")");
  if (cal.rosbag) checkRosbagOutputs(*this, cal.random ? static_cast<size_t>(cal.random->count) : cal.listed.size());
  // The robot stands at its one pose: the first camera's viewpoint is the same every frame.
  const Rigid worldFromViewpoint = placement(0, 0).worldFromViewpoint(setups_.front().rig);
  try {
    calibration_->viewpointFromTarget = sequenceBoardPoses(cal, *setups_.front().model, worldFromViewpoint, target);
  } catch (const InputError& e) {
    throw InputError(file + ": calibration.poses." + e.what());
  }
  const size_t frames = calibration_->viewpointFromTarget.size();
  poses_.assign(frames, poses_.front());
  velocities_.assign(frames, BodyVelocity{});
  for (size_t f = 0; f < frames; ++f)
    calibration_->worldFromTarget.push_back(placement(static_cast<int>(f), 0).worldFromViewpoint(setups_.front().rig) *
                                   calibration_->viewpointFromTarget[f]);
}

// Every camera's calibration files (docs/calibration.md, "Calibration sequences"): Kalibr's target
// YAML, each frame's exact corners with their sight, and the seen ones as OpenCV's corner lists.
void DatasetPlan::addCalibrationFiles() {
  const CalibrationTarget& target = scene_.calibrationTargets[static_cast<size_t>(calibration_->target)];
  const std::vector<Vec3> targetPoints = targetCorners(target.pattern);
  const int frames = static_cast<int>(poses_.size());
  std::vector<json> cornerFrames(setups_.size(), json::array());
  std::vector<std::vector<CornerListImage>> lists(setups_.size());
  for (int f = 0; f < frames; ++f) {
    const std::unique_ptr<FrameWorld> world = frameWorld(f, /*withEngine=*/false, /*withRays=*/true);
    const CalibrationTarget& moved = world->scene.calibrationTargets[static_cast<size_t>(calibration_->target)];
    // A listed pose no camera sees four corners of (what a view needs) is told, camera by camera.
    std::string sightsByCamera;
    bool calibrates = false;
    for (size_t c = 0; c < setups_.size(); ++c) {
      const Rigid worldFromViewpoint = placement(f, c).worldFromViewpoint(setups_[c].rig);
      const std::vector<ImagedCorner> corners = imagedCorners(*setups_[c].model, worldFromViewpoint, world->rays.get(), moved);
      std::map<std::string, int> sights;
      for (const ImagedCorner& corner : corners) ++sights[cornerSightName(corner.sight)];
      std::string counts;
      for (const auto& [sight, count] : sights) counts += (counts.empty() ? "" : ", ") + std::to_string(count) + " " + sight;
      sightsByCamera += (sightsByCamera.empty() ? "" : "; ") + setups_[c].camera->name + ": " + counts;
      cornerFrames[c].push_back(cornersFrameJson(f, worldFromViewpoint.inverse() * moved.worldFromTarget, corners));
      // The frame's image: its colour file, or its multilayer frame.
      const OutputKind imageKind = outputs_.layout == DatasetLayout::Multilayer ? OutputKind::Multilayer : kColourOutput;
      CornerListImage image{outputs_.framePath(setups_[c].camera->name, imageKind, f), {}};
      for (const ImagedCorner& corner : corners)
        if (corner.sight == CornerSight::Seen) {
          image.view.targetPoints.push_back(targetPoints[static_cast<size_t>(corner.index)]);
          image.view.raster.push_back(corner.raster);
        }
      // OpenCV's calibrations need four points of a view.
      calibrates = calibrates || image.view.raster.size() >= 4;
      if (image.view.raster.size() >= 4) lists[c].push_back(std::move(image));
    }
    if (!calibrates && !spec_.calibration->random)
      notes_.push_back(showPath(spec_.file) + ": calibration.poses.list[" + std::to_string(f) +
                       "]: no camera sees the 4 corners of the board a view needs (" + sightsByCamera + "): the frame calibrates nothing");
  }
  const std::string kalibr = kalibrTargetYaml(target.pattern);
  for (size_t c = 0; c < setups_.size(); ++c) {
    const std::string& name = setups_[c].camera->name;
    json& files = header_["cameras"][c]["files"];
    const json corners = {{"camera", name},
                          {"target", target.name},
                          {"convention", "raster: omnicam's (pixel centres at i + 0.5); opencv: centres at integers"},
                          {"frames", cornerFrames[c]}};
    for (StaticFile file : {StaticFile{"kalibr_target", name + "/calibration/target.yaml", kalibr},
                            StaticFile{"corners", name + "/calibration/corners.json", corners.dump() + "\n"},
                            StaticFile{"opencv_corners", name + "/calibration/opencv_corners.yml", openCvCornerLists(lists[c], std::holds_alternative<MirrorRig>(setups_[c].rig.kind))}}) {
      files[file.key] = {{"path", file.relative}, {"sha256", sha256OfBytes(file.text)}};
      statics_.push_back(std::move(file));
    }
  }
  const CalibrationSequenceSpec& cal = *spec_.calibration;
  header_["calibration"] = {{"target", target.name},
                                {"poses", cal.random ? "random" : "list"},
                                {"rosbag", cal.rosbag}};
  if (cal.rosbag) {
    // The bag's cameras for Kalibr, as the bag shows them (calibration_bag.h).
    std::vector<KalibrChainCamera> chain;
    for (size_t c = 0; c < setups_.size(); ++c)
      chain.push_back({setups_[c].camera->name, setups_[c].model.get(), worldFromModelCamera(placement(0, c), *setups_[c].model)});
    StaticFile camchain{"kalibr_camchain", kKalibrCamchainPath, ""};
    try {
      camchain.text = kalibrCamchainYaml(chain);
    } catch (const InputError& e) {
      throw InputError(showPath(spec_.file) + ": calibration.rosbag: " + e.what());
    }
    header_["calibration"]["files"][camchain.key] = {{"path", camchain.relative}, {"sha256", sha256OfBytes(camchain.text)}};
    statics_.push_back(std::move(camchain));
  }
}

std::unique_ptr<FrameWorld> DatasetPlan::frameWorld(int frame, bool withEngine, bool withRays) const {
  auto world = std::make_unique<FrameWorld>();
  world->scene = scene_;
  placeCalibrationTarget(world->scene, calibration_->target, calibration_->worldFromTarget.at(static_cast<size_t>(frame)));
  if (withEngine) world->engine = makeEngine(request_, world->scene);
  if (withRays) world->rays = std::make_unique<RayScene>(world->scene);
  return world;
}

int64_t frameWorldBytes(const Scene& scene, int rayScenes) {
  // The copy: every object (a mesh with its arrays; textures are shared, not copied).
  int64_t copy = static_cast<int64_t>(sizeof(Scene)), triangles = 0, vertices = 0, curved = 0;
  for (const SceneObject& object : scene.objects) {
    copy += static_cast<int64_t>(sizeof(SceneObject) + object.name.size() + object.semanticClass.size());
    if (const auto* mesh = std::get_if<Mesh>(&object.shape)) {
      copy += static_cast<int64_t>(mesh->vertices.size() * sizeof(Vec3) + mesh->triangles.size() * sizeof(Eigen::Vector3i) +
                                   mesh->uvs.size() * sizeof(Eigen::Vector2d));
      triangles += static_cast<int64_t>(mesh->triangles.size()), vertices += static_cast<int64_t>(mesh->vertices.size());
    } else if (const std::optional<TriangleMesh> planar = triangulatePlanar(object.shape)) {
      triangles += static_cast<int64_t>(planar->triangles.size()), vertices += static_cast<int64_t>(planar->vertices.size());
    } else {
      ++curved;
    }
  }
  // A ray scene (ray_scene.h) per triangle: Embree's index buffer and its BVH, taken as 128 bytes
  // (more than Embree's BVH4 needs), and RayScene's own vertex indices; per vertex Embree's float
  // vertex, RayScene's double copy (hits are worked out again in double) and its float UV; a
  // curved shape is one small user geometry.
  constexpr int64_t kBvhBytesPerTriangle = 128, kCurvedShapeBytes = 512;
  const int64_t rayScene = triangles * (int64_t{sizeof(Eigen::Vector3i)} * 2 + kBvhBytesPerTriangle) +
                           vertices * (int64_t{sizeof(float)} * 4 + int64_t{sizeof(Vec3)} + int64_t{sizeof(Eigen::Vector2f)}) + curved * kCurvedShapeBytes;
  return copy + rayScenes * rayScene;
}

}  // namespace omnicam
