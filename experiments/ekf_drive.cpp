#include "ekf_drive.h"

#include <cmath>
#include <random>

namespace omnicam {

namespace {

// Mean over the rows after the first (the start, where both are exact) of a position error, cm.
double meanAfterStart(const std::vector<EkfRow>& rows, Vec3 EkfRow::*estimate) {
  if (rows.size() < 2) return 0.0;
  double sum = 0.0;
  for (size_t k = 1; k < rows.size(); ++k) sum += 100.0 * ((rows[k].*estimate).head<2>() - rows[k].truth.head<2>()).norm();
  return sum / static_cast<double>(rows.size() - 1);
}

}  // namespace

double EkfTrace::meanErrorCm() const { return meanAfterStart(rows, &EkfRow::estimate); }
double EkfTrace::meanOdometryErrorCm() const { return meanAfterStart(rows, &EkfRow::odometry); }

Eigen::Matrix2d Drive::motionNoiseFor(const Odometry& u) const {
  Eigen::Matrix2d m = Eigen::Matrix2d::Zero();
  m(0, 0) = std::pow(kOdometryRangeFraction * std::abs(u.v) + 0.01, 2);
  m(1, 1) = std::pow(kOdometryTurnSigmaRad, 2);
  return m;
}

Drive makeDrive(const std::vector<RobotPose>& poses, uint64_t seed) {
  Drive drive;
  for (const RobotPose& p : poses) drive.truth.emplace_back(p.x, p.y, wrapAngle(p.yawDeg * kPi / 180.0));
  std::mt19937_64 random(seed);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  drive.noisyOdometry.resize(poses.size());
  for (size_t k = 1; k < poses.size(); ++k) {
    const Vec3& a = drive.truth[k - 1];
    const Vec3& b = drive.truth[k];
    const double omega = wrapAngle(b.z() - a.z());
    const double distance = std::hypot(b.x() - a.x(), b.y() - a.y());
    const double forward = std::cos(std::atan2(b.y() - a.y(), b.x() - a.x()) - b.z()) >= 0 ? 1.0 : -1.0;
    Odometry noisy;
    noisy.v = forward * distance * (1.0 + Drive::kOdometryRangeFraction * gaussian(random));
    noisy.omega = omega + Drive::kOdometryTurnSigmaRad * gaussian(random);
    drive.noisyOdometry[k] = noisy;
  }
  return drive;
}

EkfTrace runEkf(const Drive& drive, const std::function<const std::vector<Measurement>*(size_t)>& measurementsAt) {
  EkfTrace trace;
  const Eigen::Matrix3d initialCovariance = Eigen::Vector3d(1e-4, 1e-4, std::pow(kPi / 180.0, 2)).asDiagonal();
  LandmarkEkf ekf(drive.truth[0], initialCovariance, Eigen::Matrix2d::Identity() * 1e-4, Eigen::Matrix2d::Identity());
  Vec3 odometry = drive.truth[0];
  for (size_t k = 0; k < drive.truth.size(); ++k) {
    if (k > 0) {
      const Odometry& u = drive.noisyOdometry[k];
      odometry = motionModel(odometry, u);
      ekf.setMotionNoise(drive.motionNoiseFor(u));
      ekf.predict(u);
    }
    if (const std::vector<Measurement>* measurements = measurementsAt(k))
      for (const Measurement& m : *measurements) {
        Eigen::Matrix2d q = Eigen::Matrix2d::Zero();
        q(0, 0) = std::pow(0.05 + 0.1 * m.z(0), 2);  // range from an elevation angle worsens with distance
        q(1, 1) = std::pow(3.0 * kPi / 180.0, 2);
        ekf.setMeasurementNoise(q);
        if (ekf.update(m.z, m.landmark)) ++trace.used;
        else ++trace.gated;
      }
    trace.rows.push_back({drive.truth[k], odometry, ekf.mean(), ekf.covariance()});
  }
  return trace;
}

}  // namespace omnicam
