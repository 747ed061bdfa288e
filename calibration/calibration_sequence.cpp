#include "calibration_sequence.h"

#include <cmath>
#include <limits>

#include "errors.h"
#include "input_limits.h"
#include "json_text.h"
#include "number_format.h"

namespace omnicam {

int findCalibrationTarget(const Scene& scene, const std::string& name) {
  for (size_t t = 0; t < scene.calibrationTargets.size(); ++t)
    if (scene.calibrationTargets[t].name == name) return static_cast<int>(t);
  return -1;
}

void placeCalibrationTarget(Scene& scene, int target, const Rigid& worldFromTarget) {
  CalibrationTarget& t = scene.calibrationTargets.at(static_cast<size_t>(target));
  // The board moves with the target: newWorld ← target ← oldWorld.
  const Rigid newFromOld = worldFromTarget * t.worldFromTarget.inverse();
  Quad& board = std::get<Quad>(scene.objects.at(static_cast<size_t>(t.object)).shape);
  board = Quad{newFromOld * board.origin, newFromOld.linear() * board.edgeU, newFromOld.linear() * board.edgeV};
  t.worldFromTarget = worldFromTarget;
}

std::vector<Rigid> sequenceBoardPoses(const CalibrationSequenceSpec& spec, const Camera& camera, const Rigid& worldFromViewpoint,
                                      const CalibrationTarget& target) {
  // The floor the robot stands on (z = 0 in the world): no board goes through it, as in the study,
  // and here the whole board, its white margin included (the frames render it).
  constexpr double kFloorZ = 0.0;
  const TargetPattern& pattern = target.pattern;
  const Rigid viewpointFromWorld = worldFromViewpoint.inverse();
  if (spec.random) {
    BoardPoseOptions options = *spec.random;
    options.floorZ = kFloorZ;
    options.boardMarginM = target.margin;
    options.minBoardDistanceM = limits::kMinBoardDistanceM;
    std::vector<Rigid> poses;
    try {
      poses = boardPoses(camera, worldFromViewpoint, pattern, options);
    } catch (const InputError& e) {
      throw InputError(std::string("random: ") + e.what());
    }
    for (Rigid& pose : poses) pose = viewpointFromWorld * pose;
    return poses;
  }
  const std::vector<Vec3> outline = floorTestPoints(pattern, target.margin);
  for (size_t i = 0; i < spec.listed.size(); ++i) {
    if (!boardClearsFloor(worldFromViewpoint * spec.listed[i], outline, kFloorZ))
      throw InputError("list[" + std::to_string(i) + "]: the board goes through the floor (its every corner, margin included, must be " +
                       std::to_string(static_cast<int>(kBoardFloorClearanceM * 100)) + " cm above it)");
    if (const double nearest = boardDistance(spec.listed[i], outline, Vec3::Zero()); nearest < limits::kMinBoardDistanceM)
      throw InputError("list[" + std::to_string(i) + "]: the board comes within " + shortNumber(nearest) +
                       " m of the viewpoint (its nearest point, margin included; every point must be " + shortNumber(limits::kMinBoardDistanceM) +
                       " m away: nearer, it reaches into the mirror)");
  }
  return spec.listed;
}

namespace {

nlohmann::json rigidJson(const Rigid& r) {
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i < 3; ++i)
    rows.push_back({r.linear()(i, 0), r.linear()(i, 1), r.linear()(i, 2), r.translation()(i)});
  return rows;
}

}  // namespace

nlohmann::json cornersFrameJson(int frame, const Rigid& viewpointFromTarget, const std::vector<ImagedCorner>& corners) {
  nlohmann::json list = nlohmann::json::array();
  int seen = 0;
  for (const ImagedCorner& c : corners) {
    nlohmann::json entry = {{"index", c.index}, {"sight", cornerSightName(c.sight)}};
    // omnicam raster (pixel centres at +0.5) and OpenCV's (centres at integers).
    if (std::isfinite(c.raster.x()))
      entry["raster"] = {c.raster.x(), c.raster.y()}, entry["opencv"] = {c.raster.x() - 0.5, c.raster.y() - 0.5};
    seen += c.sight == CornerSight::Seen;
    list.push_back(std::move(entry));
  }
  return {{"frame", frame}, {"viewpoint_from_target", rigidJson(viewpointFromTarget)}, {"seen", seen}, {"corners", list}};
}

std::vector<CornersFrame> cornersFramesFromJson(const std::string& text, const std::string& source, int corners, int width,
                                                int height) {
  const nlohmann::json root = parseJsonText(text, source);
  const auto fail = [&](const std::string& field, const std::string& what) -> void {
    throw InputError(showPath(source) + ": " + field + ": " + what);
  };
  const auto number = [&](const nlohmann::json& v, const std::string& field, double most) {
    if (!v.is_number() || !(std::abs(v.get<double>()) <= most)) fail(field, "must be a finite number within ±" + shortNumber(most));
    return v.get<double>();
  };
  if (!root.is_object() || !root.contains("frames") || !root["frames"].is_array()) fail("frames", "must be an array");
  std::vector<CornersFrame> frames;
  for (size_t f = 0; f < root["frames"].size(); ++f) {
    const nlohmann::json& entry = root["frames"][f];
    const std::string where = "frames[" + std::to_string(f) + "]";
    if (!entry.is_object()) fail(where, "must be an object");
    CornersFrame frame;
    if (!entry.contains("frame") || !entry["frame"].is_number_integer() || entry["frame"].get<int64_t>() < 0 ||
        entry["frame"].get<int64_t>() > std::numeric_limits<int>::max())
      fail(where + ".frame", "must be a frame index");
    frame.frame = entry["frame"].get<int>();
    const nlohmann::json& pose = entry.contains("viewpoint_from_target") ? entry["viewpoint_from_target"] : nlohmann::json();
    if (!pose.is_array() || pose.size() != 3) fail(where + ".viewpoint_from_target", "must be 3 rows of 4 numbers");
    for (int i = 0; i < 3; ++i) {
      if (!pose[i].is_array() || pose[i].size() != 4) fail(where + ".viewpoint_from_target", "must be 3 rows of 4 numbers");
      for (int j = 0; j < 4; ++j) {
        const double v = number(pose[i][j], where + ".viewpoint_from_target", j < 3 ? 1.0 + 1e-9 : limits::kMaxWorldCoordinate);
        if (j < 3) frame.viewpointFromTarget.linear()(i, j) = v;
        else frame.viewpointFromTarget.translation()(i) = v;
      }
    }
    const Eigen::Matrix3d& r = frame.viewpointFromTarget.linear();
    if (!(r * r.transpose()).isApprox(Eigen::Matrix3d::Identity(), 1e-6) || r.determinant() < 0.0)
      fail(where + ".viewpoint_from_target", "its 3 × 3 part must be a rotation");
    if (!entry.contains("corners") || !entry["corners"].is_array()) fail(where + ".corners", "must be an array");
    std::vector<bool> listed(static_cast<size_t>(corners), false);
    for (size_t k = 0; k < entry["corners"].size(); ++k) {
      const nlohmann::json& c = entry["corners"][k];
      const std::string at = where + ".corners[" + std::to_string(k) + "]";
      if (!c.is_object() || !c.contains("index") || !c["index"].is_number_integer() || c["index"].get<int64_t>() < 0 ||
          c["index"].get<int64_t>() >= corners)
        fail(at + ".index", "must be a corner of the target (0 to " + std::to_string(corners - 1) + ")");
      const int index = c["index"].get<int>();
      if (listed[static_cast<size_t>(index)]) fail(at + ".index", "corner " + std::to_string(index) + " listed twice");
      listed[static_cast<size_t>(index)] = true;
      const auto named = [&c](CornerSight sight) { return c.contains("sight") && c["sight"] == cornerSightName(sight); };
      if (!named(CornerSight::Seen) && !named(CornerSight::BeyondRim) && !named(CornerSight::OutsideImage) &&
          !named(CornerSight::BackFacing) && !named(CornerSight::Occluded))
        fail(at + ".sight", "must be seen, beyond_rim, outside_image, back_facing or occluded");
      if (!named(CornerSight::Seen)) continue;
      if (!c.contains("raster") || !c["raster"].is_array() || c["raster"].size() != 2) fail(at + ".raster", "must be [x, y]");
      ImagedCorner corner;
      corner.index = index;
      corner.sight = CornerSight::Seen;
      corner.raster = {number(c["raster"][0], at + ".raster", 1e6), number(c["raster"][1], at + ".raster", 1e6)};
      if (!(corner.raster.x() >= 0.0 && corner.raster.x() <= width && corner.raster.y() >= 0.0 && corner.raster.y() <= height))
        fail(at + ".raster", "a seen corner must lie in the " + std::to_string(width) + " x " + std::to_string(height) + " image");
      frame.seen.push_back(corner);
    }
    frames.push_back(std::move(frame));
  }
  return frames;
}

}  // namespace omnicam
