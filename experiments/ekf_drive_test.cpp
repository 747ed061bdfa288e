// The drive every EKF experiment shares: odometry that reproduces the true poses when its noise
// is zero (closed-form steps for a straight move, a bend, a reverse and a turn on the spot, and
// every step of the thesis' loop), and noise of the size it declares.
#include "ekf_drive.h"

#include <gtest/gtest.h>

#include <cmath>

#include "scene_loader.h"

namespace omnicam {
namespace {

Vec3 drive(Vec3 pose, const std::vector<Odometry>& steps) {
  for (const Odometry& u : steps) pose = motionModel(pose, u);
  return pose;
}

void expectSteps(const std::vector<Odometry>& steps, const std::vector<Odometry>& expected) {
  ASSERT_EQ(steps.size(), expected.size());
  for (size_t i = 0; i < steps.size(); ++i) {
    EXPECT_NEAR(steps[i].v, expected[i].v, 1e-12) << "step " << i;
    EXPECT_NEAR(steps[i].omega, expected[i].omega, 1e-12) << "step " << i;
  }
}

TEST(OdometryBetween, AStraightMoveIsOneStepOfItsLength) {
  expectSteps(odometryBetween({0, 0, 0}, {0.25, 0, 0}), {{0.25, 0.0}});
}

TEST(OdometryBetween, ABendTurnsToTheChordThenToTheNewHeading) {
  // From the origin facing +x to (1, 1) facing +y: the chord points at 45°.
  expectSteps(odometryBetween({0, 0, 0}, {1, 1, kPi / 2}), {{std::sqrt(2.0), kPi / 4}, {0.0, kPi / 4}});
}

TEST(OdometryBetween, AMoveBehindIsDrivenInReverse) {
  expectSteps(odometryBetween({0, 0, 0}, {-0.3, 0, 0}), {{-0.3, 0.0}});
  expectSteps(odometryBetween({0, 0, kPi / 2}, {0, -0.5, kPi / 2}), {{-0.5, 0.0}});
}

TEST(OdometryBetween, ATurnOnTheSpotIsATurnAlone) {
  expectSteps(odometryBetween({1, 2, 0}, {1, 2, kPi / 2}), {{0.0, kPi / 2}});
}

TEST(OdometryBetween, HeadingsAcrossMinusPiTurnTheShortWay) {
  const std::vector<Odometry> steps = odometryBetween({0, 0, kPi - 0.1}, {0, 0, -kPi + 0.1});
  expectSteps(steps, {{0.0, 0.2}});
}

TEST(MeasurementNoise, GrowsWithTheRange) {
  const Eigen::Matrix2d q = measurementNoiseAt(2.0);
  EXPECT_NEAR(q(0, 0), 0.25 * 0.25, 1e-15);
  EXPECT_NEAR(q(1, 1), std::pow(3.0 * kPi / 180.0, 2), 1e-15);
  EXPECT_EQ(q(0, 1), 0.0);
  EXPECT_EQ(q(1, 0), 0.0);
}

// A robot standing still at the origin, sure of its pose, sees a landmark 2 m ahead. The gate
// takes ρ = Δr²/σ_r² < 9.21 (the pose's own uncertainty, 1.4 cm, adds 0.3 % to σ_r²), with σ_r of the
// predicted 2 m: 25 cm, so a range up to 2 + 3.03 · 0.25 = 2.76 m passes. Were σ_r taken from the
// measured range, 3 m (σ_r 35 cm, 1 m off: ρ = 8.2) would pass as well.
TEST(RunEkf, AMeasuredRangeTooLongDoesNotWidenItsOwnGate) {
  const Drive still = makeDrive({RobotPose{}, RobotPose{}}, 1, {0.0, 0.0});
  const auto traceOf = [&](double measuredRange) {
    const std::vector<Measurement> sighting{{Vec2(2.0, 0.0), RangeBearing(measuredRange, 0.0)}};
    return runEkf(still, [&](size_t k) { return k == 1 ? &sighting : nullptr; });
  };
  EXPECT_EQ(traceOf(2.7).used, 1);
  EXPECT_EQ(traceOf(2.8).gated, 1);
  EXPECT_EQ(traceOf(3.0).gated, 1);
}

class ThesisLoopDrive : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const Scene scene = loadScene(std::string(OMNICAM_SOURCE_DIR) + "/scenes/robocup2006.json");
    const CameraPath* loop = scene.findPath("thesis-loop");
    ASSERT_NE(loop, nullptr);
    poses_ = loop->poses;
  }
  static std::vector<RobotPose> poses_;
};
std::vector<RobotPose> ThesisLoopDrive::poses_;

TEST_F(ThesisLoopDrive, OdometryWithoutNoiseLandsOnEveryTruePose) {
  const Drive exact = makeDrive(poses_, 7, {0.0, 0.0});
  ASSERT_EQ(exact.truth.size(), 100u);
  int bends = 0;
  for (size_t k = 1; k < exact.truth.size(); ++k) {
    const Vec3 reached = drive(exact.truth[k - 1], exact.noisyOdometry[k]);
    EXPECT_NEAR((reached.head<2>() - exact.truth[k].head<2>()).norm(), 0.0, 1e-12) << "pose " << k;
    EXPECT_NEAR(wrapAngle(reached.z() - exact.truth[k].z()), 0.0, 1e-12) << "pose " << k;
    bends += exact.noisyOdometry[k].size() == 2;
  }
  // The loop bends at its three field corners and where it turns from the field's edge onto the
  // diagonal, each between two poses.
  EXPECT_EQ(bends, 4);
  // Chained from the start, odometry alone stays on the truth, and so does the EKF without
  // a measurement.
  const EkfTrace trace = runEkf(exact, [](size_t) { return nullptr; });
  EXPECT_LT(trace.meanOdometryErrorCm(), 1e-8);
  EXPECT_LT(trace.meanErrorCm(), 1e-8);
}

TEST_F(ThesisLoopDrive, DrivesAreRunOneByOneWithTheSameMeasurements) {
  std::vector<Drive> drives;
  for (uint64_t seed = 3; seed < 6; ++seed) drives.push_back(makeDrive(poses_, seed));
  // One landmark 1 m ahead of every fifth true pose, measured exactly.
  std::vector<std::vector<Measurement>> sightings(poses_.size());
  for (size_t k = 0; k < poses_.size(); k += 5) {
    const Vec3& p = drives[0].truth[k];
    const Vec2 landmark = p.head<2>() + Vec2(std::cos(p.z()), std::sin(p.z()));
    sightings[k].push_back({landmark, RangeBearing(1.0, 0.0)});
  }
  const MeasurementsAt at = [&](size_t k) { return &sightings[k]; };
  const EkfDrives all = runEkfOnDrives(drives, at);
  ASSERT_EQ(all.ekfErrorCm.size(), 3u);
  ASSERT_EQ(all.odometryErrorCm.size(), 3u);
  for (size_t d = 0; d < drives.size(); ++d) {
    const EkfTrace alone = runEkf(drives[d], at);
    EXPECT_EQ(all.ekfErrorCm[d], alone.meanErrorCm());
    EXPECT_EQ(all.odometryErrorCm[d], alone.meanOdometryErrorCm());
  }
  EXPECT_NE(all.odometryErrorCm[0], all.odometryErrorCm[1]);  // each drive its own noise
  const EkfTrace first = runEkf(drives[0], at);
  EXPECT_EQ(all.first.used, first.used);
  ASSERT_EQ(all.first.rows.size(), first.rows.size());
  EXPECT_EQ(all.first.rows.back().estimate, first.rows.back().estimate);
}

TEST_F(ThesisLoopDrive, NoiseHasTheDeclaredSpread) {
  // Each step's relative distance error and turn error, over the loop drawn with many seeds.
  const OdometryNoise noise;
  const Drive exact = makeDrive(poses_, 1, {0.0, 0.0});
  double rangeSquares = 0.0, turnSquares = 0.0;
  int driven = 0, turns = 0;
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    const Drive noisy = makeDrive(poses_, seed, noise);
    for (size_t k = 1; k < noisy.truth.size(); ++k)
      for (size_t i = 0; i < noisy.noisyOdometry[k].size(); ++i) {
        const Odometry& u = noisy.noisyOdometry[k][i];
        const Odometry& e = exact.noisyOdometry[k][i];
        if (e.v != 0.0) rangeSquares += std::pow(u.v / e.v - 1.0, 2), ++driven;
        turnSquares += std::pow(u.omega - e.omega, 2), ++turns;
      }
  }
  // σ estimated from thousands of draws: within 5 % of the declared σ.
  EXPECT_NEAR(std::sqrt(rangeSquares / driven), noise.rangeFraction, 0.05 * noise.rangeFraction);
  EXPECT_NEAR(std::sqrt(turnSquares / turns), noise.turnSigmaRad, 0.05 * noise.turnSigmaRad);
}

}  // namespace
}  // namespace omnicam
