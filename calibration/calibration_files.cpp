#include "calibration_files.h"

#include <opencv2/core.hpp>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <set>
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

namespace {

// The `key: value` lines of a Kalibr target file, each key once; InputError naming `source`.
std::map<std::string, std::string> kalibrFields(const std::string& text, const std::string& source) {
  std::map<std::string, std::string> fields;
  std::istringstream lines(text);
  int number = 0;
  for (std::string line; std::getline(lines, line);) {
    ++number;
    if (line.empty()) continue;
    const size_t colon = line.find(": ");
    if (colon == std::string::npos || colon == 0)
      throw InputError(showPath(source) + ": line " + std::to_string(number) + ": not `key: value` as omnicam writes it");
    const std::string key = line.substr(0, colon);
    if (!fields.emplace(key, line.substr(colon + 2)).second)
      throw InputError(showPath(source) + ": " + quote(key) + " given twice");
  }
  return fields;
}

// A number as yamlFloat writes it; nullopt for anything else.
std::optional<double> finiteNumber(const std::string& text) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace

TargetPattern targetPatternFromKalibrYaml(const std::string& text, const std::string& source) {
  const std::map<std::string, std::string> fields = kalibrFields(text, source);
  const auto field = [&](const std::string& key) -> const std::string& {
    const auto it = fields.find(key);
    if (it == fields.end()) throw InputError(showPath(source) + ": " + key + ": missing");
    return it->second;
  };
  // The scene format's bounds of a target (scene/target_fields.cpp), Kalibr's at least 3 a side.
  const auto count = [&](const std::string& key, int most) {
    const std::string& value = field(key);
    const bool digits = !value.empty() && value.size() <= 4 && value.find_first_not_of("0123456789") == std::string::npos;
    const int n = digits ? std::stoi(value) : 0;
    if (n < 3 || n > most)
      throw InputError(showPath(source) + ": " + key + ": must be an integer from 3 to " + std::to_string(most) + " (got " + quote(value) + ")");
    return n;
  };
  const auto length = [&](const std::string& key, double least, double most) {
    const std::string& value = field(key);
    const std::optional<double> v = finiteNumber(value);
    if (!v || !(*v >= least && *v <= most))
      throw InputError(showPath(source) + ": " + key + ": must be a number in [" + shortNumber(least) + ", " + shortNumber(most) +
                       "] (got " + quote(value) + ")");
    return *v;
  };
  const std::string& type = field("target_type");
  TargetPattern pattern;
  std::set<std::string> keys{"target_type"};
  if (type == "'aprilgrid'") {
    pattern = AprilGrid{count("tagRows", 100), count("tagCols", 100), length("tagSize", 1e-3, 10.0), length("tagSpacing", 1e-9, 1.0), 0};
    keys.insert({"tagCols", "tagRows", "tagSize", "tagSpacing"});
  } else if (type == "'checkerboard'") {
    const double square = length("rowSpacingMeters", 1e-4, 10.0);
    if (length("colSpacingMeters", 1e-4, 10.0) != square)
      throw InputError(showPath(source) + ": colSpacingMeters: must equal rowSpacingMeters (omnicam's squares are square)");
    const Checkerboard board{count("targetRows", 999) + 1, count("targetCols", 999) + 1, square};
    if ((board.rows + board.columns) % 2 == 0)
      throw InputError(showPath(source) + ": targetCols: one of targetRows, targetCols must be even, the other odd (a board "
                                          "without them has no first corner a detector can tell)");
    pattern = board;
    keys.insert({"targetCols", "targetRows", "rowSpacingMeters", "colSpacingMeters"});
  } else {
    throw InputError(showPath(source) + ": target_type: must be 'aprilgrid' or 'checkerboard' (got " + quote(type) + ")");
  }
  for (const auto& [key, value] : fields)
    if (!keys.count(key)) throw InputError(showPath(source) + ": " + quote(key) + ": not a field of this target type");
  // A target the scene format would refuse (ids past the tag family, a spacing off the texel grid,
  // a checkerboard whose orientation cannot be told) is no target omnicam wrote.
  if (const std::string problem = targetPatternProblem(pattern, 0.0); !problem.empty())
    throw InputError(showPath(source) + ": not a target omnicam writes: " + problem);
  return pattern;
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

std::string omnidirCalibrationYaml(const OmnidirCalibration& fit, const std::string& camera, int width, int height, bool mirrorImage) {
  cv::FileStorage fs(".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  fs.writeComment(mirrorImage ? "cv::omnidir::calibrate (Mei's unified model), OpenCV's pixel centres at integers; a mirror image, fitted "
                                "flipped top to bottom and flipped back (gamma_y < 0)"
                              : "cv::omnidir::calibrate (Mei's unified model), OpenCV's pixel centres at integers");
  fs << "camera" << camera << "image_width" << width << "image_height" << height << "mirror_image" << (mirrorImage ? 1 : 0);
  fs << "rms" << fit.rms << "views" << static_cast<int>(fit.usedViews.size());
  fs << "camera_matrix" << cv::Mat(cv::Matx33d(fit.gammaX, fit.skew, fit.cx, 0.0, fit.gammaY, fit.cy, 0.0, 0.0, 1.0)) << "xi" << fit.xi;
  fs << "distortion_coefficients"
     << cv::Mat(cv::Matx14d(fit.distortion[0], fit.distortion[1], fit.distortion[2], fit.distortion[3]));
  return fs.releaseAndGetString();
}

}  // namespace omnicam
