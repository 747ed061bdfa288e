#include "vibration.h"

namespace omnicam {

namespace {

// SplitMix64 (Steele, Lea, Flood 2014): a counter-based stream, so frame k's perturbation needs
// no other frame's.
uint64_t splitMix64(uint64_t& state) {
  uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

class UniformStream {
 public:
  UniformStream(uint64_t seed, uint64_t frame, uint64_t camera) : state_(seed) {
    // Frame and camera mixed into the start, each through a full round, so that neighbouring
    // frames and cameras start unrelated streams.
    state_ = splitMix64(state_) ^ frame;
    state_ = splitMix64(state_) ^ camera;
    (void)splitMix64(state_);
  }
  // Uniform in [−amplitude, amplitude): 53 random bits, exact in a double.
  double within(double amplitude) {
    const double unit = static_cast<double>(splitMix64(state_) >> 11) * 0x1.0p-53;
    return amplitude * (2.0 * unit - 1.0);
  }

 private:
  uint64_t state_;
};

}  // namespace

RigSpec vibratedRig(const RigSpec& rig, const Vibration& vibration, uint64_t frame, uint64_t camera) {
  if (!vibration.shakesRigs()) return rig;
  UniformStream draw(vibration.seed, frame, camera);
  RigSpec out = rig;
  // A lens camera has no camera below a mirror to move (the dataset refuses an offset amplitude
  // for one) and turns as a whole: [roll, pitch, yaw] of its lens. Its offsets are drawn all the
  // same, so that every camera's stream stays what it is.
  std::array<double, 3> offsetMm{}, rotationDeg{};
  for (int k = 0; k < 3; ++k) offsetMm[k] = draw.within(vibration.cameraOffsetMm[k]);
  for (int k = 0; k < 3; ++k) rotationDeg[k] = draw.within(vibration.cameraRotationDeg[k]);
  std::visit(Overloaded{[&](MirrorRig& mirror) {
                          for (int k = 0; k < 3; ++k) mirror.mount.offsetMm[k] += offsetMm[k];
                          for (int k = 0; k < 3; ++k) mirror.mount.rotationDeg[k] += rotationDeg[k];
                        },
                        [&](LensCameraSpec& lens) {
                          for (int k = 0; k < 3; ++k) lens.rotationDeg[k] += rotationDeg[k];
                        }},
             out.kind);
  for (int k = 0; k < 2; ++k) out.tiltDeg[k] += draw.within(vibration.rigTiltDeg[k]);
  return out;
}

RobotTilt vibratedRobotTilt(const RobotTilt& tilt, const Vibration& vibration, uint64_t frame) {
  if (vibration.robotTiltDeg == RobotTilt{0.0, 0.0}) return tilt;
  // The robot's stream: camera index 2^64 − 1, which no camera has (kMaxDatasetCameras).
  UniformStream draw(vibration.seed, frame, ~uint64_t{0});
  RobotTilt out = tilt;
  for (int k = 0; k < 2; ++k) out[k] += draw.within(vibration.robotTiltDeg[k]);
  return out;
}

}  // namespace omnicam
