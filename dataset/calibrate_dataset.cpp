#include "calibrate_dataset.h"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <set>
#include <variant>

#include "calibration_files.h"
#include "calibration_sequence.h"
#include "dataset_reader.h"
#include "errors.h"
#include "make_camera.h"
#include "output_kinds.h"
#include "target_detection.h"

namespace omnicam {

namespace {

// The camera asked for, or the first mirror camera (the first camera when there is none: refused
// below, saying why); InputError naming the dataset's cameras otherwise.
std::string cameraOf(const DatasetReader& reader, const std::string& asked) {
  const std::vector<std::string> cameras = reader.cameras();
  if (asked.empty()) {
    for (const std::string& camera : cameras)
      if (!reader.frames().empty() && std::holds_alternative<MirrorRig>(reader.cameraRig(reader.frames().front(), camera).kind))
        return camera;
    return cameras.front();
  }
  if (std::find(cameras.begin(), cameras.end(), asked) != cameras.end()) return asked;
  std::string names;
  for (const std::string& name : cameras) names += (names.empty() ? "" : ", ") + quote(name);
  throw InputError(showPath(reader.dir()) + ": no camera " + quote(asked) + " (its cameras: " + names + ")");
}

const nlohmann::json& headerCamera(const DatasetReader& reader, const std::string& camera) {
  for (const nlohmann::json& entry : reader.manifest().header.at("cameras"))
    if (entry.at("name") == camera) return entry;
  throw InputError(showPath(reader.dir()) + ": no camera " + quote(camera));
}

// How far each detected corner lies from the exact one of its index (those the frame sees).
void addDetectionErrors(const std::vector<DetectedCorner>& detected, const std::vector<ImagedCorner>& exact,
                        std::vector<double>& errors) {
  for (const DetectedCorner& d : detected)
    for (const ImagedCorner& e : exact)
      if (e.index == d.index) errors.push_back((d.raster - e.raster).norm());
}

}  // namespace

DatasetCalibration calibrateDatasetCamera(const std::string& dir, const DatasetCalibrationOptions& options) {
  const DatasetReader reader(dir);
  const nlohmann::json& header = reader.manifest().header;
  if (!header.contains("calibration") || !header["calibration"].is_object())
    throw InputError(showPath(dir) + ": not a calibration sequence (its spec has no \"calibration\"; docs/calibration.md)");
  DatasetCalibration out;
  out.camera = cameraOf(reader, options.camera);
  if (reader.frames().empty()) throw InputError(showPath(dir) + ": no frame is finished yet");
  const RigSpec rig = reader.cameraRig(reader.frames().front(), out.camera);
  if (!std::holds_alternative<MirrorRig>(rig.kind))
    throw InputError(showPath(dir) + ": camera " + quote(out.camera) +
                     " is a lens camera: cv::omnidir's unified model is fitted here to mirror cameras (its corners for "
                     "cv::calibrateCamera or cv::fisheye are in " + out.camera + "/calibration/opencv_corners.yml)");
  if (!options.exactCorners && !header.value("complete", false))
    throw InputError(showPath(dir) + ": the sequence is not finished (" + std::to_string(reader.frames().size()) + " of " +
                     std::to_string(header.value("frame_count", 0)) + " frames): corners are detected in every frame's image");
  const std::string calibrationFolder = (std::filesystem::path(dir) / out.camera / "calibration").string();
  const TargetPattern pattern = targetPatternFromKalibrYaml(reader.fileBytes(std::nullopt, out.camera, "kalibr_target", options.checkHashes),
                                                            calibrationFolder + "/target.yaml");
  const std::vector<Vec3> targetPoints = targetCorners(pattern);
  const std::vector<CornersFrame> frames =
      cornersFramesFromJson(reader.fileBytes(std::nullopt, out.camera, "corners", options.checkHashes), calibrationFolder + "/corners.json",
                            static_cast<int>(targetPoints.size()), rig.imageWidth(), rig.imageHeight());
  // One view per frame of the sequence: a corners.json of more (forged, or another sequence's) would
  // weigh frames twice and cost the fit memory by the square of its views.
  const int64_t frameCount = header.value("frame_count", int64_t{0});
  std::set<int> listed;
  for (const CornersFrame& frame : frames) {
    if (frame.frame >= frameCount)
      throw InputError(showPath(calibrationFolder + "/corners.json") + ": frame " + std::to_string(frame.frame) +
                       " is beyond the sequence's " + std::to_string(frameCount) + " frames");
    if (!listed.insert(frame.frame).second)
      throw InputError(showPath(calibrationFolder + "/corners.json") + ": frame " + std::to_string(frame.frame) + " is listed twice");
  }
  const nlohmann::json& target = header["calibration"].contains("target") ? header["calibration"]["target"] : nlohmann::json();
  out.target = target.is_string() ? target.get<std::string>() : "";
  out.frames = static_cast<int>(frames.size());
  out.truth = headerCamera(reader, out.camera).value("intrinsics", nlohmann::json());
  if (!out.truth.is_object() || !out.truth.contains("model"))
    throw InputError(showPath(reader.dir()) + "/manifest.json: camera " + quote(out.camera) + ": intrinsics: must be the camera's model (an object)");
  out.width = rig.imageWidth(), out.height = rig.imageHeight();

  std::vector<CalibrationView> views;
  std::vector<Rigid> viewpointFromTarget;
  std::vector<double> detectionErrors;
  for (size_t f = 0; f < frames.size(); ++f) {
    const CornersFrame& frame = frames[f];
    std::vector<DetectedCorner> corners;
    if (options.exactCorners) {
      for (const ImagedCorner& c : frame.seen) corners.push_back({c.index, c.raster});
    } else {
      const DecodedOutput colour = reader.readOutput(frame.frame, out.camera, kColourOutput, options.checkHashes);
      corners = detectTarget(*colour.image, pattern, ImageHandedness::Mirrored);
      out.cornersDetected += static_cast<int>(corners.size());
      addDetectionErrors(corners, frame.seen, detectionErrors);
    }
    if (corners.size() >= 4) {
      views.push_back(calibrationView(targetPoints, corners));
      viewpointFromTarget.push_back(frame.viewpointFromTarget);
      out.corners += static_cast<int>(corners.size());
    }
    if (options.progress) options.progress(static_cast<int>(f) + 1, out.frames);
  }
  if (!detectionErrors.empty()) {
    std::sort(detectionErrors.begin(), detectionErrors.end());
    out.detectionMedianPx = detectionErrors[detectionErrors.size() / 2];
    out.detectionMaxPx = detectionErrors.back();
  }
  out.views = static_cast<int>(views.size());
  if (views.size() < 3) {
    out.fit.failure = "fewer than 3 frames show the 4 corners a view needs (" + std::to_string(views.size()) + ")";
    return out;
  }
  OmnidirOptions fitOptions;
  fitOptions.fixDistortion = options.fixDistortion;
  out.fit = calibrateOmnidir(views, out.width, out.height, fitOptions);
  if (!out.fit.converged) return out;
  const CentralApproximation model = calibratedModel(out.fit, viewpointFromTarget);
  const PixelRays rays = pixelRays(*makeCamera(rig));
  for (double distance : options.heldOutDistancesM) out.heldOut.push_back(heldOutError(rays, model, distance));
  return out;
}

}  // namespace omnicam
