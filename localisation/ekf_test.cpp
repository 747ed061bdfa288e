// The EKF against numbers known without it: Jacobians against central differences, one update
// against the closed-form Kalman posterior, the gate with S⁻¹, and a seeded drive where landmark
// updates beat odometry alone.
#include "ekf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace omnicam {
namespace {

constexpr double kStep = 1e-6;

template <typename F, int Rows, int Cols>
Eigen::Matrix<double, Rows, Cols> numericJacobian(const F& f, const Eigen::Matrix<double, Cols, 1>& at) {
  Eigen::Matrix<double, Rows, Cols> j;
  for (int c = 0; c < Cols; ++c) {
    Eigen::Matrix<double, Cols, 1> plus = at, minus = at;
    plus[c] += kStep;
    minus[c] -= kStep;
    Eigen::Matrix<double, Rows, 1> d = f(plus) - f(minus);
    if (Rows >= 2) d[Rows - 1] = wrapAngle(d[Rows - 1]);  // the angle row
    j.col(c) = d / (2.0 * kStep);
  }
  return j;
}

TEST(Ekf, JacobiansMatchCentralDifferences) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> pos(-3.0, 3.0), ang(-3.0, 3.0), speed(0.0, 0.5), turn(-0.5, 0.5);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec3 s(pos(rng), pos(rng), ang(rng));
    const Odometry u{speed(rng), turn(rng)};
    const Vec2 landmark(pos(rng) + 4.0, pos(rng));
    const auto g = [&](const Vec3& x) { return motionModel(x, u); };
    EXPECT_LT((motionJacobianState(s, u) - numericJacobian<decltype(g), 3, 3>(g, s)).cwiseAbs().maxCoeff(), 1e-6);
    const auto gu = [&](const Eigen::Vector2d& c) { return motionModel(s, {c.x(), c.y()}); };
    EXPECT_LT((motionJacobianControl(s, u) - numericJacobian<decltype(gu), 3, 2>(gu, Eigen::Vector2d(u.v, u.omega)))
                  .cwiseAbs()
                  .maxCoeff(),
              1e-6);
    const auto h = [&](const Vec3& x) { return measurementModel(x, landmark); };
    EXPECT_LT((measurementJacobian(s, landmark) - numericJacobian<decltype(h), 2, 3>(h, s)).cwiseAbs().maxCoeff(), 1e-6);
  }
}

// A landmark straight ahead at distance d: H = [[−1, 0, 0], [0, −1/d, −1]], so the range update
// is the scalar Kalman update of x: σ² = σx²σr² / (σx² + σr²), x += σx²/(σx² + σr²)·(x_true − x).
TEST(Ekf, OneUpdateIsTheClosedFormKalmanPosterior) {
  const double sx2 = 0.04, sy2 = 0.01, st2 = 0.002, sr2 = 0.01, sb2 = 0.001, d = 2.0;
  LandmarkEkf ekf({0.1, 0.0, 0.0}, Vec3(sx2, sy2, st2).asDiagonal(), Eigen::Matrix2d::Zero(),
                  Eigen::Vector2d(sr2, sb2).asDiagonal());
  const Vec2 landmark(0.1 + d, 0.0);
  ASSERT_TRUE(ekf.update({d + 0.1, 0.0}, landmark));  // the robot is really at x = 0
  EXPECT_NEAR(ekf.covariance()(0, 0), sx2 * sr2 / (sx2 + sr2), 1e-12);
  EXPECT_NEAR(ekf.mean().x(), 0.1 - 0.1 * sx2 / (sx2 + sr2), 1e-12);
  // Bearing: S = σy²/d² + σθ² + σb²; θ's variance shrinks by σθ⁴/S.
  const double s = sy2 / (d * d) + st2 + sb2;
  EXPECT_NEAR(ekf.covariance()(2, 2), st2 - st2 * st2 / s, 1e-12);
}

// The thesis' gate (3.21) multiplies by S; the correct Mahalanobis distance divides by it. With
// S ≈ 4 (σr = 2 m), a measurement 1.4σ off in range (2.8 m) passes with S⁻¹ (ρ = 2.8²/4 = 1.96 <
// 9.21) and would fail with S (ρ = 2.8² · 4 ≈ 31); one 10σ off fails.
TEST(Ekf, TheGateUsesTheInverseCovariance) {
  const double sr2 = 4.0;  // a 2 m range standard deviation: S ≈ 4
  LandmarkEkf ekf({0, 0, 0}, Eigen::Matrix3d::Identity() * 1e-6, Eigen::Matrix2d::Zero(),
                  Eigen::Vector2d(sr2, 0.01).asDiagonal());
  const Vec2 landmark(10.0, 0.0);
  EXPECT_NEAR(ekf.mahalanobis({10.0 + 2.0 * 1.4, 0.0}, landmark), 1.96, 1e-3);  // (2.8)² / 4
  EXPECT_TRUE(ekf.update({10.0 + 2.0 * 1.4, 0.0}, landmark));
  const Vec3 before = ekf.mean();
  EXPECT_FALSE(ekf.update({10.0 + 20.0, 0.0}, landmark));
  EXPECT_EQ(ekf.mean(), before);
}

// A seeded drive around a square of four landmarks: odometry drifts, the EKF does not.
TEST(Ekf, LandmarkUpdatesBeatOdometryOnASeededDrive) {
  const std::vector<Vec2> landmarks{{3, 2}, {-3, 2}, {-3, -2}, {3, -2}};
  std::mt19937_64 rng(11);
  std::normal_distribution<double> unit(0.0, 1.0);
  const double sv = 0.02, sw = 0.02, sr = 0.05, sb = 0.02;
  Vec3 truth(2.0, -1.0, kPi / 2), odometry = truth;
  LandmarkEkf ekf(truth, Eigen::Matrix3d::Identity() * 1e-4, Eigen::Vector2d(sv * sv, sw * sw).asDiagonal(),
                  Eigen::Vector2d(sr * sr, sb * sb).asDiagonal());
  double odometryError = 0.0, ekfError = 0.0;
  const int steps = 200;
  for (int t = 0; t < steps; ++t) {
    const Odometry command{0.1, 0.05};
    truth = motionModel(truth, command);
    const Odometry measured{command.v + sv * unit(rng), command.omega + sw * unit(rng)};
    odometry = motionModel(odometry, measured);
    ekf.predict(measured);
    for (const Vec2& l : landmarks) {
      const RangeBearing z = measurementModel(truth, l) + Eigen::Vector2d(sr * unit(rng), sb * unit(rng));
      ekf.update(z, l);
    }
    odometryError += (odometry.head<2>() - truth.head<2>()).norm() / steps;
    ekfError += (ekf.mean().head<2>() - truth.head<2>()).norm() / steps;
  }
  EXPECT_LT(ekfError, 0.05);
  EXPECT_GT(odometryError, 3.0 * ekfError);
}

}  // namespace
}  // namespace omnicam
