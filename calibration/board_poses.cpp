#include "board_poses.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "errors.h"
#include "imaged_corners.h"

namespace omnicam {

namespace {

// The middle of the printed pattern in the target frame: the corners' bounding box centre.
Vec3 patternCentre(const TargetPattern& pattern) {
  const std::vector<Vec3> corners = targetCorners(pattern);
  Vec3 lo = corners.front(), hi = corners.front();
  for (const Vec3& c : corners) {
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  return 0.5 * (lo + hi);
}

// A rotation whose z axis is `normal`, turned `rollRad` about it.
Eigen::Matrix3d facing(const Vec3& normal, double rollRad) {
  const Vec3 z = normal.normalized();
  const Vec3 helper = std::abs(z.z()) < 0.9 ? Vec3::UnitZ() : Vec3::UnitX();
  const Vec3 x0 = helper.cross(z).normalized(), y0 = z.cross(x0);
  const Vec3 x = std::cos(rollRad) * x0 + std::sin(rollRad) * y0;
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = z.cross(x);
  r.col(2) = z;
  return r;
}

}  // namespace

bool boardClearsFloor(const Rigid& worldFromTarget, const std::vector<Vec3>& points, double floorZ) {
  return std::all_of(points.begin(), points.end(),
                     [&](const Vec3& c) { return (worldFromTarget * c).z() >= floorZ + kBoardFloorClearanceM; });
}

std::vector<Vec3> floorTestPoints(const TargetPattern& pattern, const std::optional<double>& boardMarginM) {
  if (!boardMarginM) return targetCorners(pattern);
  const std::array<Vec3, 4> outline = targetBoardOutline(pattern, *boardMarginM);
  return {outline.begin(), outline.end()};
}

double boardDistance(const Rigid& worldFromTarget, const std::vector<Vec3>& outline, const Vec3& point) {
  Vec3 lo = outline.front(), hi = outline.front();
  for (const Vec3& c : outline) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
  const Vec3 p = worldFromTarget.inverse() * point;
  const Vec3 nearest(std::clamp(p.x(), lo.x(), hi.x()), std::clamp(p.y(), lo.y(), hi.y()), 0.0);
  return (p - nearest).norm();
}

std::vector<Rigid> boardPoses(const Camera& camera, const Rigid& worldFromViewpoint, const TargetPattern& pattern,
                              const BoardPoseOptions& o) {
  std::mt19937_64 random(o.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Vec3 centre = patternCentre(pattern);
  const std::vector<Vec3> floorPoints = floorTestPoints(pattern, o.boardMarginM);
  CalibrationTarget board;
  board.pattern = pattern;
  std::vector<Rigid> poses;
  for (int draw = 0; draw < o.maxDraws && static_cast<int>(poses.size()) < o.count; ++draw) {
    // A ray the camera images, uniform over the image.
    const Vec2 raster(unit(random) * camera.width(), unit(random) * camera.height());
    const double distance = o.nearM + unit(random) * (o.farM - o.nearM);
    const double tilt = std::acos(1.0 - unit(random) * (1.0 - std::cos(o.maxTiltDeg * kPi / 180.0)));
    const double tiltAzimuth = 2.0 * kPi * unit(random), roll = 2.0 * kPi * unit(random);
    if (!camera.images(raster)) continue;
    const std::optional<CameraRay> ray = camera.generateRay({raster});
    if (!ray) continue;
    const Vec3 direction = worldFromViewpoint.linear() * ray->direction;
    const Vec3 at = worldFromViewpoint * ray->origin + distance * direction;
    // Facing the camera (z toward it), tilted away about an axis across the line of sight.
    const Eigen::Matrix3d toward = facing(-direction, tiltAzimuth);
    const Eigen::Matrix3d tilted = Eigen::AngleAxisd(tilt, toward.col(0)).toRotationMatrix() * toward;
    board.worldFromTarget.linear() = tilted * Eigen::AngleAxisd(roll, Vec3::UnitZ()).toRotationMatrix();
    board.worldFromTarget.translation() = at - board.worldFromTarget.linear() * centre;
    if (o.floorZ && !boardClearsFloor(board.worldFromTarget, floorPoints, *o.floorZ)) continue;
    // A board centred near the viewpoint reaches past it with its edges: no part of it nearer than this.
    if (o.minBoardDistanceM && boardDistance(board.worldFromTarget, floorPoints, worldFromViewpoint.translation()) < *o.minBoardDistanceM)
      continue;
    const std::vector<ImagedCorner> corners = imagedCorners(camera, worldFromViewpoint, nullptr, board);
    const auto seen = std::count_if(corners.begin(), corners.end(), [](const ImagedCorner& c) { return c.sight == CornerSight::Seen; });
    if (seen >= o.minSeenCorners) poses.push_back(board.worldFromTarget);
  }
  if (static_cast<int>(poses.size()) < o.count)
    throw InputError("board poses: only " + std::to_string(poses.size()) + " of " + std::to_string(o.count) +
                     " poses with " + std::to_string(o.minSeenCorners) + " corners seen in " + std::to_string(o.maxDraws) +
                     " draws (nearer boards, a smaller tilt or fewer corners)");
  return poses;
}

}  // namespace omnicam
