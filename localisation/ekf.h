#pragma once
// EKF self-localisation from range-bearing landmark measurements (thesis §3.4.2, Eqs. 3.11–3.23,
// with the corrections of docs: in G, ∂y/∂θ = +v·cos(θ+ω); in V, ∂y/∂ω = +v·cos(θ+ω); H is the
// standard range-bearing Jacobian; the validation gate uses S⁻¹).
// State (x, y, θ): metres, metres, radians CCW from world +X. Control u = (v, ω): distance
// driven after turning by ω. Measurement z = (range, bearing): metres, radians CCW from the
// robot's heading, wrapped to (−π, π].
#include <Eigen/Dense>

#include "geometry.h"

namespace omnicam {

struct Odometry {
  double v = 0.0, omega = 0.0;
};

using RangeBearing = Eigen::Vector2d;
using Matrix32 = Eigen::Matrix<double, 3, 2>;
using Matrix23 = Eigen::Matrix<double, 2, 3>;

// g (Eq. 3.11) and its Jacobians G = ∂g/∂x (3.15) and V = ∂g/∂u (3.16), corrected.
Vec3 motionModel(const Vec3& state, const Odometry& u);
Eigen::Matrix3d motionJacobianState(const Vec3& state, const Odometry& u);
Matrix32 motionJacobianControl(const Vec3& state, const Odometry& u);
// h (Eq. 3.12) and H = ∂h/∂x (3.18, the standard form).
RangeBearing measurementModel(const Vec3& state, const Vec2& landmark);
Matrix23 measurementJacobian(const Vec3& state, const Vec2& landmark);

class LandmarkEkf {
 public:
  // M: motion noise covariance of (v, ω); Q: measurement noise covariance of (range, bearing);
  // gate: γ of the validation gate ρ = νᵀ S⁻¹ ν < γ (9.21: 99 % of χ² with 2 degrees of freedom).
  LandmarkEkf(const Vec3& mean, const Eigen::Matrix3d& covariance, const Eigen::Matrix2d& motionNoise,
              const Eigen::Matrix2d& measurementNoise, double gate = 9.21);

  void predict(const Odometry& u);  // Eqs. 3.13–3.14
  // Eqs. 3.17–3.23. Returns false (and changes nothing) when the measurement fails the gate.
  bool update(const RangeBearing& z, const Vec2& landmark);
  // ρ of a measurement against the current estimate (Eq. 3.21, with S⁻¹).
  double mahalanobis(const RangeBearing& z, const Vec2& landmark) const;

  // Noise that changes with the step (odometry noise grows with the distance driven; range
  // noise with the range).
  void setMotionNoise(const Eigen::Matrix2d& m) { motionNoise_ = m; }
  void setMeasurementNoise(const Eigen::Matrix2d& q) { measurementNoise_ = q; }

  const Vec3& mean() const { return mean_; }
  const Eigen::Matrix3d& covariance() const { return covariance_; }

 private:
  Vec3 mean_;
  Eigen::Matrix3d covariance_;
  Eigen::Matrix2d motionNoise_, measurementNoise_;
  double gate_;
};

}  // namespace omnicam
