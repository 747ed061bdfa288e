#pragma once
// Reading a dataset camera back into OpenCV's cv::omnidir terms: the intrinsics of
// intrinsics/opencv.yaml and, from a camera_from_world transform (the inverse of a poses.tum
// line), the rvec/tvec that cv::omnidir::projectPoints takes. Header-only: OpenCV stays out of
// the library's interface for everyone else.
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "geometry.h"

namespace omnicam {

struct OmnidirIntrinsics {
  cv::Mat K, D;
  double xi = 0.0;
};

inline OmnidirIntrinsics readOmnidirIntrinsics(const cv::FileStorage& fs) {
  OmnidirIntrinsics k;
  fs["K"] >> k.K;
  fs["D"] >> k.D;
  fs["xi"] >> k.xi;
  return k;
}

// rvec (Rodrigues) and tvec of `cameraFromWorld`.
inline void omnidirExtrinsics(const Rigid& cameraFromWorld, cv::Mat& rvec, cv::Mat& tvec) {
  cv::Mat rotation(3, 3, CV_64F);
  tvec.create(3, 1, CV_64F);
  for (int i = 0; i < 3; ++i) {
    tvec.at<double>(i) = cameraFromWorld.translation()[i];
    for (int j = 0; j < 3; ++j) rotation.at<double>(i, j) = cameraFromWorld.linear()(i, j);
  }
  cv::Rodrigues(rotation, rvec);
}

}  // namespace omnicam
