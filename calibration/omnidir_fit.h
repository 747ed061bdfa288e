#pragma once
// A calibration as a user runs one: OpenCV's cv::omnidir::calibrate (Mei's unified model with
// radial-tangential distortion, opencv_contrib) from corner observations.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "central_fit.h"
#include "geometry.h"
#include "target_detection.h"

namespace omnicam {

// cv::omnidir::calibrate's linker name (OpenCV 4's C++ signature), which calibrateOmnidir looks up
// when it loads OpenCV's ccalib module at its first call (tested against the linked function).
inline constexpr const char* kOmnidirCalibrateSymbol =
    "_ZN2cv7omnidir9calibrateERKNS_11_InputArrayES3_NS_5Size_IiEERKNS_17_InputOutputArrayES8_S8_RKNS_12_OutputArrayESB_iNS_"
    "12TermCriteriaESB_";

// One image's observations: target-frame corners and where they are imaged (omnicam raster).
struct CalibrationView {
  std::vector<Vec3> targetPoints;
  std::vector<Vec2> raster;
};

// The view of corners found by index (a detector's, or the exact ones) on a target whose corners
// are `targetPoints` (targetCorners' order).
CalibrationView calibrationView(const std::vector<Vec3>& targetPoints, const std::vector<DetectedCorner>& corners);

struct OmnidirOptions {
  bool fixDistortion = false;  // k1, k2, p1, p2 held at zero
  bool fixSkew = true;
  // A catadioptric image is a mirror image: OpenCV calibrates it flipped top to bottom, and the
  // result is flipped back (gamma_y < 0, as omnicam's own intrinsics, docs/conventions.md).
  ImageHandedness handedness = ImageHandedness::Mirrored;
  int maxIterations = 300;
  double epsilon = 1e-12;
};

// What the calibration found, in omnicam's intrinsics' terms (the camera's describe(): OpenCV's
// pixel centres at integers).
struct OmnidirCalibration {
  bool converged = false;   // false: OpenCV's initialisation kept no view, or it threw
  std::string failure;      // why, when it did not
  double rms = 0.0;         // reprojection error, px
  double xi = 0.0, gammaX = 0.0, gammaY = 0.0, skew = 0.0, cx = 0.0, cy = 0.0;
  std::array<double, 4> distortion{};  // k1, k2, p1, p2
  std::vector<int> usedViews;          // the views OpenCV's initialisation kept
  std::vector<Rigid> cameraFromTarget;  // per used view: the target in the fitted camera frame
};

// The memory cv::omnidir::calibrate takes for `views` (its Gauss-Newton steps hold a dense
// Jacobian of every corner by every view's pose): calibrateOmnidir requires it first
// (MemoryShortage, not an allocation failure deep in OpenCV).
int64_t omnidirFitBytes(const std::vector<CalibrationView>& views);

OmnidirCalibration calibrateOmnidir(const std::vector<CalibrationView>& views, int width, int height,
                                    const OmnidirOptions& options);

// The calibrated model placed in the rig: its intrinsics, and its camera frame in the rig's
// viewpoint frame from the calibration's own extrinsics against the true board poses
// (viewpointFromTarget, one per input view), averaged over the views it used. What a user's
// calibrated camera is, to be measured against the truth like the best-fit central model.
CentralApproximation calibratedModel(const OmnidirCalibration& fit, const std::vector<Rigid>& viewpointFromTarget);

// A central model's reprojection error (px) and ray error (mrad) for points `distanceM` from its
// viewpoint along the camera's true rays (0: at infinity), over every pixel centre the camera
// images (central_fit.h's maps) where the model projects the point and has a ray; the others are
// its unmodelled share (a calibration whose model images less than the camera does).
struct HeldOutError {
  double distanceM = 0.0;
  double medianPx = 0.0, rmsPx = 0.0, maxPx = 0.0;
  double medianMrad = 0.0, rmsMrad = 0.0;
  double unmodelledShare = 0.0;
};
HeldOutError heldOutError(const Camera& camera, const CentralApproximation& model, double distanceM);
// The same over rays traced once (pixelRays), for many models or distances of one camera.
HeldOutError heldOutError(const PixelRays& rays, const CentralApproximation& model, double distanceM);

}  // namespace omnicam
