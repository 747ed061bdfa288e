#include "target_detection.h"

#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace omnicam {

namespace {

// 8-bit sRGB grey, as a camera's file would hold it; flipped left to right for a mirrored image,
// so that detectors see the world the right way round.
cv::Mat greyOf(const ImageRGBA& image, ImageHandedness handedness) {
  cv::Mat grey(image.height, image.width, CV_8UC1);
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i) {
      const float* p = image.at(i, j);
      const float encoded = linearToSrgb(std::clamp((p[0] + p[1] + p[2]) / 3.0f, 0.0f, 1.0f));
      const int column = handedness == ImageHandedness::Mirrored ? image.width - 1 - i : i;
      grey.at<uint8_t>(j, column) = static_cast<uint8_t>(std::lround(255.0f * encoded));
    }
  return grey;
}

// OpenCV's point in the grey image (pixel centres at integers) as omnicam's raster point.
Vec2 rasterOf(const cv::Point2f& p, int width, ImageHandedness handedness) {
  const double x = handedness == ImageHandedness::Mirrored ? width - 1 - p.x : p.x;
  return {x + 0.5, p.y + 0.5};
}

// A checkerboard's outer square counts as black below this grey level (8-bit sRGB).
constexpr double kDarkLevel = 100.0;

// Kalibr's limit on how far cornerSubPix may move a detected corner (px²).
constexpr double kMaxSubpixelShiftSquared = 1.5;

// AprilTag reads the image magnified this much (measured on 720-px omnidirectional frames, where
// tags are 12-35 px: 2× decodes none of 36 tags, 4× 21, 5× 28, 6× 25).
constexpr int kDetectionMagnification = 5;

double cross(const cv::Point2f& a, const cv::Point2f& b) { return static_cast<double>(a.x) * b.y - static_cast<double>(a.y) * b.x; }

}  // namespace

std::vector<DetectedCorner> detectCheckerboard(const ImageRGBA& image, const Checkerboard& board, ImageHandedness handedness) {
  const cv::Mat grey = greyOf(image, handedness);
  const int columns = board.columns - 1, rows = board.rows - 1;
  std::vector<cv::Point2f> found;
  if (!cv::findChessboardCornersSB(grey, cv::Size(columns, rows), found, cv::CALIB_CB_EXHAUSTIVE | cv::CALIB_CB_ACCURACY))
    return {};
  // OpenCV orders the corners row by row from one of the board's ends, either way round. Of the
  // four orders the board's shape allows, ours runs right along x and up along y as the (now
  // unmirrored) image shows them — counter-clockwise with the image's y down — and starts at
  // the corner whose outer diagonal square is black.
  const auto at = [&](int order, int r, int c) -> const cv::Point2f& {
    const int rr = (order & 1) ? rows - 1 - r : r, cc = (order & 2) ? columns - 1 - c : c;
    return found[static_cast<size_t>(rr * columns + cc)];
  };
  int chosen = -1, dark = 0;
  double darkest = 256.0;
  for (int order = 0; order < 4; ++order) {
    const cv::Point2f& origin = at(order, 0, 0);
    const cv::Point2f alongX = at(order, 0, std::min(1, columns - 1)) - origin, alongY = at(order, std::min(1, rows - 1), 0) - origin;
    if (!(cross(alongX, alongY) < 0.0)) continue;  // x right and y up: clockwise in image rows
    // Half a diagonal beyond the first corner: inside the outer corner square.
    const cv::Point2f outside = origin - 0.5f * (at(order, std::min(1, rows - 1), std::min(1, columns - 1)) - origin);
    const int x = static_cast<int>(std::lround(outside.x)), y = static_cast<int>(std::lround(outside.y));
    if (x < 0 || y < 0 || x >= grey.cols || y >= grey.rows) continue;
    const double level = grey.at<uint8_t>(y, x);
    if (level < kDarkLevel) ++dark;
    if (level < darkest) {
      darkest = level;
      chosen = order;
    }
  }
  // Both ends black (rows + columns even; the loader refuses such boards): no order to trust.
  if (chosen < 0 || dark != 1) return {};
  std::vector<DetectedCorner> corners;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) corners.push_back({r * columns + c, rasterOf(at(chosen, r, c), image.width, handedness)});
  return corners;
}

std::vector<DetectedCorner> detectAprilGrid(const ImageRGBA& image, const AprilGrid& grid, ImageHandedness handedness) {
  const cv::Mat grey = greyOf(image, handedness);
  // Kalibr's tags have a two-bit border: the family widened by two (AprilRobotics/apriltag#45).
  // Its corner squares split the white ring around each tag that AprilTag segments by: the
  // detector reads a dilated copy (black shrinks by a pixel), and the corners, X-junctions of
  // tag and corner square, are refined on the image itself.
  const std::unique_ptr<apriltag_family_t, void (*)(apriltag_family_t*)> owned(tag36h11_create(), tag36h11_destroy);
  apriltag_family_t* family = owned.get();
  family->width_at_border += 2;
  family->total_width += 2;
  for (uint32_t i = 0; i < family->nbits; ++i) {
    ++family->bit_x[i];
    ++family->bit_y[i];
  }
  const std::unique_ptr<apriltag_detector_t, void (*)(apriltag_detector_t*)> detector(apriltag_detector_create(),
                                                                                      apriltag_detector_destroy);
  apriltag_detector_add_family(detector.get(), family);
  detector->quad_decimate = 1.0f;
  detector->nthreads = 1;
  // Magnified first, so that the dilation shrinks black by a fifth of a pixel of the image: tag
  // bits of one or two pixels survive it.
  cv::Mat magnified, dilated;
  cv::resize(grey, magnified, cv::Size(), kDetectionMagnification, kDetectionMagnification, cv::INTER_LINEAR);
  cv::dilate(magnified, dilated, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3)));
  image_u8_t view{dilated.cols, dilated.rows, static_cast<int32_t>(dilated.step), dilated.data};
  const std::unique_ptr<zarray_t, void (*)(zarray_t*)> detections(apriltag_detector_detect(detector.get(), &view),
                                                                  apriltag_detections_destroy);
  std::vector<DetectedCorner> corners;
  std::vector<int> seen;
  const int tags = grid.tagRows * grid.tagColumns, pointsPerRow = 2 * grid.tagColumns;
  for (int k = 0; k < zarray_size(detections.get()); ++k) {
    apriltag_detection_t* d = nullptr;
    zarray_get(detections.get(), k, &d);
    const int t = d->id - grid.firstId;
    if (t < 0 || t >= tags || d->hamming > 0) continue;
    if (std::find(seen.begin(), seen.end(), t) != seen.end()) continue;  // a tag twice: keep the first
    seen.push_back(t);
    // Kalibr's points of tag t: bottom-left, bottom-right, top-right, top-left — AprilTag's
    // p[0..3].
    const int base = (t / grid.tagColumns) * 2 * pointsPerRow + (t % grid.tagColumns) * 2;
    const std::array<int, 4> indices = {base, base + 1, base + pointsPerRow + 1, base + pointsPerRow};
    std::vector<cv::Point2f> refined;
    // AprilTag's pixel centres are at +0.5 (of the magnified image); OpenCV's at integers.
    for (int i = 0; i < 4; ++i)
      refined.emplace_back(static_cast<float>(d->p[i][0] / kDetectionMagnification - 0.5),
                           static_cast<float>(d->p[i][1] / kDetectionMagnification - 0.5));
    // The refinement's window: about a tag bit, so that it holds the X-junction of tag and corner
    // square and no neighbour's; a tag a corner of which it moves further than Kalibr allows
    // (1.5 px²) is dropped.
    double side = 0.0;
    for (int i = 0; i < 4; ++i) side += 0.25 * cv::norm(refined[static_cast<size_t>(i)] - refined[static_cast<size_t>((i + 1) % 4)]);
    const int halfWindow = std::clamp(static_cast<int>(std::lround(side / 10.0)), 2, 4);
    const std::vector<cv::Point2f> detected = refined;
    cv::cornerSubPix(grey, refined, cv::Size(halfWindow, halfWindow), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 40, 0.001));
    bool steady = true;
    for (int i = 0; i < 4; ++i) {
      const cv::Point2f shift = refined[static_cast<size_t>(i)] - detected[static_cast<size_t>(i)];
      steady = steady && shift.dot(shift) <= kMaxSubpixelShiftSquared;
    }
    if (!steady) continue;  // as Kalibr: the tag's corners go together
    for (int i = 0; i < 4; ++i)
      corners.push_back({indices[static_cast<size_t>(i)], rasterOf(refined[static_cast<size_t>(i)], image.width, handedness)});
  }
  std::sort(corners.begin(), corners.end(), [](const DetectedCorner& a, const DetectedCorner& b) { return a.index < b.index; });
  return corners;
}

std::vector<DetectedCorner> detectTarget(const ImageRGBA& image, const TargetPattern& pattern, ImageHandedness handedness) {
  if (const auto* board = std::get_if<Checkerboard>(&pattern)) return detectCheckerboard(image, *board, handedness);
  return detectAprilGrid(image, std::get<AprilGrid>(pattern), handedness);
}

}  // namespace omnicam
