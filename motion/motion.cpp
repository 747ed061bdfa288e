#include "motion.h"

#include <cmath>

namespace omnicam {

namespace {

// sin(x)/x and (1 − cos x)/x, exact near 0 (their series) where the quotients lose digits.
double sinOverX(double x) { return std::abs(x) < 1e-4 ? 1.0 - x * x / 6.0 : std::sin(x) / x; }
double versineOverX(double x) { return std::abs(x) < 1e-4 ? x / 2.0 - x * x * x / 24.0 : (1.0 - std::cos(x)) / x; }

}  // namespace

Rigid worldFromRobot(const RobotPose& pose) {
  Rigid t = Rigid::Identity();
  t.translate(Vec3(pose.x, pose.y, 0.0));
  t.rotate(Eigen::AngleAxisd(radians(pose.yawDeg), Vec3::UnitZ()));
  return t;
}

RobotPose poseAfter(const RobotPose& start, const BodyVelocity& velocity, double seconds) {
  // The body frame turns at ω while moving at v in it: the displacement in the start's body frame
  // is ∫₀ᵗ R(ωs) v ds = t·[S −V; V S]·v with S = sin θ/θ, V = (1 − cos θ)/θ, θ = ωt.
  const double theta = radians(velocity.yawRateDegPerS) * seconds;
  const double s = sinOverX(theta) * seconds, v = versineOverX(theta) * seconds;
  const double forward = s * velocity.vx - v * velocity.vy, left = v * velocity.vx + s * velocity.vy;
  const double yaw = radians(start.yawDeg), c = std::cos(yaw), n = std::sin(yaw);
  return {start.x + c * forward - n * left, start.y + n * forward + c * left,
          start.yawDeg + velocity.yawRateDegPerS * seconds};
}

BodyVelocity velocityBetween(const RobotPose& from, const RobotPose& to, double seconds) {
  double turnDeg = std::remainder(to.yawDeg - from.yawDeg, 360.0);
  const double theta = radians(turnDeg);
  // The displacement in the start's body frame, then the inverse of poseAfter's matrix.
  const double yaw = radians(from.yawDeg), c = std::cos(yaw), n = std::sin(yaw);
  const double dx = to.x - from.x, dy = to.y - from.y;
  const double forward = c * dx + n * dy, left = -n * dx + c * dy;
  const double s = sinOverX(theta), v = versineOverX(theta), det = s * s + v * v;
  return {(s * forward + v * left) / det / seconds, (-v * forward + s * left) / det / seconds, turnDeg / seconds};
}

}  // namespace omnicam
