#include "lens_camera.h"

#include <cmath>
#include <limits>

#include "errors.h"

namespace omnicam {

namespace {

// omnicam's raster puts pixel centres at +½; the lens models at integers (OpenCV's).
const Vec2 kHalfPixel(0.5, 0.5);

bool inside(const Camera& camera, const Vec2& raster) {
  return raster.x() >= 0.0 && raster.y() >= 0.0 && raster.x() <= camera.width() && raster.y() <= camera.height();
}

}  // namespace

LensCamera::LensCamera(const RigSpec& rig) : Camera(rig), lens_(rig.lensCamera()) {
  modelName_ = lensModelName(lens().model);
  viewpointFromLens_ = viewpointFromLens(lens());
}

std::optional<CameraRay> LensCamera::generateRay(const CameraSample& sample) const {
  if (!inside(*this, sample.raster)) return std::nullopt;
  const auto d = lensDirection(lens().model, sample.raster - kHalfPixel);
  if (!d) return std::nullopt;
  return CameraRay{Vec3::Zero(), viewpointFromLens_ * *d};
}

std::optional<Vec2> LensCamera::project(const Vec3& pointViewpoint) const {
  const auto pixel = lensProject(lens().model, viewpointFromLens_.transpose() * pointViewpoint);
  if (!pixel) return std::nullopt;
  return *pixel + kHalfPixel;
}

bool LensCamera::images(const Vec2& raster) const {
  return inside(*this, raster) && lensDirection(lens().model, raster - kHalfPixel).has_value();
}

nlohmann::json LensCamera::describe() const { return lensIntrinsicsJson(lens()); }

namespace {

// Degrees that the scene format's reader turns back into exactly `rad` (it takes radians(d)):
// degrees(rad) itself, or one of its neighbours a few ulps away (the degrees a user wrote), so
// that a lens written out reads back equal — rig equality keys caches and resumed datasets.
double exactDegrees(double rad) {
  double up = degrees(rad), down = up;
  if (radians(up) == rad) return up;
  for (int step = 0; step < 16; ++step) {
    up = std::nextafter(up, std::numeric_limits<double>::infinity());
    down = std::nextafter(down, -std::numeric_limits<double>::infinity());
    if (radians(up) == rad) return up;
    if (radians(down) == rad) return down;
  }
  return degrees(rad);
}

nlohmann::json fields(const KannalaBrandt& m) {
  return {{"fx", m.fx}, {"fy", m.fy}, {"cx", m.cx}, {"cy", m.cy}, {"k", m.k}, {"max_theta_deg", exactDegrees(m.maxThetaRad)}};
}
nlohmann::json fields(const DoubleSphere& m) {
  return {{"fx", m.fx}, {"fy", m.fy}, {"cx", m.cx}, {"cy", m.cy}, {"xi", m.xi}, {"alpha", m.alpha}};
}
nlohmann::json fields(const ExtendedUnified& m) {
  return {{"fx", m.fx}, {"fy", m.fy}, {"cx", m.cx}, {"cy", m.cy}, {"alpha", m.alpha}, {"beta", m.beta}};
}
nlohmann::json fields(const FThetaLens& m) {
  nlohmann::json out = {{"cx", m.cx}, {"cy", m.cy}, {"fov_deg", 2.0 * exactDegrees(m.maxThetaRad)}};  // read as radians(fov / 2)
  if (m.kind == FThetaLens::Kind::Polynomial)
    out["k"] = m.k;
  else
    out["f_px"] = m.f;
  return out;
}
nlohmann::json fields(const Equirectangular& m) {
  return {{"longitude_deg", {exactDegrees(m.lonMinRad), exactDegrees(m.lonMaxRad)}},
          {"latitude_deg", {exactDegrees(m.latMinRad), exactDegrees(m.latMaxRad)}}};
}
nlohmann::json fields(const PinholeRadTan& m) {
  const LensDistortion& d = m.distortion;
  return {{"fx", m.fx}, {"fy", m.fy}, {"cx", m.cx}, {"cy", m.cy},
          {"distortion", {{"k1", d.k1}, {"k2", d.k2}, {"p1", d.p1}, {"p2", d.p2}, {"k3", d.k3}}}};
}

}  // namespace

nlohmann::json lensIntrinsicsJson(const LensCameraSpec& lens) {
  nlohmann::json out = std::visit([](const auto& m) { return fields(m); }, lens.model);
  out["model"] = lensModelName(lens.model);
  out["width"] = lens.width;
  out["height"] = lens.height;
  out["rotation_deg"] = lens.rotationDeg;
  out["pixel_centre"] = "integer";
  out["note"] = "camera frame at the lens' centre of projection (the rig's viewpoint): X right, Y down, Z along the optical axis (OpenCV's)";
  return out;
}

}  // namespace omnicam
