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

Eigen::Matrix2d measurementNoiseAt(double range) {
  Eigen::Matrix2d q = Eigen::Matrix2d::Zero();
  q(0, 0) = std::pow(0.05 + 0.1 * range, 2);  // range from an elevation angle worsens with distance
  q(1, 1) = std::pow(3.0 * kPi / 180.0, 2);
  return q;
}

Eigen::Matrix2d Drive::motionNoiseFor(const Odometry& u) const {
  Eigen::Matrix2d m = Eigen::Matrix2d::Zero();
  m(0, 0) = std::pow(noise.rangeFraction * std::abs(u.v) + 0.01, 2);
  m(1, 1) = std::pow(noise.turnSigmaRad, 2);
  return m;
}

std::vector<Odometry> odometryBetween(const Vec3& from, const Vec3& to) {
  const Vec2 chord = to.head<2>() - from.head<2>();
  const double distance = chord.norm();
  if (distance == 0.0) return {{0.0, wrapAngle(to.z() - from.z())}};
  const double turnToChord = wrapAngle(std::atan2(chord.y(), chord.x()) - from.z());
  const bool forward = std::cos(turnToChord) >= 0.0;
  const Odometry drive{forward ? distance : -distance, forward ? turnToChord : wrapAngle(turnToChord + kPi)};
  const double turnAfter = wrapAngle(to.z() - motionModel(from, drive).z());
  if (std::abs(turnAfter) < 1e-12) return {drive};
  return {drive, {0.0, turnAfter}};
}

Drive makeDrive(const std::vector<RobotPose>& poses, uint64_t seed, const OdometryNoise& noise) {
  Drive drive;
  drive.noise = noise;
  for (const RobotPose& p : poses) drive.truth.emplace_back(p.x, p.y, wrapAngle(p.yawDeg * kPi / 180.0));
  std::mt19937_64 random(seed);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  drive.noisyOdometry.resize(poses.size());
  for (size_t k = 1; k < poses.size(); ++k)
    for (Odometry step : odometryBetween(drive.truth[k - 1], drive.truth[k])) {
      step.v *= 1.0 + noise.rangeFraction * gaussian(random);
      step.omega += noise.turnSigmaRad * gaussian(random);
      drive.noisyOdometry[k].push_back(step);
    }
  return drive;
}

EkfTrace runEkf(const Drive& drive, const MeasurementsAt& measurementsAt) {
  EkfTrace trace;
  const Eigen::Matrix3d initialCovariance = Eigen::Vector3d(1e-4, 1e-4, std::pow(kPi / 180.0, 2)).asDiagonal();
  LandmarkEkf ekf(drive.truth[0], initialCovariance, Eigen::Matrix2d::Identity() * 1e-4, Eigen::Matrix2d::Identity());
  Vec3 odometry = drive.truth[0];
  for (size_t k = 0; k < drive.truth.size(); ++k) {
    for (const Odometry& u : drive.noisyOdometry[k]) {
      odometry = motionModel(odometry, u);
      ekf.setMotionNoise(drive.motionNoiseFor(u));
      ekf.predict(u);
    }
    if (const std::vector<Measurement>* measurements = measurementsAt(k))
      for (const Measurement& m : *measurements) {
        ekf.setMeasurementNoise(measurementNoiseAt(measurementModel(ekf.mean(), m.landmark)(0)));
        if (ekf.update(m.z, m.landmark)) ++trace.used;
        else ++trace.gated;
      }
    trace.rows.push_back({drive.truth[k], odometry, ekf.mean(), ekf.covariance()});
  }
  return trace;
}

EkfDrives runEkfOnDrives(const std::vector<Drive>& drives, const MeasurementsAt& measurementsAt) {
  EkfDrives result;
  for (size_t d = 0; d < drives.size(); ++d) {
    EkfTrace trace = runEkf(drives[d], measurementsAt);
    result.odometryErrorCm.push_back(trace.meanOdometryErrorCm());
    result.ekfErrorCm.push_back(trace.meanErrorCm());
    if (d == 0) result.first = std::move(trace);
  }
  return result;
}

}  // namespace omnicam
