// Calibration files read by their consumers: Kalibr's target YAML by Kalibr's own rules (its
// ConfigReader, as Python reads YAML), OpenCV's corner lists by cv::FileStorage into a calibration.
#include "calibration_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "board_poses.h"
#include "errors.h"
#include "imaged_corners.h"
#include "make_camera.h"
#include "placement.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;

// kalibr_common/ConfigReader.py, CalibrationTargetParameters.getTargetParams (ethz-asl/kalibr),
// on PyYAML's reading of the file: the keys it reads, with the types and ranges it checks.
constexpr const char* kKalibrReader = R"PY(
import sys, yaml
d = yaml.safe_load(open(sys.argv[1]))
kind = d['target_type']
def integer(k):
    v = d[k]
    assert isinstance(v, int) and v >= 3, (k, v)
    return v
def real(k):
    v = d[k]
    assert isinstance(v, float) and v > 0, (k, v)
    return v
if kind == 'aprilgrid':
    got = (integer('tagCols'), integer('tagRows'), real('tagSize'), real('tagSpacing'))
elif kind == 'checkerboard':
    got = (integer('targetCols'), integer('targetRows'), real('rowSpacingMeters'), real('colSpacingMeters'))
else:
    raise SystemExit('unknown target_type %r' % kind)
print(kind, *got)
)PY";

std::string kalibrReads(const std::string& yaml) {
  const fs::path dir = fs::temp_directory_path() / ("omnicam_kalibr_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "reader.py") << kKalibrReader;
  std::ofstream(dir / "target.yaml") << yaml;
  const std::string command = "/usr/bin/python3 " + (dir / "reader.py").string() + " " + (dir / "target.yaml").string() +
                              " > " + (dir / "out.txt").string();
  const int status = std::system(command.c_str());
  std::ifstream in(dir / "out.txt");
  std::string line;
  std::getline(in, line);
  fs::remove_all(dir);
  return status == 0 ? line : "failed: " + std::to_string(status);
}

TEST(CalibrationFiles, KalibrReadsTheTargetYaml) {
  EXPECT_EQ(kalibrReads(kalibrTargetYaml(AprilGrid{6, 7, 0.088, 0.3, 0})), "aprilgrid 7 6 0.088 0.3");
  EXPECT_EQ(kalibrReads(kalibrTargetYaml(Checkerboard{7, 10, 0.05})), "checkerboard 9 6 0.05 0.05");
  EXPECT_EQ(kalibrReads(kalibrTargetYaml(AprilGrid{3, 3, 1.0, 0.25, 0})), "aprilgrid 3 3 1.0 0.25");  // whole metres stay floats
  EXPECT_EQ(kalibrReads(kalibrTargetYaml(Checkerboard{7, 10, 1e-4})), "checkerboard 9 6 0.0001 0.0001");  // "1e-04" would be a string
  EXPECT_THROW(kalibrTargetYaml(AprilGrid{2, 6, 0.088, 0.3, 0}), InputError);  // Kalibr needs 3 rows
  EXPECT_THROW(kalibrTargetYaml(AprilGrid{6, 6, 0.088, 0.3, 36}), InputError);  // and tag 0 first
  EXPECT_THROW(kalibrTargetYaml(Checkerboard{3, 10, 0.05}), InputError);
  // The problem names the scene's field of the pattern (a dataset adds its file and field).
  EXPECT_EQ(kalibrTargetProblem(AprilGrid{6, 6, 0.088, 0.3, 36}),
            "pattern.first_id: Kalibr's AprilGrids start at tag 0 (this target's first_id is 36)");
  EXPECT_EQ(kalibrTargetProblem(AprilGrid{6, 2, 0.088, 0.3, 0}),
            "pattern.tag_columns: Kalibr's target files need at least 3 tag columns (this target has 2)");
  EXPECT_EQ(kalibrTargetProblem(AprilGrid{2, 6, 0.088, 0.3, 0}),
            "pattern.tag_rows: Kalibr's target files need at least 3 tag rows (this target has 2)");
  EXPECT_EQ(kalibrTargetProblem(Checkerboard{10, 3, 0.05}),
            "pattern.columns: Kalibr's target files need at least 3 inner corners a row (this target has 2)");
  EXPECT_EQ(kalibrTargetProblem(AprilGrid{3, 3, 0.088, 0.3, 0}), "");
}

// omnicam calibrate reads a dataset's target back from the Kalibr file it wrote: the same pattern,
// corner for corner; anything else in the file is refused with its key.
TEST(CalibrationFiles, AKalibrTargetReadsBackAsThePatternItWasWrittenFrom) {
  for (const TargetPattern& pattern : {TargetPattern{AprilGrid{6, 5, 0.088, 0.3, 0}}, TargetPattern{Checkerboard{7, 10, 0.05}}}) {
    const TargetPattern back = targetPatternFromKalibrYaml(kalibrTargetYaml(pattern), "target.yaml");
    ASSERT_EQ(back.index(), pattern.index());
    const std::vector<Vec3> corners = targetCorners(pattern), again = targetCorners(back);
    ASSERT_EQ(again.size(), corners.size());
    for (size_t k = 0; k < corners.size(); ++k) EXPECT_EQ(again[k], corners[k]) << k;
  }
  const auto refusal = [](const std::string& text) {
    try {
      (void)targetPatternFromKalibrYaml(text, "target.yaml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string grid = kalibrTargetYaml(AprilGrid{6, 5, 0.088, 0.3, 0});
  EXPECT_EQ(refusal(grid + "tagSize: 0.1\n"), "target.yaml: \"tagSize\" given twice");
  EXPECT_EQ(refusal(grid + "codeOffset: 0\n"), "target.yaml: \"codeOffset\": not a field of this target type");
  EXPECT_EQ(refusal("target_type: 'aprilgrid'\ntagCols: 6\n"), "target.yaml: tagRows: missing");
  EXPECT_EQ(refusal("target_type: 'circlegrid'\n"), "target.yaml: target_type: must be 'aprilgrid' or 'checkerboard' (got \"'circlegrid'\")");
  EXPECT_EQ(refusal("target_type: 'checkerboard'\ntargetCols: 9\ntargetRows: 99999\nrowSpacingMeters: 0.05\ncolSpacingMeters: 0.05\n"),
            "target.yaml: targetRows: must be an integer from 3 to 999 (got \"99999\")");
  EXPECT_EQ(refusal("target_type: 'checkerboard'\ntargetCols: 8\ntargetRows: 6\nrowSpacingMeters: 0.05\ncolSpacingMeters: 0.05\n")
                .rfind("target.yaml: targetCols: one of targetRows, targetCols must be even", 0),
            0u);
  EXPECT_EQ(refusal("target_type: 'aprilgrid'\ntagCols: 40\ntagRows: 40\ntagSize: 0.05\ntagSpacing: 0.3\n"),
            "target.yaml: not a target omnicam writes: ids 0 to 1599 exceed tag family 36h11's 587 codes");
  EXPECT_EQ(refusal("target_type: 'checkerboard'\ntargetCols: 9\ntargetRows: 6\nrowSpacingMeters: nan\ncolSpacingMeters: 0.05\n"),
            "target.yaml: rowSpacingMeters: must be a number in [0.0001, 10] (got \"nan\")");
  EXPECT_EQ(refusal("tagCols 6\n"), "target.yaml: line 1: not `key: value` as omnicam writes it");
}

TEST(CalibrationFiles, OpenCvCornerListsCalibrateAsTheViewsThemselves) {
  RigSpec rig;
  rig.mirrorRig().imageSize = 360;
  const std::shared_ptr<const Camera> camera = makeCamera(rig);
  const Rigid worldFromViewpoint = CameraPlacement(RobotPose{}).worldFromViewpoint(rig);
  const Checkerboard board{7, 10, 0.05};
  BoardPoseOptions poses;
  poses.count = 12;
  poses.seed = 3;
  CalibrationTarget target;
  target.pattern = board;
  const std::vector<Vec3> corners = targetCorners(board);
  std::vector<CornerListImage> images;
  for (const Rigid& pose : boardPoses(*camera, worldFromViewpoint, board, poses)) {
    target.worldFromTarget = pose;
    CornerListImage image;
    image.name = "frame_" + std::to_string(images.size()) + ".png";
    for (const ImagedCorner& c : imagedCorners(*camera, worldFromViewpoint, nullptr, target))
      if (c.sight == CornerSight::Seen) {
        image.view.targetPoints.push_back(corners[static_cast<size_t>(c.index)]);
        image.view.raster.push_back(c.raster);
      }
    images.push_back(image);
  }
  const std::vector<CornerListImage> back = readOpenCvCornerLists(openCvCornerLists(images, true), "corners.yml");
  ASSERT_EQ(back.size(), images.size());
  std::vector<CalibrationView> direct, read;
  for (size_t k = 0; k < images.size(); ++k) {
    EXPECT_EQ(back[k].name, images[k].name);
    ASSERT_EQ(back[k].view.raster.size(), images[k].view.raster.size());
    for (size_t i = 0; i < images[k].view.raster.size(); ++i) {
      EXPECT_EQ(back[k].view.raster[i], images[k].view.raster[i]);
      EXPECT_EQ(back[k].view.targetPoints[i], images[k].view.targetPoints[i]);
    }
    direct.push_back(images[k].view);
    read.push_back(back[k].view);
  }
  OmnidirOptions options;
  options.fixDistortion = true;
  const OmnidirCalibration a = calibrateOmnidir(direct, 360, 360, options), b = calibrateOmnidir(read, 360, 360, options);
  ASSERT_TRUE(b.converged) << b.failure;
  EXPECT_EQ(a.xi, b.xi);
  EXPECT_NEAR(b.xi, camera->describe()["xi"].get<double>(), 1e-6);
  EXPECT_THROW(readOpenCvCornerLists("%YAML:1.0\nimages: 3\n", "bad.yml"), InputError);
}

}  // namespace
}  // namespace omnicam
