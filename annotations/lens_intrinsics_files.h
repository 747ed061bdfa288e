#pragma once
// A lens camera's intrinsics (lens_camera.h) in the layouts other tools read, where a layout for
// its model exists (docs/lens-cameras.md lists which):
//   OpenCV (cv::FileStorage): cv::fisheye for Kannala–Brandt and the equidistant f-θ lens
//     (camera_model fisheye, K, D = k1..k4), calib3d for the pinhole (camera_model pinhole, K,
//     D = k1, k2, p1, p2, k3);
//   Kalibr camchain: pinhole-equi (Kannala–Brandt, equidistant), ds, eucm, pinhole-radtan (a
//     pinhole without k3), every number a float as Kalibr's reader demands;
//   camodocal: KANNALA_BRANDT (k2..k5 = OpenCV's k1..k4), PINHOLE (without k3).
// All in OpenCV's pixel convention (centres at integers) and camera frame (X right, Y down, Z
// forward): the lens' frame, which poses.tum and the sidecar's camera_from_world give.
#include <optional>
#include <string>
#include <vector>

#include "lens_camera.h"

namespace omnicam {

// The Kannala–Brandt view of a lens, where it is one: Kannala–Brandt itself, or the equidistant
// f-θ lens (k = 0).
std::optional<KannalaBrandt> asKannalaBrandt(const LensModel& model);
// A pinhole Kalibr and camodocal describe: their radtan has no k3.
const PinholeRadTan* asFourCoefficientPinhole(const LensModel& model);

// A lens in Kalibr's (and EuRoC's sensor.yaml's) terms: camera_model, intrinsics, distortion.
struct KalibrLens {
  std::string cameraModel;       // pinhole, ds, eucm
  std::vector<double> intrinsics;  // in Kalibr's order for the model
  std::string distortionModel;   // equidistant, radtan, none
  std::vector<double> coefficients;
};
std::optional<KalibrLens> kalibrLensOf(const LensModel& model);

std::optional<std::string> openCvLensYaml(const LensCamera& camera);
std::optional<std::string> kalibrLensYaml(const std::string& name, const LensCamera& camera);
std::optional<std::string> camodocalLensYaml(const std::string& name, const LensCamera& camera);

}  // namespace omnicam
