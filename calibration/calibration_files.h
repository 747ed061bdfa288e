#pragma once
// Calibration data in the layouts calibration tools read: Kalibr's target YAML, and corner lists
// as OpenCV's FileStorage writes them (what cv::omnidir::calibrate and cv::calibrateCamera take).
#include <string>
#include <vector>

#include "calibration_target.h"
#include "omnidir_fit.h"

namespace omnicam {

// Kalibr's target file (kalibr_common/ConfigReader.py, CalibrationTargetParameters): an AprilGrid
// as tagCols, tagRows, tagSize (m), tagSpacing (a share of tagSize); a checkerboard as its inner
// corners (targetCols, targetRows) and square edges (rowSpacingMeters, colSpacingMeters).
// Targets Kalibr would misread or refuse (an AprilGrid whose first id is not 0; fewer than 3 tag
// or inner-corner rows or columns) throw InputError with kalibrTargetProblem's words.
std::string kalibrTargetYaml(const TargetPattern& pattern);
// The target of a Kalibr target file as kalibrTargetYaml writes it (one `key: value` a line, every
// key once, nothing else): read strictly, InputError naming `source` and the key otherwise.
TargetPattern targetPatternFromKalibrYaml(const std::string& text, const std::string& source);
// Why Kalibr cannot read this target ("" when it can), led by the scene's field of the pattern
// ("pattern.first_id: ...").
std::string kalibrTargetProblem(const TargetPattern& pattern);

// OpenCV's corner lists, one entry per image: the image's name, its corners in the target frame
// (object_points, N×1 CV_64FC3) and in the image (image_points, N×1 CV_64FC2, OpenCV's pixel
// centres at integers), and `mirror_image`: 1 for a mirror camera's image (a mirror image, which
// cv::omnidir fits flipped top to bottom), 0 for a lens camera's. Returns the file's text
// (cv::FileStorage YAML).
struct CornerListImage {
  std::string name;
  CalibrationView view;  // omnicam raster
};
std::string openCvCornerLists(const std::vector<CornerListImage>& images, bool mirrorImage);
// Read back as OpenCV reads it (rasters converted to omnicam's); throws InputError naming `source`.
std::vector<CornerListImage> readOpenCvCornerLists(const std::string& text, const std::string& source);

// A cv::omnidir calibration of camera `camera` (width × height images) as cv::FileStorage YAML:
// camera_matrix K (gamma_x, skew, cx; 0, gamma_y, cy; OpenCV's pixel centres at integers), xi,
// distortion_coefficients (k1, k2, p1, p2), the RMS and the views used, and `mirror_image`: 1 for
// a mirror camera's fit (gamma_y < 0: fitted flipped top to bottom and flipped back).
std::string omnidirCalibrationYaml(const OmnidirCalibration& fit, const std::string& camera, int width, int height, bool mirrorImage);

}  // namespace omnicam
