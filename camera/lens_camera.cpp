#include "lens_camera.h"

#include "errors.h"

namespace omnicam {

namespace {

// omnicam's raster puts pixel centres at +½; the lens models at integers (OpenCV's).
const Vec2 kHalfPixel(0.5, 0.5);

bool inside(const Camera& camera, const Vec2& raster) {
  return raster.x() >= 0.0 && raster.y() >= 0.0 && raster.x() <= camera.width() && raster.y() <= camera.height();
}

}  // namespace

LensCamera::LensCamera(const RigSpec& rig) : Camera(rig) {
  if (!rig.lens) throw InputError("rig: a lens camera needs rig.lens");
  modelName_ = lensModelName(rig.lens->model);
  viewpointFromLens_ = viewpointFromLens(*rig.lens);
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

nlohmann::json fields(const KannalaBrandt& m) {
  return {{"fx", m.fx}, {"fy", m.fy}, {"cx", m.cx}, {"cy", m.cy}, {"k", m.k}, {"max_theta_deg", degrees(m.maxThetaRad)}};
}
nlohmann::json fields(const DoubleSphere& m) {
  return {{"fx", m.fx}, {"fy", m.fy}, {"cx", m.cx}, {"cy", m.cy}, {"xi", m.xi}, {"alpha", m.alpha}};
}
nlohmann::json fields(const ExtendedUnified& m) {
  return {{"fx", m.fx}, {"fy", m.fy}, {"cx", m.cx}, {"cy", m.cy}, {"alpha", m.alpha}, {"beta", m.beta}};
}
nlohmann::json fields(const FThetaLens& m) {
  nlohmann::json out = {{"cx", m.cx}, {"cy", m.cy}, {"fov_deg", 2.0 * degrees(m.maxThetaRad)}};
  if (m.kind == FThetaLens::Kind::Polynomial)
    out["k"] = m.k;
  else
    out["f_px"] = m.f;
  return out;
}
nlohmann::json fields(const Equirectangular& m) {
  return {{"longitude_deg", {degrees(m.lonMinRad), degrees(m.lonMaxRad)}},
          {"latitude_deg", {degrees(m.latMinRad), degrees(m.latMaxRad)}}};
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
  out["note"] = "camera frame at the effective viewpoint F': X right, Y down, Z along the optical axis (OpenCV's)";
  return out;
}

}  // namespace omnicam
