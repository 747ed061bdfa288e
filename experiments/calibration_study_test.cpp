// The calibration study's triangulation in closed form: an exact model triangulates every point
// where it is; the same model moved by δ (its rays parallel to the true ones, from δ off)
// triangulates every point exactly δ off.
#include "calibration_study.h"

#include <gtest/gtest.h>

#include "central_fit.h"
#include "make_camera.h"

namespace omnicam {
namespace {

TEST(CalibrationStudy, TriangulationFromAShiftedExactModelErrsByTheShift) {
  RigSpec rig;
  const std::shared_ptr<const Camera> camera = makeCamera(rig);
  const CentralApproximation exact = fitCentralApproximation(*camera);
  const TriangulationError none = triangulationError(*camera, exact, 1.0, 0.25);
  EXPECT_GT(none.points, 1000);
  EXPECT_LT(none.p90Mm, 1e-6);
  CentralApproximation shifted = exact;
  shifted.viewpoint = Vec3(0.0, 0.003, 0.001);
  shifted.cameraFromViewpoint.translation() = -(exact.cameraFromViewpoint.linear() * shifted.viewpoint);
  const TriangulationError moved = triangulationError(*camera, shifted, 1.0, 0.25);
  EXPECT_EQ(moved.points, none.points);
  EXPECT_NEAR(moved.medianMm, 1e3 * shifted.viewpoint.norm(), 1e-6);
  EXPECT_NEAR(moved.p90Mm, 1e3 * shifted.viewpoint.norm(), 1e-6);
}

// A run without figures links to none: each figure's place says it was not drawn.
TEST(CalibrationStudy, TheReportOfARunWithoutFiguresLinksToNone) {
  const CalibrationStudyResults results;
  const CalibrationStudyOptions options = CalibrationStudyOptions::quick();
  const std::string with = calibrationStudyMarkdown(results, options, "cmd");
  EXPECT_NE(with.find("](figures/calibration_study_error.svg)"), std::string::npos);
  EXPECT_NE(with.find("](figures/calibration_study_residuals.png)"), std::string::npos);
  const std::string without = calibrationStudyMarkdown(results, options, "cmd", false);
  EXPECT_EQ(without.find("figures/"), std::string::npos) << without;
  EXPECT_NE(without.find("(held-out error against misalignment: not drawn in this run)"), std::string::npos);
  EXPECT_NE(without.find("(residual maps: not drawn in this run)"), std::string::npos);
}

}  // namespace
}  // namespace omnicam
