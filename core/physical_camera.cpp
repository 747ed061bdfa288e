#include "physical_camera.h"

#include <cmath>

#include "central_camera.h"
#include "errors.h"
#include "lens_distortion.h"

namespace omnicam {

std::optional<Vec3> Pinhole::direction(const Vec2& rasterPoint) const {
  const auto normalised = undistort(distortion, (rasterPoint - principalPoint) / focalPx);
  if (!normalised) return std::nullopt;
  return (viewpointFromPinhole * Vec3(normalised->x(), normalised->y(), 1.0)).normalized();
}

std::optional<Vec2> Pinhole::raster(const Vec3& pointViewpoint) const {
  const Vec3 q = viewpointFromPinhole.transpose() * (pointViewpoint - position);
  if (!(q.z() > 0.0)) return std::nullopt;
  const Vec2 undistorted(q.x() / q.z(), q.y() / q.z());
  const Vec2 distorted = distort(distortion, undistorted);
  // Beyond the lens' fold the raster point's own ray is another one: such a point is not imaged
  // (direction() refuses the same raster points).
  if (!distortion.none()) {
    const auto back = undistort(distortion, distorted);
    if (!back || (*back - undistorted).norm() > 1e-9 * (1.0 + undistorted.norm())) return std::nullopt;
  }
  return principalPoint + focalPx * distorted;
}

Pinhole pinholeOf(const RigSpec& rig) {
  const OmniCamera ideal = rig.idealCamera();
  const CameraMount& m = rig.mount;
  Pinhole p;
  p.position = ideal.mirror().pinholeInViewpoint() + 1e-3 * Vec3(m.offsetMm[0], m.offsetMm[1], m.offsetMm[2]);
  p.viewpointFromPinhole = (Eigen::AngleAxisd(radians(m.rotationDeg[0]), Vec3::UnitX()) *
                            Eigen::AngleAxisd(radians(m.rotationDeg[1]), Vec3::UnitY()) *
                            Eigen::AngleAxisd(radians(m.rotationDeg[2]), Vec3::UnitZ()))
                               .toRotationMatrix();
  p.focalPx = ideal.physicalFocalLength();
  p.principalPoint = ideal.centre() + Vec2(m.principalPointOffsetPx[0], m.principalPointOffsetPx[1]);
  p.distortion = m.distortion;
  return p;
}

PhysicalCamera::PhysicalCamera(const RigSpec& rig)
    : Camera(rig), mirror_(rig.mirror()), pinhole_(pinholeOf(rig)), rimZ_(rig.idealCamera().rimPoint().z()) {
  // Below the vertex the pinhole is outside the (upper sheet's) mirror.
  if (!(pinhole_.position.z() < mirror_.heightAt(0.0, 0.0)))
    throw InputError("camera.offset_mm: puts the pinhole on or above the mirror; it must stay below its vertex");
  checkMirrorInView();
}

void PhysicalCamera::checkMirrorInView() const {
  // A camera turned or moved away from the mirror, or a lens that folds early, renders a black
  // frame: refuse it instead. Compared on a coarse grid with the ideal camera's footprint.
  constexpr int kGrid = 24;
  const RigSpec& r = rig();
  const OmniCamera ideal = r.idealCamera();
  int seen = 0, idealSeen = 0;
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const Vec2 raster((i + 0.5) * r.imageSize / kGrid, (j + 0.5) * r.imageSize / kGrid);
      seen += generateRay({raster}).has_value();
      idealSeen += ideal.insideRim(raster);
    }
  if (4 * seen < idealSeen)
    throw InputError("camera: the mirror fills " + std::to_string(100 * seen / std::max(idealSeen, 1)) +
                     " % of what the ideal camera sees of it (at least 25 % needed): the camera is moved or turned "
                     "away from the mirror, or its lens folds inside the image");
}

std::optional<Vec3> PhysicalCamera::mirrorPointSeen(const Vec3& direction) const {
  const auto point = mirror_.firstHit(pinhole_.position, direction);
  if (!point || point->z() > rimZ_) return std::nullopt;
  return point;
}

std::optional<CameraRay> PhysicalCamera::generateRay(const CameraSample& sample) const {
  const auto d = pinhole_.direction(sample.raster);
  if (!d) return std::nullopt;
  const auto m = mirrorPointSeen(*d);
  if (!m) return std::nullopt;
  const Vec3 n = mirror_.normalAt(*m);
  return CameraRay{*m, (*d - 2.0 * d->dot(n) * n).normalized()};
}

namespace {

// Fermat: the reflection point is where the path pinhole → mirror → point is stationary. On the
// sheet as a height field M(x, y) = (x, y, z(x, y)), its gradient is −(û_O + û_P)·∂M, with û the
// unit vectors from M to the pinhole O and to the point P; this returns (û_O + û_P)·∂M/∂x, ·∂M/∂y.
Vec2 reflectionResidual(const HyperbolicMirror& mirror, const Vec3& o, const Vec3& p, const Vec2& xy) {
  const Vec3 m(xy.x(), xy.y(), mirror.heightAt(xy.x(), xy.y()));
  const Vec3 s = (o - m).normalized() + (p - m).normalized();
  const Vec2 slope = mirror.slopeAt(xy.x(), xy.y());
  return {s.x() + s.z() * slope.x(), s.y() + s.z() * slope.y()};
}

}  // namespace

std::optional<Vec2> PhysicalCamera::project(const Vec3& p) const {
  const Vec3& o = pinhole_.position;
  // Start where the central model sees the point: exact for the ideal rig, close otherwise.
  const auto start = mirror_.pointAlong(p);
  if (!start) return std::nullopt;
  Vec2 xy = start->head<2>();
  const double scale = mirror_.c();
  const double h = 1e-7 * scale;  // central differences: truncation h², rounding ε/h, both far below a step
  bool converged = false;
  for (int iteration = 0; iteration < 60 && !converged; ++iteration) {
    const Vec2 f = reflectionResidual(mirror_, o, p, xy);
    Eigen::Matrix2d j;
    for (int axis = 0; axis < 2; ++axis) {
      Vec2 step = Vec2::Zero();
      step[axis] = h;
      j.col(axis) = (reflectionResidual(mirror_, o, p, xy + step) - reflectionResidual(mirror_, o, p, xy - step)) / (2 * h);
    }
    if (!(std::abs(j.determinant()) > 0.0)) return std::nullopt;
    Vec2 delta = j.inverse() * f;
    // Damped: never a step longer than a tenth of c, so the iterate stays on the mirror's scale.
    if (delta.norm() > 0.1 * scale) delta *= 0.1 * scale / delta.norm();
    xy -= delta;
    if (!xy.allFinite()) return std::nullopt;
    // Quadratic convergence: once a step is this small the next would be below rounding.
    converged = delta.norm() <= 1e-13 * scale;
  }
  if (!converged) return std::nullopt;
  const Vec3 m(xy.x(), xy.y(), mirror_.heightAt(xy.x(), xy.y()));
  if (m.z() > rimZ_) return std::nullopt;
  // The physical root: pinhole and point both on the mirror's outer side, and the mirror point
  // the first thing the pinhole sees in that direction.
  const Vec3 n = mirror_.normalAt(m);
  const Vec3 toPinhole = (o - m).normalized(), toPoint = (p - m).normalized();
  if (!(n.dot(toPinhole) * n.dot(toPoint) > 0.0)) return std::nullopt;
  const auto seen = mirrorPointSeen(m - o);
  if (!seen || (*seen - m).norm() > 1e-9 * scale) return std::nullopt;
  return pinhole_.raster(m);
}

std::optional<MeiIntrinsics> PhysicalCamera::meiEquivalent() const {
  const CameraMount& mount = rig().mount;
  if (mount.offsetMm != std::array<double, 3>{0.0, 0.0, 0.0} || mount.rotationDeg != std::array<double, 3>{0.0, 0.0, 0.0} ||
      mount.distortion.k3 != 0.0)
    return std::nullopt;
  // The aligned pinhole's normalised coordinates are the unified model's scaled by s = γ/f with
  // v's sign flipped (γ_y = −γ), so its lens is Mei's distortion with rescaled coefficients;
  // cv::omnidir has no k3.
  const OmniCamera ideal = rig().idealCamera();
  const OpenCvIntrinsics k = ideal.openCvIntrinsics();
  const double s = ideal.gamma() / pinhole_.focalPx;
  const LensDistortion& l = mount.distortion;
  MeiIntrinsics mei;
  mei.xi = k.xi, mei.gammaX = k.gamma_x, mei.gammaY = k.gamma_y;
  mei.cx = pinhole_.principalPoint.x() - 0.5;
  mei.cy = pinhole_.principalPoint.y() - 0.5;
  mei.lens = {l.k1 * s * s, l.k2 * s * s * s * s, -l.p1 * s, l.p2 * s, 0.0};
  return mei;
}

const CentralApproximation& PhysicalCamera::centralApproximation() const {
  std::call_once(fitOnce_, [this] { fit_ = std::make_unique<CentralApproximation>(fitCentralApproximation(*this)); });
  return *fit_;
}

nlohmann::json PhysicalCamera::describe() const {
  const CameraMount& mount = rig().mount;
  const LensDistortion& l = mount.distortion;
  const bool atFocus = mount.offsetMm == std::array<double, 3>{0.0, 0.0, 0.0};
  nlohmann::json out = {
      {"model", "physical"},
      // A pinhole at F keeps the single viewpoint whatever its rotation or lens.
      {"non_central", !atFocus},
      {"width", width()},
      {"height", height()},
      {"pixel_centre", "half-integer"},
      {"pinhole",
       {{"position_m", {pinhole_.position.x(), pinhole_.position.y(), pinhole_.position.z()}},
        {"rotation_deg", mount.rotationDeg},
        {"focal_px", pinhole_.focalPx},
        {"principal_point_px", {pinhole_.principalPoint.x(), pinhole_.principalPoint.y()}},
        {"distortion", {{"k1", l.k1}, {"k2", l.k2}, {"p1", l.p1}, {"p2", l.p2}, {"k3", l.k3}}}}},
      {"mirror", {{"shape", "hyperboloid"}, {"k", mirror_.k()}, {"c", mirror_.c()}, {"rim_z_m", rimZ_}}},
      {"note",
       "each pixel's ray leaves the mirror from its own point; positions in the viewpoint frame (origin "
       "F', robot axes: x forward, y left, z up; the sidecar's camera_from_world frame is it turned by "
       "diag(1, -1, -1)); non_central: false when all reflected rays' lines meet in F'; pinhole axes x = image u, y = image v, z = optical "
       "axis; raster coordinates continuous (pixel centres at +0.5)"}};
  if (const auto mei = meiEquivalent()) {
    nlohmann::json exact = unifiedIntrinsicsJson(rig().idealCamera());
    if (!pinhole_.distortion.none()) {
      // The lens bends the rim and horizon circles: no radius describes them.
      exact.erase("rim_radius_px");
      exact.erase("horizon_radius_px");
    }
    exact["cx"] = mei->cx;
    exact["cy"] = mei->cy;
    exact["distortion"] = {mei->lens.k1, mei->lens.k2, mei->lens.p1, mei->lens.p2};
    out["mei_equivalent"] = exact;
  } else {
    // No central model is exact here; say how close the best one comes.
    out["central_approximation"] = toJson(centralApproximation());
  }
  return out;
}

}  // namespace omnicam
