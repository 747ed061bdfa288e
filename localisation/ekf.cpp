#include "ekf.h"

#include <cmath>

namespace omnicam {

Vec3 motionModel(const Vec3& s, const Odometry& u) {
  const double heading = s.z() + u.omega;
  return {s.x() + u.v * std::cos(heading), s.y() + u.v * std::sin(heading), wrapAngle(heading)};
}

Eigen::Matrix3d motionJacobianState(const Vec3& s, const Odometry& u) {
  const double heading = s.z() + u.omega;
  Eigen::Matrix3d g = Eigen::Matrix3d::Identity();
  g(0, 2) = -u.v * std::sin(heading);
  g(1, 2) = u.v * std::cos(heading);  // the thesis prints −v·cos
  return g;
}

Matrix32 motionJacobianControl(const Vec3& s, const Odometry& u) {
  const double heading = s.z() + u.omega;
  Matrix32 v;
  v << std::cos(heading), -u.v * std::sin(heading),
       std::sin(heading), u.v * std::cos(heading),  // the thesis prints −v·cos
       0.0, 1.0;
  return v;
}

RangeBearing measurementModel(const Vec3& s, const Vec2& l) { return rangeBearingOnFloor(s.head<2>(), s.z(), l); }

Matrix23 measurementJacobian(const Vec3& s, const Vec2& l) {
  const double dx = l.x() - s.x(), dy = l.y() - s.y();
  const double q2 = dx * dx + dy * dy, q = std::sqrt(q2);
  Matrix23 h;
  h << -dx / q, -dy / q, 0.0,
       dy / q2, -dx / q2, -1.0;
  return h;
}

LandmarkEkf::LandmarkEkf(const Vec3& mean, const Eigen::Matrix3d& covariance, const Eigen::Matrix2d& motionNoise,
                         const Eigen::Matrix2d& measurementNoise, double gate)
    : mean_(mean), covariance_(covariance), motionNoise_(motionNoise), measurementNoise_(measurementNoise), gate_(gate) {}

void LandmarkEkf::predict(const Odometry& u) {
  const Eigen::Matrix3d g = motionJacobianState(mean_, u);
  const Matrix32 v = motionJacobianControl(mean_, u);
  mean_ = motionModel(mean_, u);
  covariance_ = g * covariance_ * g.transpose() + v * motionNoise_ * v.transpose();
}

double LandmarkEkf::mahalanobis(const RangeBearing& z, const Vec2& landmark) const {
  const Matrix23 h = measurementJacobian(mean_, landmark);
  const Eigen::Matrix2d s = h * covariance_ * h.transpose() + measurementNoise_;
  RangeBearing innovation = z - measurementModel(mean_, landmark);
  innovation.y() = wrapAngle(innovation.y());
  return innovation.dot(s.ldlt().solve(innovation));
}

bool LandmarkEkf::update(const RangeBearing& z, const Vec2& landmark) {
  if (!(mahalanobis(z, landmark) < gate_)) return false;
  const Matrix23 h = measurementJacobian(mean_, landmark);
  const Eigen::Matrix2d s = h * covariance_ * h.transpose() + measurementNoise_;
  const Matrix32 k = covariance_ * h.transpose() * s.inverse();
  RangeBearing innovation = z - measurementModel(mean_, landmark);
  innovation.y() = wrapAngle(innovation.y());
  mean_ += k * innovation;
  mean_.z() = wrapAngle(mean_.z());
  covariance_ = (Eigen::Matrix3d::Identity() - k * h) * covariance_;
  return true;
}

}  // namespace omnicam
