#pragma once
// Vibration (docs/motion.md, "Vibration"): the rig of a shaking robot, perturbed afresh for every
// frame and camera. Each perturbation is drawn uniformly within ± its amplitude from a stream
// that depends only on (seed, frame, camera), so a resumed, sharded or reordered run perturbs
// every frame the same way.
#include <array>
#include <cstdint>

#include "placement.h"
#include "rig.h"

namespace omnicam {

struct Vibration {
  uint64_t seed = 0;
  std::array<double, 3> cameraOffsetMm{0.0, 0.0, 0.0};    // added to rig.camera.offset_mm
  std::array<double, 3> cameraRotationDeg{0.0, 0.0, 0.0};  // added to rig.camera.rotation_deg (a lens camera's rig.lens.rotation_deg)
  // Tilts (roll, pitch): each camera's rig on its own (added to its rig.tilt_deg, drawn per
  // camera), and the whole robot (added to its tilt, drawn once per frame: every camera alike).
  std::array<double, 2> rigTiltDeg{0.0, 0.0};
  std::array<double, 2> robotTiltDeg{0.0, 0.0};
  // Whether it shakes each camera's rig (not only the robot's tilt).
  bool shakesRigs() const {
    return cameraOffsetMm != std::array<double, 3>{} || cameraRotationDeg != std::array<double, 3>{} ||
           rigTiltDeg != std::array<double, 2>{};
  }
  bool none() const {
    return cameraOffsetMm == std::array<double, 3>{} && cameraRotationDeg == std::array<double, 3>{} &&
           rigTiltDeg == std::array<double, 2>{} && robotTiltDeg == std::array<double, 2>{};
  }
  bool operator==(const Vibration&) const = default;
};

// `rig` as it is during frame `frame` of camera `camera`: every amplitude's perturbation added.
// Without amplitudes, `rig` itself.
RigSpec vibratedRig(const RigSpec& rig, const Vibration& vibration, uint64_t frame, uint64_t camera);
// The robot's tilt during frame `frame`: `tilt` plus the robot-tilt amplitude's perturbation,
// from a stream of its own (no camera's). Without that amplitude, `tilt` itself.
RobotTilt vibratedRobotTilt(const RobotTilt& tilt, const Vibration& vibration, uint64_t frame);

}  // namespace omnicam
