#include "omnidir_fit.h"

#include <opencv2/ccalib/omnidir.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "errors.h"
#include "memory_budget.h"

namespace omnicam {

CalibrationView calibrationView(const std::vector<Vec3>& targetPoints, const std::vector<DetectedCorner>& corners) {
  CalibrationView view;
  for (const DetectedCorner& c : corners) {
    view.targetPoints.push_back(targetPoints[static_cast<size_t>(c.index)]);
    view.raster.push_back(c.raster);
  }
  return view;
}

namespace {

// cv::omnidir::calibrate's own type (decltype: the header only, no link to its library).
using OmnidirCalibrate = decltype(&cv::omnidir::calibrate);

// Linking ccalib would load its highgui, videoio and imgcodecs (~150 shared libraries) into every
// omnicam process at start-up; only calibrations need it, so it is loaded here, once.
OmnidirCalibrate omnidirCalibrate() {
  static const OmnidirCalibrate function = [] {
    void* library = ::dlopen(OMNICAM_OPENCV_CCALIB, RTLD_NOW | RTLD_LOCAL);
    if (!library)
      throw ExternalError(std::string("cannot load OpenCV's ccalib module (") + ::dlerror() + "): make deps installs it");
    void* symbol = ::dlsym(library, kOmnidirCalibrateSymbol);
    if (!symbol) throw ExternalError(std::string("OpenCV's ccalib module has no cv::omnidir::calibrate (") + ::dlerror() + ")");
    return reinterpret_cast<OmnidirCalibrate>(symbol);
  }();
  return function;
}

}  // namespace

int64_t omnidirFitBytes(const std::vector<CalibrationView>& views) {
  int64_t points = 0;
  for (const CalibrationView& v : views) points += static_cast<int64_t>(v.raster.size());
  const int64_t parameters = 6 * static_cast<int64_t>(views.size()) + 10;
  // A dense Jacobian (2 rows a corner, 6 columns a view and 10 for the camera) and its transpose,
  // JᵀJ and its inverse, in doubles.
  return 8 * (2 * (2 * points) * parameters + 2 * parameters * parameters);
}

OmnidirCalibration calibrateOmnidir(const std::vector<CalibrationView>& views, int width, int height,
                                    const OmnidirOptions& o) {
  const bool mirrored = o.handedness == ImageHandedness::Mirrored;
  // OpenCV takes one 1×N matrix per view (CV_64FC3 and CV_64FC2; N×3 single-channel throws).
  std::vector<cv::Mat> objectPoints, imagePoints;
  for (const CalibrationView& v : views) {
    if (v.targetPoints.size() != v.raster.size())
      throw std::invalid_argument("calibrateOmnidir: a view's target points and raster points differ in number");
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
  requireMemory(omnidirFitBytes(views), "fitting cv::omnidir to " + std::to_string(views.size()) + " views");
  int flags = 0;
  if (o.fixSkew) flags |= cv::omnidir::CALIB_FIX_SKEW;
  if (o.fixDistortion)
    flags |= cv::omnidir::CALIB_FIX_K1 | cv::omnidir::CALIB_FIX_K2 | cv::omnidir::CALIB_FIX_P1 | cv::omnidir::CALIB_FIX_P2;
  cv::Mat K, xi, D, idx;
  std::vector<cv::Mat> rvecs, tvecs;
  OmnidirCalibration r;
  try {
    // The criteria's type must be COUNT + EPS exactly, or the loop never ends.
    r.rms = omnidirCalibrate()(objectPoints, imagePoints, cv::Size(width, height), K, xi, D, rvecs, tvecs, flags,
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
  r.skew = K.at<double>(0, 1);
  r.cx = K.at<double>(0, 2);
  r.gammaY = mirrored ? -K.at<double>(1, 1) : K.at<double>(1, 1);
  r.cy = mirrored ? height - 1 - K.at<double>(1, 2) : K.at<double>(1, 2);
  for (int k = 0; k < 4; ++k) r.distortion[static_cast<size_t>(k)] = D.at<double>(k);
  // The flip changes v = γy·y_d + cy into H − 1 − v: the same camera frame and distorted point
  // (x_d, y_d), so skew, distortion and extrinsics are the image's own; only γy and cy change.
  for (size_t k = 0; k < rvecs.size(); ++k) {
    cv::Mat rotation;
    cv::Rodrigues(rvecs[k], rotation);
    Rigid t = Rigid::Identity();
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) t.linear()(a, b) = rotation.at<double>(a, b);
      t.translation()(a) = tvecs[k].at<double>(a);
    }
    r.cameraFromTarget.push_back(t);
  }
  return r;
}

CentralApproximation calibratedModel(const OmnidirCalibration& fit, const std::vector<Rigid>& viewpointFromTarget) {
  if (!fit.converged || fit.cameraFromTarget.empty() || fit.cameraFromTarget.size() != fit.usedViews.size())
    throw std::invalid_argument("calibratedModel: the calibration did not converge");
  for (int view : fit.usedViews)
    if (view < 0 || static_cast<size_t>(view) >= viewpointFromTarget.size())
      throw std::invalid_argument("calibratedModel: a used view has no true board pose");
  // omnicam's Mei model has no skew: a calibration that fitted one cannot be placed as it is.
  if (fit.skew != 0.0) throw std::invalid_argument("calibratedModel: the calibration fitted a skew (calibrate with fixSkew)");
  CentralApproximation model;
  model.intrinsics.xi = fit.xi;
  model.intrinsics.gammaX = fit.gammaX;
  model.intrinsics.gammaY = fit.gammaY;
  model.intrinsics.cx = fit.cx;
  model.intrinsics.cy = fit.cy;
  model.intrinsics.lens.k1 = fit.distortion[0];
  model.intrinsics.lens.k2 = fit.distortion[1];
  model.intrinsics.lens.p1 = fit.distortion[2];
  model.intrinsics.lens.p2 = fit.distortion[3];
  // cameraFromViewpoint = cameraFromTarget · targetFromViewpoint, per view; the mean of the
  // rotations (as quaternions, signs aligned) and of the translations.
  Eigen::Vector4d quaternionSum = Eigen::Vector4d::Zero();
  Vec3 translationSum = Vec3::Zero();
  Eigen::Quaterniond first;
  for (size_t k = 0; k < fit.cameraFromTarget.size(); ++k) {
    const Rigid cameraFromViewpoint = fit.cameraFromTarget[k] * viewpointFromTarget[static_cast<size_t>(fit.usedViews[k])].inverse();
    Eigen::Quaterniond q(cameraFromViewpoint.linear());
    if (k == 0) first = q;
    if (q.dot(first) < 0.0) q.coeffs() = -q.coeffs();
    quaternionSum += q.coeffs();
    translationSum += cameraFromViewpoint.translation();
  }
  const double views = static_cast<double>(fit.cameraFromTarget.size());
  model.cameraFromViewpoint.linear() = Eigen::Quaterniond(quaternionSum.normalized()).toRotationMatrix();
  model.cameraFromViewpoint.translation() = translationSum / views;
  model.viewpoint = model.cameraFromViewpoint.inverse().translation();
  return model;
}

namespace {

struct MapStatistics {
  double median = 0.0, rms = 0.0, max = 0.0;
  double unmodelledShare = 0.0;
};

// Over the map's imaged pixels (NaN: not imaged); infinite errors (the model has no projection
// or ray there) are counted apart.
MapStatistics statistics(const std::vector<float>& map) {
  std::vector<float> errors;
  size_t imaged = 0;
  for (float e : map) {
    imaged += !std::isnan(e);
    if (std::isfinite(e)) errors.push_back(e);
  }
  MapStatistics s;
  if (imaged > 0) s.unmodelledShare = 1.0 - static_cast<double>(errors.size()) / static_cast<double>(imaged);
  if (errors.empty()) return s;
  double squares = 0.0;
  for (float e : errors) {
    squares += static_cast<double>(e) * e;
    s.max = std::max(s.max, static_cast<double>(e));
  }
  s.rms = std::sqrt(squares / static_cast<double>(errors.size()));
  std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(errors.size() / 2), errors.end());
  s.median = errors[errors.size() / 2];
  return s;
}

}  // namespace

HeldOutError heldOutError(const Camera& camera, const CentralApproximation& model, double distanceM) {
  return heldOutError(pixelRays(camera), model, distanceM);
}

HeldOutError heldOutError(const PixelRays& rays, const CentralApproximation& model, double distanceM) {
  const MapStatistics px = statistics(centralResidualMap(rays, model, distanceM));
  const MapStatistics rad = statistics(centralRayErrorMap(rays, model, distanceM));
  HeldOutError h;
  h.distanceM = distanceM;
  h.medianPx = px.median, h.rmsPx = px.rms, h.maxPx = px.max;
  h.medianMrad = 1e3 * rad.median, h.rmsMrad = 1e3 * rad.rms;
  h.unmodelledShare = std::max(px.unmodelledShare, rad.unmodelledShare);
  return h;
}

}  // namespace omnicam
