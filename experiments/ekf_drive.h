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

// The odometry that moves `from` exactly to `to` under motionModel: turn toward the chord and
// drive along it (backward when it points behind), then, where the path bends between them,
// turn on the spot to the heading at `to` — a path's poses face along its tangent, which at a
// bend is not the chord's direction, and one (v, ω) step could not reach them.
std::vector<Odometry> odometryBetween(const Vec3& from, const Vec3& to);

// Odometry's noise: σ of each step's distance as a fraction of it, σ of each turn.
struct OdometryNoise {
  double rangeFraction = 0.08;
  double turnSigmaRad = 1.5 * kPi / 180.0;
};

// Odometry between consecutive true poses, then noise drawn once for every condition.
struct Drive {
  std::vector<Vec3> truth;
  std::vector<std::vector<Odometry>> noisyOdometry;  // [k]: steps moving truth[k-1] → truth[k]; [0] none
  OdometryNoise noise;
  Eigen::Matrix2d motionNoiseFor(const Odometry& u) const;
};

Drive makeDrive(const std::vector<RobotPose>& poses, uint64_t seed, const OdometryNoise& noise = {});

// Q of a range-bearing measurement of a landmark at `range` metres: σ_r = 5 cm + 10 % of it,
// σ_b = 3°. runEkf takes the range the estimate predicts, not the measured one: a wrong range
// read far too long must not loosen its own gate.
Eigen::Matrix2d measurementNoiseAt(double range);

using MeasurementsAt = std::function<const std::vector<Measurement>*(size_t)>;

// Drives every pose; pose k brings the measurements measurementsAt(k) returns (null: none).
EkfTrace runEkf(const Drive& drive, const MeasurementsAt& measurementsAt);

// The same measurements on several drives, each with its own odometry noise: one drive's error
// is a draw. Each drive's mean errors (cm), and the first drive's whole trace.
struct EkfDrives {
  EkfTrace first;
  std::vector<double> odometryErrorCm, ekfErrorCm;
};
EkfDrives runEkfOnDrives(const std::vector<Drive>& drives, const MeasurementsAt& measurementsAt);

}  // namespace omnicam
