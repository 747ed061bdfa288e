// Calibration targets against independent implementations: OpenCV's checkerboard detector finds
// the corners where the target says they are, the tags are AprilTag's own images, and an
// AprilGrid's corners are Kalibr's formula.
#include "calibration_target.h"

#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "errors.h"
#include "scene_loader.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;

// Test images are the board's texture magnified by this (nearest: the edges stay where they are).
constexpr int kMagnify = 4;

cv::Mat boardImage(const TargetBoard& board) {
  const Texture& t = *board.texture;
  cv::Mat grey(t.height(), t.width(), CV_8UC1);
  for (int r = 0; r < t.height(); ++r)
    for (int c = 0; c < t.width(); ++c)
      grey.at<uint8_t>(r, c) = static_cast<uint8_t>(std::lround(255.0f * t.rgbLinear()[(static_cast<size_t>(r) * t.width() + c) * 3]));
  cv::Mat magnified;
  cv::resize(grey, magnified, cv::Size(), kMagnify, kMagnify, cv::INTER_NEAREST);
  return magnified;
}

// Where a target-frame point lies in boardImage (OpenCV: pixel centres at integers).
cv::Point2d imagePoint(const TargetBoard& board, const Vec3& p) {
  const double texel = board.edgeU.x() / board.texture->width();
  const double u = (p.x() - board.origin.x()) / texel, v = (board.origin.y() + board.edgeV.y() - p.y()) / texel;
  return {u * kMagnify - 0.5, v * kMagnify - 0.5};
}

double nearest(const std::vector<cv::Point2f>& found, const cv::Point2d& p) {
  double best = 1e9;
  for (const cv::Point2f& f : found) best = std::min(best, std::hypot(f.x - p.x, f.y - p.y));
  return best;
}

TEST(CalibrationTarget, CheckerboardCornersAreWhereOpenCvFindsThem) {
  const Checkerboard pattern{7, 10, 0.03};
  const TargetBoard board = targetBoard(pattern, 0.03, 0.03f, 0.85f);
  const cv::Mat image = boardImage(board);
  std::vector<cv::Point2f> found;
  ASSERT_TRUE(cv::findChessboardCornersSB(image, cv::Size(9, 6), found, cv::CALIB_CB_EXHAUSTIVE | cv::CALIB_CB_ACCURACY));
  const std::vector<Vec3> corners = targetCorners(pattern);
  ASSERT_EQ(corners.size(), 54u);
  EXPECT_EQ(corners[10], Vec3(0.03, 0.03, 0.0));  // row 1, column 1
  double worst = 0.0;
  for (const Vec3& c : corners) worst = std::max(worst, nearest(found, imagePoint(board, c)));
  std::printf("checkerboard: OpenCV's corners at most %.4f px from the target's (squares of %d px)\n", worst,
              kMagnify * kTargetTexelsPerCell);
  EXPECT_LT(worst, 0.1) << "px, squares of " << kMagnify * kTargetTexelsPerCell << " px";
  // The bottom-left square is black, its neighbours white.
  EXPECT_LT(image.at<uint8_t>(imagePoint(board, {-0.015, -0.015, 0.0})), 16);
  EXPECT_GT(image.at<uint8_t>(imagePoint(board, {0.015, -0.015, 0.0})), 200);
  EXPECT_GT(image.at<uint8_t>(imagePoint(board, {-0.015, 0.015, 0.0})), 200);
}

TEST(CalibrationTarget, TagBitsAreAprilTagsOwnImages) {
  apriltag_family_t* family = tag36h11_create();
  ASSERT_EQ(aprilGridFamilySize(), 587);
  for (int id = 0; id < aprilGridFamilySize(); ++id) {
    image_u8_t* own = apriltag_to_image(family, static_cast<uint32_t>(id));
    const std::vector<bool> bits = aprilTagBits(id);
    // apriltag_to_image: a white ring, the one-bit black border, then the 6 × 6 data bits.
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c)
        ASSERT_EQ(bits[static_cast<size_t>(r * 6 + c)], own->buf[(r + 2) * own->stride + c + 2] != 0)
            << "id " << id << " row " << r << " column " << c;
    image_u8_destroy(own);
  }
  tag36h11_destroy(family);
}

TEST(CalibrationTarget, AprilGridCornersAreKalibrsPoints) {
  const AprilGrid grid{4, 5, 0.05, 0.3, 3};
  // Kalibr's GridCalibrationTargetAprilgrid::points().
  const std::vector<Vec3> corners = targetCorners(grid);
  ASSERT_EQ(corners.size(), 80u);
  for (int r = 0; r < 8; ++r)
    for (int c = 0; c < 10; ++c) {
      const Vec3 kalibr((c / 2) * (1.0 + 0.3) * 0.05 + (c % 2) * 0.05, (r / 2) * (1.0 + 0.3) * 0.05 + (r % 2) * 0.05, 0.0);
      EXPECT_LT((corners[static_cast<size_t>(r * 10 + c)] - kalibr).norm(), 1e-12) << r << ", " << c;
    }
  EXPECT_EQ(targetPatternProblem(grid, 0.01), "");
  EXPECT_NE(targetPatternProblem(AprilGrid{4, 5, 0.05, 0.33, 3}, 0.01).find("tag_spacing"), std::string::npos);
  EXPECT_NE(targetPatternProblem(AprilGrid{4, 5, 0.05, 0.3, 570}, 0.01).find("587"), std::string::npos);

  // That AprilTag decodes every tag where these corners say: calibration_test (the detector lives
  // in calibration/).
}

class CalibrationTargetScene : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("omnicam_target_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& target) {
    const fs::path p = dir_ / "scene.json";
    std::ofstream(p) << R"({"format": "omnicam-scene/1", "materials": {"m": {"color": 0.5}},
      "objects": [{"type": "sphere", "material": "m", "center": [0, 0, 0], "radius": 0.1}, )"
                     << target << "]}";
    return p.string();
  }
  std::string errorOf(const std::string& target) {
    try {
      loadScene(write(target));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(CalibrationTargetScene, BoardIsATexturedQuadWhoseCornersAreTheTargets) {
  const Scene s = loadScene(write(R"({"name": "board", "type": "calibration_target", "class": "target",
      "pattern": {"kind": "checkerboard", "rows": 5, "columns": 6, "square": 0.04},
      "origin": [1, 2, 0.5], "x_axis": [0, 1, 0], "y_axis": [0, 0, 2]})"));
  ASSERT_EQ(s.calibrationTargets.size(), 1u);
  const CalibrationTarget& target = s.calibrationTargets[0];
  ASSERT_EQ(target.object, 1);
  const SceneObject& board = s.objects[1];
  EXPECT_EQ(board.name, "board");
  EXPECT_EQ(board.semanticClass, "target");
  const Quad& quad = std::get<Quad>(board.shape);
  const Material& print = s.materials[static_cast<size_t>(board.material)];
  ASSERT_TRUE(print.texture);
  const std::vector<Vec3> corners = worldCorners(target);
  ASSERT_EQ(corners.size(), 20u);
  EXPECT_LT((corners[0] - Vec3(1, 2, 0.5)).norm(), 1e-12);
  EXPECT_LT((corners[6] - Vec3(1, 2.04, 0.54)).norm(), 1e-12);  // row 1, column 1: along y_axis = +Z
  // Around every corner the board alternates black and white, as the scene's renderers see it.
  const Vec3 normal = quad.edgeU.cross(quad.edgeV).normalized();
  EXPECT_LT((normal - Vec3(1, 0, 0)).norm(), 1e-12);  // the printed face looks along x_axis × y_axis
  const auto albedoAt = [&](const Vec3& p) {
    const Vec3 d = p - quad.origin;
    return print.texture->sample(d.dot(quad.edgeU) / quad.edgeU.squaredNorm(), d.dot(quad.edgeV) / quad.edgeV.squaredNorm()).x();
  };
  const Vec3 right(0, 1, 0), up(0, 0, 1);
  for (size_t k = 0; k < corners.size(); ++k) {
    const int r = static_cast<int>(k) / 5, c = static_cast<int>(k) % 5;
    const bool lowerLeftBlack = (r + c) % 2 == 0;
    const float lowerLeft = albedoAt(corners[k] - 0.01 * right - 0.01 * up);
    const float lowerRight = albedoAt(corners[k] + 0.01 * right - 0.01 * up);
    EXPECT_FLOAT_EQ(lowerLeft, lowerLeftBlack ? 0.03f : 0.85f) << k;
    EXPECT_FLOAT_EQ(lowerRight, lowerLeftBlack ? 0.85f : 0.03f) << k;
  }
}

TEST_F(CalibrationTargetScene, BadTargetsNameTheirField) {
  const std::string file = (dir_ / "scene.json").string();
  const std::string pose = R"("origin": [0, 0, 1], "x_axis": [1, 0, 0], "y_axis": [0, 0, 1])";
  const std::string grid = R"("kind": "aprilgrid", "tag_rows": 2, "tag_columns": 3, "tag_size": 0.08, "tag_spacing": 0.3)";
  EXPECT_EQ(errorOf(R"({"type": "calibration_target", "pattern": {)" + grid + "}, " + pose + "}"), "");
  EXPECT_EQ(errorOf(R"({"type": "calibration_target", "pattern": {"kind": "checkerboard", "rows": 6, "columns": 8, "square": 0.05}, )" +
                    pose + "}"),
            file + ": objects[1].pattern.columns: rows + columns must be odd (one side even, one odd: else the board has no "
                   "first corner a detector can tell)");
  EXPECT_EQ(errorOf(R"({"type": "calibration_target", "pattern": {"kind": "circles"}, )" + pose + "}"),
            file + ": objects[1].pattern.kind: unknown pattern kind \"circles\" (checkerboard, aprilgrid)");
  EXPECT_EQ(errorOf(R"({"type": "calibration_target", "pattern": {"kind": "aprilgrid", "tag_rows": 2, "tag_columns": 3,
      "tag_size": 0.08, "tag_spacing": 0.33}, )" + pose + "}"),
            file + ": objects[1].pattern: tag_spacing must be a positive multiple of 1/80 (the gap a whole number of the "
                   "pattern's texels, an eighth of a tag bit)");
  EXPECT_EQ(errorOf(R"({"type": "calibration_target", "pattern": {)" + grid + R"(, "first_id": 584}, )" + pose + "}"),
            file + ": objects[1].pattern: ids 584 to 589 exceed tag family 36h11's 587 codes");
  EXPECT_EQ(errorOf(R"({"type": "calibration_target", "pattern": {)" + grid +
                    R"(}, "origin": [0, 0, 1], "x_axis": [1, 0, 0], "y_axis": [1, 0, 1]})"),
            file + ": objects[1].y_axis: must be perpendicular to x_axis");
  EXPECT_EQ(errorOf(R"({"type": "calibration_target", "pattern": {)" + grid + R"(}, "margin": 0.0001, )" + pose + "}"),
            file + ": objects[1].margin: must be at least one texel of the pattern (0.001 m; the texture repeats)");
  EXPECT_EQ(errorOf(R"({"type": "calibration_target", "pattern": {)" + grid + R"(}, "material": "m", )" + pose + "}"),
            file + ": objects[1].material: unknown field");
}

// The board's outline (what must clear a floor): an AprilGrid's pattern reaches a gap (spacing ×
// size) beyond its outer tags, the margin beyond that; a checkerboard's a square beyond its inner
// corners.
TEST(CalibrationTarget, BoardOutlineIsThePatternAndItsMargin) {
  const std::array<Vec3, 4> grid = targetBoardOutline(AprilGrid{5, 5, 0.06, 0.3, 0}, 0.012);
  EXPECT_NEAR(grid[0].x(), -0.018 - 0.012, 1e-12);
  EXPECT_NEAR(grid[0].y(), -0.018 - 0.012, 1e-12);
  EXPECT_NEAR(grid[2].x(), 5 * 1.3 * 0.06 + 0.012, 1e-12);
  EXPECT_NEAR(grid[2].y(), 5 * 1.3 * 0.06 + 0.012, 1e-12);
  const std::array<Vec3, 4> board = targetBoardOutline(Checkerboard{7, 10, 0.05}, 0.05);
  EXPECT_NEAR(board[0].x(), -0.1, 1e-12);
  EXPECT_NEAR(board[2].x(), 9 * 0.05 + 0.05, 1e-12);
  EXPECT_NEAR(board[2].y(), 6 * 0.05 + 0.05, 1e-12);
  EXPECT_EQ(board[1].y(), board[0].y());
  EXPECT_EQ(board[3].x(), board[0].x());
}

}  // namespace
}  // namespace omnicam
