#pragma once
// A robot driving a path with noisy odometry and localising itself with the thesis' EKF from
// range-bearing measurements of known landmarks (ekf.h): the drive every experiment shares, so
// that conditions differ only in their measurements.
#include <functional>
#include <vector>

#include "ekf.h"
#include "placement.h"

namespace omnicam {

struct Measurement {
  Vec2 landmark;  // the identified landmark's position
  RangeBearing z;
};

struct EkfRow {
  Vec3 truth, odometry, estimate;
  Eigen::Matrix3d covariance;
};

struct EkfTrace {
  std::vector<EkfRow> rows;
  int used = 0, gated = 0;
  // Mean position errors (cm) of the estimate and of odometry alone, after the start.
  double meanErrorCm() const;
  double meanOdometryErrorCm() const;
};

// Odometry between consecutive true poses, then noise drawn once for every condition.
struct Drive {
  std::vector<Vec3> truth;
  std::vector<Odometry> noisyOdometry;  // [k] moves truth[k-1] → truth[k]; [0] unused
  Eigen::Matrix2d motionNoiseFor(const Odometry& u) const;
  static constexpr double kOdometryRangeFraction = 0.08;
  static constexpr double kOdometryTurnSigmaRad = 1.5 * kPi / 180.0;
};

Drive makeDrive(const std::vector<RobotPose>& poses, uint64_t seed);

// Drives every pose; pose k brings the measurements measurementsAt(k) returns (null: none).
EkfTrace runEkf(const Drive& drive, const std::function<const std::vector<Measurement>*(size_t)>& measurementsAt);

}  // namespace omnicam
