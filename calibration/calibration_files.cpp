#include "calibration_files.h"

#include <opencv2/core.hpp>
#include <sstream>

#include "errors.h"
#include "number_format.h"

namespace omnicam {

std::string kalibrTargetProblem(const TargetPattern& pattern) {
  // Kalibr's ConfigReader refuses fewer than 3 rows or columns (tags, or inner corners).
  const auto atLeastThree = [](int value, const std::string& field, const char* what) -> std::string {
    if (value >= 3) return "";
    return field + ": Kalibr's target files need at least 3 " + what + " (this target has " + std::to_string(value) + ")";
  };
  std::string problem;
  if (const auto* g = std::get_if<AprilGrid>(&pattern)) {
    // Kalibr takes tag k for the grid's k-th cell: a grid starting at another id would be read wrong.
    if (g->firstId != 0)
      return "pattern.first_id: Kalibr's AprilGrids start at tag 0 (this target's first_id is " + std::to_string(g->firstId) + ")";
    problem = atLeastThree(g->tagColumns, "pattern.tag_columns", "tag columns");
    return problem.empty() ? atLeastThree(g->tagRows, "pattern.tag_rows", "tag rows") : problem;
  }
  const auto& b = std::get<Checkerboard>(pattern);
  problem = atLeastThree(b.columns - 1, "pattern.columns", "inner corners a row");
  return problem.empty() ? atLeastThree(b.rows - 1, "pattern.rows", "inner corners a column") : problem;
}

std::string kalibrTargetYaml(const TargetPattern& pattern) {
  if (const std::string problem = kalibrTargetProblem(pattern); !problem.empty()) throw InputError(problem);
  std::ostringstream yaml;
  if (const auto* g = std::get_if<AprilGrid>(&pattern)) {
    yaml << "target_type: 'aprilgrid'\n"
         << "tagCols: " << g->tagColumns << "\n"
         << "tagRows: " << g->tagRows << "\n"
         << "tagSize: " << yamlFloat(g->tagSize) << "\n"
         << "tagSpacing: " << yamlFloat(g->tagSpacing) << "\n";
    return yaml.str();
  }
  const auto& b = std::get<Checkerboard>(pattern);
  yaml << "target_type: 'checkerboard'\n"
       << "targetCols: " << b.columns - 1 << "\n"
       << "targetRows: " << b.rows - 1 << "\n"
       << "rowSpacingMeters: " << yamlFloat(b.square) << "\n"
       << "colSpacingMeters: " << yamlFloat(b.square) << "\n";
  return yaml.str();
}

std::string openCvCornerLists(const std::vector<CornerListImage>& images, bool mirrorImage) {
  cv::FileStorage fs(".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  // The points are where the image shows them; a catadioptric image is a mirror image, which
  // cv::omnidir fits with gamma_y < 0 or, flipped top to bottom (y -> height - 1 - y), as usual.
  // A lens camera's image is not one: its points calibrate as they are.
  if (mirrorImage)
    fs.writeComment("image_points: OpenCV pixels (centres at integers) of a mirror image: flip y to height - 1 - y for cv::omnidir::calibrate");
  else
    fs.writeComment("image_points: OpenCV pixels (centres at integers) of a lens camera's image (not a mirror image): calibrate with them as they are");
  fs << "mirror_image" << (mirrorImage ? 1 : 0);
  fs << "images" << "[";
  for (const CornerListImage& image : images) {
    const CalibrationView& v = image.view;
    cv::Mat object(static_cast<int>(v.targetPoints.size()), 1, CV_64FC3), raster(static_cast<int>(v.raster.size()), 1, CV_64FC2);
    for (size_t k = 0; k < v.targetPoints.size(); ++k) {
      object.at<cv::Vec3d>(static_cast<int>(k)) = {v.targetPoints[k].x(), v.targetPoints[k].y(), v.targetPoints[k].z()};
      raster.at<cv::Vec2d>(static_cast<int>(k)) = {v.raster[k].x() - 0.5, v.raster[k].y() - 0.5};
    }
    fs << "{" << "name" << image.name << "object_points" << object << "image_points" << raster << "}";
  }
  fs << "]";
  return fs.releaseAndGetString();
}

std::vector<CornerListImage> readOpenCvCornerLists(const std::string& text, const std::string& source) {
  std::vector<CornerListImage> out;
  try {
    cv::FileStorage fs(text, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
    const cv::FileNode images = fs["images"];
    if (!images.isSeq()) throw InputError(showPath(source) + ": images: missing or not a list");
    for (const cv::FileNode& node : images) {
      CornerListImage image;
      node["name"] >> image.name;
      cv::Mat object, raster;
      node["object_points"] >> object;
      node["image_points"] >> raster;
      if (object.type() != CV_64FC3 || raster.type() != CV_64FC2 || object.total() != raster.total())
        throw InputError(showPath(source) + ": images[" + std::to_string(out.size()) +
                         "]: object_points (N×1, 3 channels) and image_points (N×1, 2 channels) must match");
      if (object.cols != 1 || raster.cols != 1 || !cv::checkRange(object) || !cv::checkRange(raster))
        throw InputError(showPath(source) + ": images[" + std::to_string(out.size()) +
                         "]: points must be N×1 and finite");
      for (size_t k = 0; k < object.total(); ++k) {
        const cv::Vec3d p = object.at<cv::Vec3d>(static_cast<int>(k));
        const cv::Vec2d r = raster.at<cv::Vec2d>(static_cast<int>(k));
        image.view.targetPoints.emplace_back(p[0], p[1], p[2]);
        image.view.raster.emplace_back(r[0] + 0.5, r[1] + 0.5);
      }
      out.push_back(std::move(image));
    }
  } catch (const cv::Exception& e) {
    throw InputError(showPath(source) + ": not an OpenCV corner list (" + e.msg + ")");
  }
  return out;
}

}  // namespace omnicam
