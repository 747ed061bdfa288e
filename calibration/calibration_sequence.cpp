#include "calibration_sequence.h"

#include <cmath>

#include "errors.h"

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

std::vector<Rigid> sequenceBoardPoses(const CalibrationSequenceSpec& spec, const Camera& camera, const TargetPattern& pattern) {
  if (!spec.random) return spec.listed;
  return boardPoses(camera, Rigid::Identity(), pattern, *spec.random);
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
