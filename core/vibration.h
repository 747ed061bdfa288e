#pragma once
// Vibration (docs/motion.md, "Vibration"): the rig of a shaking robot, perturbed afresh for every
// frame and camera. Each perturbation is drawn uniformly within ± its amplitude from a stream
// that depends only on (seed, frame, camera), so a resumed, sharded or reordered run perturbs
// every frame the same way.
#include <array>
#include <cstdint>

#include "rig.h"

namespace omnicam {

struct Vibration {
  uint64_t seed = 0;
  std::array<double, 3> cameraOffsetMm{0.0, 0.0, 0.0};    // added to rig.camera.offset_mm
  std::array<double, 3> cameraRotationDeg{0.0, 0.0, 0.0};  // added to rig.camera.rotation_deg
  std::array<double, 2> rigTiltDeg{0.0, 0.0};              // added to rig.tilt_deg (roll, pitch)
  bool none() const {
    return cameraOffsetMm == std::array<double, 3>{} && cameraRotationDeg == std::array<double, 3>{} &&
           rigTiltDeg == std::array<double, 2>{};
  }
  bool operator==(const Vibration&) const = default;
};

// `rig` as it is during frame `frame` of camera `camera`: every amplitude's perturbation added.
// Without amplitudes, `rig` itself.
RigSpec vibratedRig(const RigSpec& rig, const Vibration& vibration, uint64_t frame, uint64_t camera);

}  // namespace omnicam
