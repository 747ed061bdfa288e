#include "omnidir_fit.h"

#include <opencv2/ccalib/omnidir.hpp>
#include <opencv2/core.hpp>

namespace omnicam {

OmnidirCalibration calibrateOmnidir(const std::vector<CalibrationView>& views, int width, int height,
                                    const OmnidirOptions& o) {
  const bool mirrored = o.handedness == ImageHandedness::Mirrored;
  // OpenCV takes one 1×N matrix per view (CV_64FC3 and CV_64FC2; N×3 single-channel throws).
  std::vector<cv::Mat> objectPoints, imagePoints;
  for (const CalibrationView& v : views) {
    cv::Mat object(1, static_cast<int>(v.targetPoints.size()), CV_64FC3), image(1, static_cast<int>(v.raster.size()), CV_64FC2);
    for (size_t k = 0; k < v.targetPoints.size(); ++k) {
      object.at<cv::Vec3d>(0, static_cast<int>(k)) = {v.targetPoints[k].x(), v.targetPoints[k].y(), v.targetPoints[k].z()};
      // omnicam's raster has pixel centres at +0.5, OpenCV's at integers; mirrored: flipped top to bottom.
      const double x = v.raster[k].x() - 0.5, y = mirrored ? height - v.raster[k].y() - 0.5 : v.raster[k].y() - 0.5;
      image.at<cv::Vec2d>(0, static_cast<int>(k)) = {x, y};
    }
    objectPoints.push_back(object);
    imagePoints.push_back(image);
  }
  int flags = 0;
  if (o.fixSkew) flags |= cv::omnidir::CALIB_FIX_SKEW;
  if (o.fixDistortion)
    flags |= cv::omnidir::CALIB_FIX_K1 | cv::omnidir::CALIB_FIX_K2 | cv::omnidir::CALIB_FIX_P1 | cv::omnidir::CALIB_FIX_P2;
  cv::Mat K, xi, D, idx;
  std::vector<cv::Mat> rvecs, tvecs;
  OmnidirCalibration r;
  try {
    // The criteria's type must be COUNT + EPS exactly, or the loop never ends.
    r.rms = cv::omnidir::calibrate(objectPoints, imagePoints, cv::Size(width, height), K, xi, D, rvecs, tvecs, flags,
                                   cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, o.maxIterations, o.epsilon),
                                   idx);
  } catch (const cv::Exception& e) {
    r.failure = e.what();
    return r;
  }
  if (idx.empty() || K.empty()) {
    r.failure = "OpenCV's initialisation kept no view";
    return r;
  }
  r.converged = true;
  for (int k = 0; k < static_cast<int>(idx.total()); ++k) r.usedViews.push_back(idx.at<int>(k));
  r.xi = xi.at<double>(0);
  r.gammaX = K.at<double>(0, 0);
  r.skew = mirrored ? -K.at<double>(0, 1) : K.at<double>(0, 1);  // it multiplies y, which the flip negates
  r.cx = K.at<double>(0, 2);
  r.gammaY = mirrored ? -K.at<double>(1, 1) : K.at<double>(1, 1);
  r.cy = mirrored ? height - 1 - K.at<double>(1, 2) : K.at<double>(1, 2);
  for (int k = 0; k < 4; ++k) r.distortion[static_cast<size_t>(k)] = D.at<double>(k);
  if (mirrored) r.distortion[2] = -r.distortion[2];  // p1 multiplies y' = -y: its sign flips with the image
  return r;
}

}  // namespace omnicam
