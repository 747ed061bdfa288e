#include "calibration_sequence.h"

#include <cmath>

#include "errors.h"
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

}  // namespace omnicam
