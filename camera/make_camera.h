#pragma once
// The camera of a rig: the closed-form central model when the rig is ideal, else the physical
// camera traced through the mirror. `traced` asks for the physical camera even for the ideal rig
// (the check that both agree).
#include <memory>

#include "camera.h"
#include "central_fit.h"

namespace omnicam {

std::shared_ptr<const Camera> makeCamera(const RigSpec& rig, bool traced = false);

// makeCamera(rig)->describe(), remembered for the last few rigs: a non-central rig's description
// holds its best-fit central model (tens of milliseconds to fit), and a rendered path writes one
// sidecar per frame of the same rig. Thread-safe.
nlohmann::json describeCamera(const RigSpec& rig);

// The unified (Mei) model to give tools that assume one (cv::omnidir, Kalibr, camodocal): exact
// for the ideal rig and for the aligned pinhole with a k3-free lens; otherwise the best fit.
struct CentralModel {
  MeiIntrinsics intrinsics;
  // Set when the model is not exact: the fit, its camera frame and its residuals (central_fit.h).
  std::optional<CentralApproximation> approximation;
  std::optional<double> rimRadiusPx;  // the rim's circle about (cx, cy), where the rim is one
  // The model's camera frame: the fit's, or the unified model's (omni_camera.h) when exact.
  Rigid cameraFromViewpoint() const;
};
CentralModel centralModelOf(const Camera& camera);

}  // namespace omnicam
