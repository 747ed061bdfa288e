// Calibration targets as the camera images them, against the detectors a calibration would use:
// exact corners (the camera's own project) and OpenCV's and AprilTag's corners in noise-free
// 720-px renders agree to within the detectors' own accuracy, on the ideal and a misaligned rig;
// hidden corners are told apart by why they are hidden.
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <opencv2/ccalib/omnidir.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "fast_renderer.h"
#include "board_poses.h"
#include "central_fit.h"
#include "imaged_corners.h"
#include "omnidir_fit.h"
#include "make_camera.h"
#include "memory_budget.h"
#include "placement.h"
#include "scene_loader.h"
#include "target_detection.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;

// A floor, an AprilGrid in front of the robot and a checkerboard behind it; `extra` more objects,
// `rig` the rig's JSON.
Scene targetScene(const std::string& extra, const std::string& rig = "{}") {
  const fs::path dir = fs::temp_directory_path() / ("omnicam_calibration_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "scene.json") << R"({"format": "omnicam-scene/1", "rig": )" << rig << R"(,
    "materials": {"floor": {"color": [0.2, 0.5, 0.2]}, "grey": {"color": 0.4}},
    "objects": [{"name": "floor", "type": "quad", "material": "floor", "origin": [-3, -3, 0], "edge_u": [6, 0, 0], "edge_v": [0, 6, 0]},
      {"name": "grid", "type": "calibration_target", "origin": [0.6, 0.35, 0.1], "x_axis": [0, -1, 0], "y_axis": [0, 0, 1],
       "pattern": {"kind": "aprilgrid", "tag_rows": 6, "tag_columns": 6, "tag_size": 0.088, "tag_spacing": 0.3}},
      {"name": "chess", "type": "calibration_target", "origin": [-0.8, -0.2, 0.2], "x_axis": [0, 1, 0], "y_axis": [0, 0, 1],
       "pattern": {"kind": "checkerboard", "rows": 7, "columns": 10, "square": 0.05}})"
                                    << extra << "]}";
  Scene scene = loadScene((dir / "scene.json").string());
  fs::remove_all(dir);
  return scene;
}

struct Agreement {
  size_t detected = 0, seen = 0;
  double median = 0.0, p99 = 0.0, worst = 0.0;
};

// Renders `scene` at 720 px (16 spp, unlit: no noise) from `pose` and compares every corner each
// detector finds with the exact one of the same index; per target, in scene order.
std::vector<Agreement> agreement(const Scene& scene, const RobotPose& pose, const std::string& label) {
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().imageSize = 720;
  settings.spp = 16;
  const FastRenderer renderer(scene);
  const ImageRGBA image = renderer.render(pose, settings);
  const std::shared_ptr<const Camera> camera = makeCamera(settings.rig);
  const Rigid worldFromViewpoint = CameraPlacement(pose).worldFromViewpoint(settings.rig);
  std::vector<Agreement> out;
  for (const CalibrationTarget& target : scene.calibrationTargets) {
    Agreement a;
    const std::vector<ImagedCorner> exact = imagedCorners(*camera, worldFromViewpoint, &renderer.rays(), target);
    a.seen = static_cast<size_t>(std::count_if(exact.begin(), exact.end(), [](const ImagedCorner& c) { return c.sight == CornerSight::Seen; }));
    const std::vector<DetectedCorner> found = detectTarget(image, target.pattern, ImageHandedness::Mirrored);
    a.detected = found.size();
    std::vector<double> errors;
    for (const DetectedCorner& d : found) {
      const ImagedCorner& e = exact[static_cast<size_t>(d.index)];
      EXPECT_EQ(e.sight, CornerSight::Seen) << label << " " << target.name << " corner " << d.index;
      errors.push_back((d.raster - e.raster).norm());
    }
    std::sort(errors.begin(), errors.end());
    if (!errors.empty()) {
      a.median = errors[errors.size() / 2];
      a.p99 = errors[std::min(errors.size() - 1, static_cast<size_t>(0.99 * errors.size()))];
      a.worst = errors.back();
    }
    std::printf("%s, %s: %zu corners detected of %zu seen; detected - exact: median %.3f px, 99th percentile %.3f px, worst %.3f px\n",
                label.c_str(), target.name.c_str(), a.detected, a.seen, a.median, a.p99, a.worst);
    out.push_back(a);
  }
  return out;
}

void expectAgreement(const std::vector<Agreement>& a) {
  ASSERT_EQ(a.size(), 2u);
  EXPECT_GE(a[0].detected, 100u) << "AprilGrid: most of its 144 corners";  // measured 112, 116
  EXPECT_EQ(a[1].detected, 54u) << "the whole checkerboard";
  for (const Agreement& t : a) {
    EXPECT_LT(t.median, 0.1);
    EXPECT_LT(t.p99, 0.5);
  }
}

TEST(CalibrationTargets, ExactCornersAgreeWithOpenCvAndAprilTagOnTheIdealRig) {
  expectAgreement(agreement(targetScene(""), {0.0, 0.0, 10.0}, "ideal rig"));
}

TEST(CalibrationTargets, ExactCornersAgreeWithTheDetectorsOnAMisalignedRig) {
  // Non-central: the pinhole 2 mm off the axis, tilted 1°; project() traces the exact mirror.
  expectAgreement(
      agreement(targetScene("", R"({"camera": {"offset_mm": [2, 0, 0], "rotation_deg": [1, 0, 0]}})"), {0.0, 0.0, 10.0}, "misaligned rig"));
}

// The printed AprilGrid itself (its texture, magnified 4× nearest, seen straight on): AprilTag
// decodes every tag and puts its corners where the target says they are.
TEST(CalibrationTargets, AprilTagDecodesEveryPrintedTagAtItsCorners) {
  const AprilGrid grid{4, 5, 0.05, 0.3, 3};
  const TargetBoard board = targetBoard(grid, 0.01, 0.03f, 0.85f);
  const Texture& texture = *board.texture;
  constexpr int kMagnify = 4;
  ImageRGBA image(texture.width() * kMagnify, texture.height() * kMagnify);
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i) {
      const float* t = &texture.rgbLinear()[(static_cast<size_t>(j / kMagnify) * texture.width() + i / kMagnify) * 3];
      float* p = image.at(i, j);
      p[0] = t[0], p[1] = t[1], p[2] = t[2], p[3] = 1.0f;
    }
  const std::vector<DetectedCorner> found = detectAprilGrid(image, grid, ImageHandedness::Direct);
  ASSERT_EQ(found.size(), 80u) << "every corner of the 20 tags";
  const std::vector<Vec3> corners = targetCorners(grid);
  const double texel = board.edgeU.x() / texture.width();
  double worst = 0.0;
  for (const DetectedCorner& d : found) {
    const Vec3& c = corners[static_cast<size_t>(d.index)];
    // omnicam raster: the image's top-left corner at (0, 0), y down.
    const Vec2 expected((c.x() - board.origin.x()) / texel * kMagnify, (board.origin.y() + board.edgeV.y() - c.y()) / texel * kMagnify);
    worst = std::max(worst, (d.raster - expected).norm());
  }
  std::printf("printed AprilGrid: AprilTag's corners at most %.4f px from the target's (bits of %d px)\n", worst, kMagnify * kTargetTexelsPerCell);
  EXPECT_LT(worst, 0.1);
}

// A board's distance from a point is to its nearest point: straight across its face where the
// point faces it, else to its edge or corner (closed forms); drawn boards with a least distance
// keep every point of the board that far from the viewpoint, the centre's distance alone does not.
TEST(CalibrationTargets, ABoardsDistanceIsToItsNearestPointAndDrawnBoardsKeepIt) {
  const std::vector<Vec3> outline = {{0, 0, 0}, {0.4, 0, 0}, {0.4, 0.3, 0}, {0, 0.3, 0}};
  Rigid worldFromTarget = Rigid::Identity();
  worldFromTarget.translation() = Vec3(1, 2, 3);
  EXPECT_NEAR(boardDistance(worldFromTarget, outline, Vec3(1.2, 2.1, 3.25)), 0.25, 1e-15);          // over the face
  EXPECT_NEAR(boardDistance(worldFromTarget, outline, Vec3(1.6, 2.1, 3.0)), 0.2, 1e-15);            // beside an edge
  EXPECT_NEAR(boardDistance(worldFromTarget, outline, Vec3(1.7, 2.7, 3.12)), std::hypot(0.3, 0.4, 0.12), 1e-15);  // past a corner

  const auto camera = makeCamera(RigSpec{});
  const Rigid worldFromViewpoint = CameraPlacement(RobotPose{}).worldFromViewpoint(camera->rig());
  const AprilGrid grid{6, 6, 0.088, 0.3, 0};
  BoardPoseOptions near;
  near.count = 20;
  near.nearM = 0.05;
  near.farM = 0.08;
  near.minSeenCorners = 4;
  near.boardMarginM = 0.02;
  const std::vector<Vec3> board = floorTestPoints(grid, near.boardMarginM);
  double centreOnly = 1.0;
  for (const Rigid& pose : boardPoses(*camera, worldFromViewpoint, grid, near))
    centreOnly = std::min(centreOnly, boardDistance(pose, board, worldFromViewpoint.translation()));
  EXPECT_LT(centreOnly, 0.05) << "tilted boards centred 5 cm away reach nearer with their edges";
  near.minBoardDistanceM = 0.05;
  for (const Rigid& pose : boardPoses(*camera, worldFromViewpoint, grid, near))
    EXPECT_GE(boardDistance(pose, board, worldFromViewpoint.translation()), 0.05);
}

TEST(CalibrationTargets, HiddenCornersSayWhy) {
  // A box between the robot and the grid's left half, the checkerboard turned away.
  const Scene scene = targetScene(R"(, {"name": "pillar", "type": "box", "material": "grey", "center": [0.4, 0.25, 0.3], "size": [0.05, 0.12, 0.6]})");
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().imageSize = 360;
  const FastRenderer renderer(scene);
  const std::shared_ptr<const Camera> camera = makeCamera(settings.rig);
  const Rigid worldFromViewpoint = CameraPlacement(RobotPose{0.0, 0.0, 0.0}).worldFromViewpoint(settings.rig);
  const std::vector<ImagedCorner> grid = imagedCorners(*camera, worldFromViewpoint, &renderer.rays(), scene.calibrationTargets[0]);
  const auto count = [](const std::vector<ImagedCorner>& corners, CornerSight sight) {
    return std::count_if(corners.begin(), corners.end(), [&](const ImagedCorner& c) { return c.sight == sight; });
  };
  EXPECT_GT(count(grid, CornerSight::Occluded), 0);
  EXPECT_GT(count(grid, CornerSight::Seen), 0);
  // Which: the corners whose line of sight from the viewpoint passes through the box (the ideal
  // rig is central: every ray leaves F').
  const Vec3 viewpoint = worldFromViewpoint.translation();
  const Box& box = std::get<Box>(scene.objects[3].shape);
  for (const ImagedCorner& c : grid) {
    const Vec3 corner = worldCorners(scene.calibrationTargets[0])[static_cast<size_t>(c.index)];
    // The segment from F' to the corner against the axis-aligned box (slab test).
    double t0 = 0.0, t1 = 1.0;
    for (int axis = 0; axis < 3; ++axis) {
      const double d = corner[axis] - viewpoint[axis], lo = box.center[axis] - box.size[axis] / 2, hi = box.center[axis] + box.size[axis] / 2;
      double a = (lo - viewpoint[axis]) / d, b = (hi - viewpoint[axis]) / d;
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
    }
    EXPECT_EQ(c.sight == CornerSight::Occluded, t0 < t1) << "corner " << c.index;
  }
  // Seen from behind: the robot on the far side of the grid.
  const Rigid behind = CameraPlacement(RobotPose{1.2, 0.0, 180.0}).worldFromViewpoint(settings.rig);
  const std::vector<ImagedCorner> back = imagedCorners(*camera, behind, &renderer.rays(), scene.calibrationTargets[0]);
  EXPECT_EQ(count(back, CornerSight::BackFacing), static_cast<long>(back.size()));
  // Far away, the board sinks below the mirror's field of view... or is cut by the rim: corners
  // high above the mirror at close range are beyond it.
  Scene high = scene;
  high.calibrationTargets[0].worldFromTarget.translation() = Vec3(0.05, 0.35, 1.5);
  const std::vector<ImagedCorner> above = imagedCorners(*camera, worldFromViewpoint, &renderer.rays(), high.calibrationTargets[0]);
  EXPECT_EQ(count(above, CornerSight::BeyondRim), static_cast<long>(above.size()));
}

// Exact corners of 20 seeded AprilGrid poses around the robot, as calibration views, and the
// boards' true poses in the viewpoint frame.
struct ExactViews {
  std::vector<CalibrationView> views;
  std::vector<Rigid> viewpointFromTarget;
};
ExactViews exactViews(const Camera& camera) {
  const Rigid worldFromViewpoint = CameraPlacement(RobotPose{}).worldFromViewpoint(camera.rig());
  const AprilGrid grid{6, 6, 0.088, 0.3, 0};
  BoardPoseOptions poses;
  poses.count = 20;
  poses.seed = 7;
  ExactViews out;
  CalibrationTarget board;
  board.pattern = grid;
  const std::vector<Vec3> corners = targetCorners(grid);
  for (const Rigid& pose : boardPoses(camera, worldFromViewpoint, grid, poses)) {
    board.worldFromTarget = pose;
    CalibrationView view;
    for (const ImagedCorner& c : imagedCorners(camera, worldFromViewpoint, nullptr, board))
      if (c.sight == CornerSight::Seen) {
        view.targetPoints.push_back(corners[static_cast<size_t>(c.index)]);
        view.raster.push_back(c.raster);
      }
    EXPECT_GE(view.raster.size(), 12u);
    out.views.push_back(view);
    out.viewpointFromTarget.push_back(worldFromViewpoint.inverse() * pose);
  }
  return out;
}

// calibrateOmnidir finds cv::omnidir::calibrate by its linker name when it opens ccalib: that name
// is the one of the function this test links against.
TEST(CalibrationTargets, TheOmnidirCalibrateOpenedAtRunTimeIsOpenCvsOwn) {
  EXPECT_EQ(::dlsym(RTLD_DEFAULT, kOmnidirCalibrateSymbol), reinterpret_cast<void*>(&cv::omnidir::calibrate));
}

// cv::omnidir's dense Jacobian grows with corners × views: 20,000 views of 4 corners would take
// about 300 GB (8 bytes × 2 × 160,000 rows × 120,010 columns, twice). Said before OpenCV allocates
// any of it, as every other memory shortage is.
TEST(CalibrationTargets, AFitBeyondMemoryIsAShortageNotAnAllocationFailure) {
  CalibrationView view;
  view.targetPoints = {{0, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0}, {0.1, 0.1, 0}};
  view.raster = {{10, 10}, {20, 10}, {10, 20}, {20, 20}};
  const std::vector<CalibrationView> views(20000, view);
  EXPECT_GT(omnidirFitBytes(views), int64_t{300} * 1000 * 1000 * 1000);
  EXPECT_THROW(calibrateOmnidir(views, 720, 720, OmnidirOptions{}), MemoryShortage);
}

// The ideal rig's intrinsics are known in closed form (its describe()); OpenCV's omnidir
// calibration from exact corners recovers them, and the calibrated model reprojects held-out
// points at every distance where the camera images them.
TEST(CalibrationTargets, OmnidirRecoversTheIdealRigsIntrinsicsFromExactCorners) {
  RigSpec rig;
  rig.mirrorRig().imageSize = 720;
  const std::shared_ptr<const Camera> camera = makeCamera(rig);
  const ExactViews exact = exactViews(*camera);
  OmnidirOptions options;
  options.fixDistortion = true;
  const OmnidirCalibration fit = calibrateOmnidir(exact.views, 720, 720, options);
  ASSERT_TRUE(fit.converged) << fit.failure;
  const nlohmann::json truth = camera->describe();
  const auto relative = [](double found, double expected) { return std::abs(found - expected) / std::abs(expected); };
  std::printf("ideal rig, exact corners, distortion fixed: rms %.2e px, %zu of 20 views; xi %.6f (truth %.6f, %.2e), "
              "gamma_x %.4f (%.4f, %.2e), gamma_y %.4f (%.4f, %.2e), cx %.4f (%.4f, %.2e), cy %.4f (%.4f, %.2e)\n",
              fit.rms, fit.usedViews.size(), fit.xi, truth["xi"].get<double>(), relative(fit.xi, truth["xi"]), fit.gammaX,
              truth["gamma_x"].get<double>(), relative(fit.gammaX, truth["gamma_x"]), fit.gammaY, truth["gamma_y"].get<double>(),
              relative(fit.gammaY, truth["gamma_y"]), fit.cx, truth["cx"].get<double>(), relative(fit.cx, truth["cx"]), fit.cy,
              truth["cy"].get<double>(), relative(fit.cy, truth["cy"]));
  EXPECT_LT(relative(fit.xi, truth["xi"]), 1e-3);
  EXPECT_LT(relative(fit.gammaX, truth["gamma_x"]), 1e-3);
  EXPECT_LT(relative(fit.gammaY, truth["gamma_y"]), 1e-3);
  EXPECT_LT(relative(fit.cx, truth["cx"]), 1e-3);
  EXPECT_LT(relative(fit.cy, truth["cy"]), 1e-3);
  EXPECT_LT(fit.rms, 1e-3);
  // Placed by its own extrinsics, the calibrated model is the rig's: camera frame rig.h's, at F'.
  const CentralApproximation model = calibratedModel(fit, exact.viewpointFromTarget);
  EXPECT_LT((model.cameraFromViewpoint.linear() - unifiedCameraFromViewpoint().linear()).norm(), 1e-6);
  EXPECT_LT(model.viewpoint.norm(), 1e-6);
  for (double d : {0.2, 0.5, 1.0, 5.0}) EXPECT_LT(heldOutError(*camera, model, d).maxPx, 1e-3) << d << " m";
}

// A misaligned rig calibrates to a fine-looking RMS, close to the best-fit central model, and
// its calibrated model errs on held-out points nearby. Measured (720 px, exact corners): pinhole
// 2 mm off along x: rms 0.41 px; xi 1.0295 (best fit 1.0292), centre x 230.2 (232.1); held-out
// median 4.5 px at 0.2 m, 1.5 px at 0.5 m, 2.4 px at 5 m. Off along y, the centre moves in y: the
// flip of the mirror image for OpenCV and back keeps cy's side (and p1's sign).
TEST(CalibrationTargets, AMisalignedRigsCalibrationLooksFineButErrsNearby) {
  for (const std::array<double, 3> offset : {std::array<double, 3>{2.0, 0.0, 0.0}, std::array<double, 3>{0.0, 2.0, 0.0}}) {
    RigSpec rig;
    rig.mirrorRig().imageSize = 720;
    rig.mirrorRig().mount.offsetMm = offset;
    const std::shared_ptr<const Camera> camera = makeCamera(rig);
    const ExactViews exact = exactViews(*camera);
    const OmnidirCalibration fit = calibrateOmnidir(exact.views, 720, 720, OmnidirOptions{});
    ASSERT_TRUE(fit.converged) << fit.failure;
    const CentralApproximation model = calibratedModel(fit, exact.viewpointFromTarget);
    const CentralApproximation best = fitCentralApproximation(*camera);
    std::printf("pinhole off by (%.0f, %.0f) mm, exact corners: rms %.3f px, xi %.4f, gamma %.2f %.2f, centre %.2f %.2f, "
                "k1 %.4f, p1 %.5f, p2 %.5f;", offset[0], offset[1], fit.rms, fit.xi, fit.gammaX, fit.gammaY, fit.cx, fit.cy,
                fit.distortion[0], fit.distortion[2], fit.distortion[3]);
    std::vector<HeldOutError> held;
    for (double d : {0.2, 0.5, 1.0, 5.0}) {
      held.push_back(heldOutError(*camera, model, d));
      std::printf(" %.1f m: median %.3f px, max %.3f px;", d, held.back().medianPx, held.back().maxPx);
    }
    const MeiIntrinsics& b = best.intrinsics;
    std::printf("\n  best-fit central model: xi %.4f, gamma %.2f %.2f, centre %.2f %.2f, k1 %.4f, p1 %.5f, p2 %.5f\n", b.xi,
                b.gammaX, b.gammaY, b.cx, b.cy, b.lens.k1, b.lens.p1, b.lens.p2);
    EXPECT_LT(fit.rms, 0.5);  // a calibration that looks fine
    EXPECT_GT(held[0].medianPx, held[1].medianPx);
    EXPECT_LT(std::abs(fit.xi - b.xi), 0.005 * b.xi);
    EXPECT_LT(std::abs(fit.cx - b.cx), 5.0);
    EXPECT_LT(std::abs(fit.cy - b.cy), 5.0);
    EXPECT_LT(fit.gammaY, 0.0);
    // The tangential terms, which the flip must leave alone (measured within 0.0012 of the best fit).
    EXPECT_LT(std::abs(fit.distortion[2] - b.lens.p1), 0.005);
    EXPECT_LT(std::abs(fit.distortion[3] - b.lens.p2), 0.005);
  }
}

}  // namespace
}  // namespace omnicam
