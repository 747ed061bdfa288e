#include "physical_camera.h"

#include <cmath>

#include "central_camera.h"
#include "errors.h"
#include "fermat_path.h"
#include "lens_distortion.h"

namespace omnicam {

PhysicalCamera::PhysicalCamera(const RigSpec& rig) : Camera(rig), mirror_(mirrorSurfaceOf(rig.mirrorRig())), pinhole_(pinholeOf(rig.mirrorRig())) {
  if (pinhole_.orthographic && !pinhole_.distortion.none())
    throw InputError("camera.distortion: the paraboloid's orthographic camera has no lens model here; give "
                     "rig.mirror.camera_distance_m for a perspective camera");
  // Below the vertex the camera is outside the mirror.
  if (!(pinhole_.position.z() < mirror_->heightAt(0.0, 0.0)))
    throw InputError("camera.offset_mm: puts the pinhole on or above the mirror; it must stay below its vertex");
  checkMirrorInView();
}

void PhysicalCamera::checkMirrorInView() const {
  // A camera turned or moved away from the mirror, or a lens that folds early, renders a black
  // frame: refuse it instead. Compared on a coarse grid with the disc inscribed in the image,
  // which the ideal camera of every shape fills (its rim touches the border).
  constexpr int kGrid = 24;
  const double size = width();  // square
  int seen = 0, disc = 0;
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const Vec2 raster((i + 0.5) * size / kGrid, (j + 0.5) * size / kGrid);
      seen += generateRay({raster}).has_value();
      disc += (raster - Vec2(0.5 * size, 0.5 * size)).norm() <= 0.5 * size;
    }
  if (4 * seen < disc)
    throw InputError("camera: the mirror fills " + std::to_string(100 * seen / std::max(disc, 1)) +
                     " % of the image's disc (at least 25 % needed): the camera is moved or turned "
                     "away from the mirror, or its lens folds inside the image");
}

std::optional<Vec3> PhysicalCamera::mirrorPointSeen(const CameraRay& ray) const {
  const auto point = mirror_->firstHit(ray.origin, ray.direction);
  if (!point || !mirror_->insideRim(*point)) return std::nullopt;
  return point;
}

std::optional<CameraRay> PhysicalCamera::generateRay(const CameraSample& sample) const {
  const auto ray = pinhole_.ray(sample.raster);
  if (!ray) return std::nullopt;
  const auto m = mirrorPointSeen(*ray);
  if (!m) return std::nullopt;
  const Vec3 n = mirror_->normalAt(*m);
  const Vec3& d = ray->direction;
  return CameraRay{*m, (d - 2.0 * d.dot(n) * n).normalized()};
}

namespace {

// Fermat: the reflection point is where the path camera → mirror → point is stationary. On the
// mirror as a height field M(x, y) = (x, y, z(x, y)), its gradient is −(û_C + û_P)·∂M, with û the
// unit vectors from M toward the camera and toward the point P; this returns (û_C + û_P)·∂M/∂x,
// ·∂M/∂y. Toward the camera: to the pinhole, or against the axis of an orthographic camera.
Vec2 reflectionResidual(const MirrorSurface& mirror, const Pinhole& camera, const Vec3& p, const Vec2& xy) {
  const Vec3 m(xy.x(), xy.y(), mirror.heightAt(xy.x(), xy.y()));
  const Vec3 s = -camera.rayTo(m).direction + (p - m).normalized();
  const Vec2 slope = mirror.slopeAt(xy.x(), xy.y());
  return {s.x() + s.z() * slope.x(), s.y() + s.z() * slope.y()};
}

}  // namespace

std::optional<Vec3> PhysicalCamera::reflectionPoint(const Vec3& p, Vec2 xy) const {
  const MirrorSurface& mirror = *mirror_;
  const double scale = mirror.rimRadius();
  const double h = 1e-7 * scale;  // central differences: truncation h², rounding ε/h, both far below a step
  bool converged = false;
  for (int iteration = 0; iteration < 100 && !converged; ++iteration) {
    const Vec2 f = reflectionResidual(mirror, pinhole_, p, xy);
    Eigen::Matrix2d j;
    for (int axis = 0; axis < 2; ++axis) {
      Vec2 step = Vec2::Zero();
      step[axis] = h;
      j.col(axis) = (reflectionResidual(mirror, pinhole_, p, xy + step) - reflectionResidual(mirror, pinhole_, p, xy - step)) / (2 * h);
    }
    if (!(std::abs(j.determinant()) > 0.0)) return std::nullopt;
    Vec2 delta = j.inverse() * f;
    // Damped: never a step longer than a tenth of the rim radius, so the iterate stays on the mirror.
    if (delta.norm() > 0.1 * scale) delta *= 0.1 * scale / delta.norm();
    xy -= delta;
    // Off the mirror (no reflection point out there): give up early, not after every iteration.
    if (!xy.allFinite() || xy.norm() > 2.0 * scale) return std::nullopt;
    // Quadratic convergence: once a step is this small the next would be below rounding.
    converged = delta.norm() <= 1e-13 * scale;
  }
  if (!converged) return std::nullopt;
  const Vec3 m(xy.x(), xy.y(), mirror.heightAt(xy.x(), xy.y()));
  return physicalReflection(p, m) ? std::optional<Vec3>(m) : std::nullopt;
}

bool PhysicalCamera::physicalReflection(const Vec3& p, const Vec3& m) const {
  if (!mirror_->insideRim(m)) return false;
  // The physical root: camera and point both on the mirror's outer side, and the mirror point
  // the first thing the camera sees along its ray to it.
  const Vec3 n = mirror_->normalAt(m);
  const CameraRay toM = pinhole_.rayTo(m);
  if (!(n.dot(-toM.direction) * n.dot((p - m).normalized()) > 0.0)) return false;
  const auto seen = mirrorPointSeen(toM);
  return seen && (*seen - m).norm() <= 1e-9 * mirror_->rimRadius();
}

std::optional<Vec2> PhysicalCamera::project(const Vec3& p) const {
  // A perspective pinhole on the axis of a shape with a closed form (the cone) needs no search:
  // the closed form is the answer, "not seen" included.
  if (!pinhole_.orthographic && pinhole_.position.head<2>().squaredNorm() == 0.0)
    if (const auto axial = mirror_->axialReflection(p, pinhole_.position.z())) {
      if (!*axial || !physicalReflection(p, **axial)) return std::nullopt;
      return pinhole_.raster(**axial);
    }
  for (const Vec2& start : mirror_->projectionStarts(p, pinhole_.position))
    if (const auto m = reflectionPoint(p, start)) return pinhole_.raster(*m);
  // The straight path from the camera to p through the mirror's body: no mirror point reflects p
  // (fermat_path.h), and the search need not say so.
  if (straightPathMeetsBody(p)) return std::nullopt;
  // The minimum at a corner of the body, proven on the spot: nothing reflects p either.
  if (minimumAtACorner(p)) return std::nullopt;
  // The shape's starts are quick and almost always enough; the convex search always converges.
  return projectFromFermatMinimum(p);
}

namespace {

// −∇L at x: the unit vectors from x toward the camera and toward p, added.
Vec3 descent(const Vec3& x, const Vec3& camera, const Vec3& p) { return (camera - x).normalized() + (p - x).normalized(); }

}  // namespace

bool PhysicalCamera::minimumAtACorner(const Vec3& p) const {
  // L(X) = |X − camera| + |X − p| is convex, so a point of the body where −∇L lies in the body's
  // normal cone is where L is least over the body (the optimality condition of a convex problem
  // is also sufficient). When the straight path misses the body that minimum is unique, and a
  // reflection point would be one (fermat_path.h): a minimum at a corner — strictly inside its
  // normal cone, not on the mirror's own normal — means no mirror point reflects p. Margins of
  // 10⁻⁴ leave every doubtful case to the search.
  if (pinhole_.orthographic) return false;
  const Vec3& c = pinhole_.position;
  const MirrorSurface& mirror = *mirror_;
  constexpr double kMargin = 1e-4;
  if (mirror.hasApex()) {
    // The apex (the origin): its normal cone is {v : v_z ≤ −|v_xy| / slope}, the slope of the
    // generators (∂z/∂r) around it.
    const Vec3 w = descent(Vec3::Zero(), c, p);
    const double slope = mirror.slopeAt(1e-9 * mirror.rimRadius(), 0.0).norm();
    if (w.z() < -w.head<2>().norm() / slope - kMargin * w.norm()) return true;
  }
  // The rim's edge: where L is least along the rim circle on p's side of the axis, dL/dθ = −r·(w·t)
  // vanishes (w = −∇L, t the circle's tangent); bisected on w·t itself, which, unlike L a
  // kilometre long, rounding does not flatten. Then the condition there: −∇L = a·(∇h, −1) + b·e_z
  // with a, b > 0 (∇h the mirror's slope, radial at the rim).
  const double r = mirror.rimRadius(), top = mirror.rimZ();
  const auto rimPoint = [&](double theta) { return Vec3(r * std::cos(theta), r * std::sin(theta), top); };
  const auto tangential = [&](double theta) {
    return descent(rimPoint(theta), c, p).dot(Vec3(-std::sin(theta), std::cos(theta), 0.0));
  };
  const Vec2 side = p.head<2>() - c.head<2>();
  const double towardP = side.squaredNorm() > 0.0 ? std::atan2(side.y(), side.x()) : 0.0;
  double lo = towardP - 0.5 * kPi, hi = towardP + 0.5 * kPi;
  if (!(tangential(lo) > 0.0 && tangential(hi) < 0.0)) return false;  // no minimum bracketed
  for (int step = 0; step < 60 && hi - lo > 1e-15; ++step) {
    const double middle = 0.5 * (lo + hi);
    (tangential(middle) > 0.0 ? lo : hi) = middle;
  }
  const double theta = 0.5 * (lo + hi);
  const Vec3 x = rimPoint(theta);
  const Vec3 w = descent(x, c, p);
  const Vec2 slope = mirror.slopeAt(x.x(), x.y());
  if (!(std::abs(tangential(theta)) <= 1e-9 * w.norm()) || !(slope.squaredNorm() > 0.0)) return false;
  const double onMirror = w.head<2>().dot(slope) / slope.squaredNorm();  // a
  const double onTop = w.z() + onMirror;                                 // b
  return onMirror > kMargin * w.norm() && onTop > kMargin * w.norm();
}

bool PhysicalCamera::straightPathMeetsBody(const Vec3& p) const {
  if (pinhole_.orthographic) return false;  // its paths run along the axis: left to the search
  const Vec3& c = pinhole_.position;
  const Vec3 toP = p - c;
  const double length = toP.norm();
  if (!(length > 0.0)) return true;
  const Vec3 direction = toP / length;
  // In through the mirror (the camera is below it, outside the body), within the rim ...
  if (const auto hit = mirror_->firstHit(c, direction))
    if (mirror_->insideRim(*hit) && (*hit - c).norm() <= length) return true;
  // ... or through the rim's disc.
  if (direction.z() != 0.0) {
    const double t = (mirror_->rimZ() - c.z()) / direction.z();
    if (t > 0.0 && t <= length && (c + t * direction).head<2>().norm() <= mirror_->rimRadius()) return true;
  }
  return false;
}

std::optional<Vec2> PhysicalCamera::projectFromFermatMinimum(const Vec3& p) const {
  const FermatMinimum minimum = minimiseFermatPath(*mirror_, pinhole_, p);
  // On the rim plane or inside the body, the reflection law has no solution at all
  // (fermat_path.h). On the mirror, or at one of its corners, Newton's method polishes the point
  // and the checks tell whether it reflects.
  if (minimum.on == FermatMinimum::On::Inside || minimum.on == FermatMinimum::On::RimPlane) return std::nullopt;
  const auto m = reflectionPoint(p, minimum.point.head<2>());
  if (!m) return std::nullopt;
  return pinhole_.raster(*m);
}

std::optional<MeiIntrinsics> PhysicalCamera::meiEquivalent() const {
  const MirrorRig& rig = this->rig().mirrorRig();
  const CameraMount& mount = rig.mount;
  const auto* paraboloid = std::get_if<ParaboloidMirror>(&rig.shape);
  if (paraboloid && pinhole_.orthographic &&
      mount.rotationDeg == std::array<double, 3>{0.0, 0.0, 0.0}) {
    // The orthographic paraboloid is the unified model with ξ = 1 (Geyer and Daniilidis): a
    // mirror point at radius r = h·tan(θ/2) seen f px per metre gives γ = h·f. Moving the camera
    // sideways moves the mirror's image by −f·offset; along the axis, nothing.
    const double gamma = paraboloid->h * pinhole_.focalPx;
    const Vec2 centre = pinhole_.principalPoint - pinhole_.focalPx * pinhole_.position.head<2>();
    MeiIntrinsics mei;
    mei.xi = 1.0, mei.gammaX = gamma, mei.gammaY = -gamma;
    mei.cx = centre.x() - 0.5;
    mei.cy = centre.y() - 0.5;
    return mei;
  }
  if (!std::holds_alternative<HyperboloidMirror>(rig.shape) || mount.offsetMm != std::array<double, 3>{0.0, 0.0, 0.0} ||
      mount.rotationDeg != std::array<double, 3>{0.0, 0.0, 0.0} || mount.distortion.k3 != 0.0)
    return std::nullopt;
  // The aligned pinhole's normalised coordinates are the unified model's scaled by s = γ/f with
  // v's sign flipped (γ_y = −γ), so its lens is Mei's distortion with rescaled coefficients;
  // cv::omnidir has no k3.
  const OmniCamera ideal = rig.idealCamera();
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

namespace {

// Whether the reflected rays' lines all meet in one point: the hyperboloid's pinhole at F, or
// the paraboloid's orthographic camera looking along its axis (wherever it is moved sideways).
bool singleViewpoint(const MirrorRig& rig, const Pinhole& camera) {
  const CameraMount& mount = rig.mount;
  return std::visit(
      Overloaded{[&](const HyperboloidMirror&) { return mount.offsetMm == std::array<double, 3>{0.0, 0.0, 0.0}; },
                 [&](const ParaboloidMirror&) {
                   return camera.orthographic && mount.rotationDeg == std::array<double, 3>{0.0, 0.0, 0.0};
                 },
                 [](const SphereMirror&) { return false; }, [](const ConeMirror&) { return false; }},
      rig.shape);
}

}  // namespace

nlohmann::json PhysicalCamera::describe() const {
  const MirrorRig& rig = this->rig().mirrorRig();
  const CameraMount& mount = rig.mount;
  const LensDistortion& l = mount.distortion;
  nlohmann::json out = {
      {"model", "physical"},
      {"non_central", !singleViewpoint(rig, pinhole_)},
      {"width", width()},
      {"height", height()},
      {"pixel_centre", "half-integer"},
      {"pinhole",
       {{"projection", pinhole_.orthographic ? "orthographic" : "perspective"},
        {"position_m", {pinhole_.position.x(), pinhole_.position.y(), pinhole_.position.z()}},
        {"rotation_deg", mount.rotationDeg},
        {pinhole_.orthographic ? "px_per_m" : "focal_px", pinhole_.focalPx},
        {"principal_point_px", {pinhole_.principalPoint.x(), pinhole_.principalPoint.y()}},
        {"distortion", {{"k1", l.k1}, {"k2", l.k2}, {"p1", l.p1}, {"p2", l.p2}, {"k3", l.k3}}}}},
      {"mirror", mirror_->toJson()},
      {"note",
       "each pixel's ray leaves the mirror from its own point; positions in the viewpoint frame (origin at "
       "the mirror's design point: the hyperboloid's F', the paraboloid's focus, the sphere's centre, the "
       "cone's apex; robot axes: x forward, y left, z up, turned by the rig's tilt_deg; the sidecar's camera_from_world frame is it "
       "turned by diag(1, -1, -1)); non_central: false when all reflected rays' lines meet in one point; "
       "pinhole axes x = image u, y = image v, z = optical axis; raster coordinates continuous (pixel "
       "centres at +0.5)"}};
  if (const auto mei = meiEquivalent()) {
    nlohmann::json exact = mei->toJson();
    exact.update({{"width", width()}, {"height", height()}});
    if (std::holds_alternative<HyperboloidMirror>(rig.shape)) exact = unifiedIntrinsicsJson(rig.idealCamera());
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
