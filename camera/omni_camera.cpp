#include "omni_camera.h"

#include <cmath>
#include <string>

#include "errors.h"

namespace omnicam {

Rigid unifiedCameraFromViewpoint() {
  Rigid t = Rigid::Identity();
  t.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  return t;
}

namespace {
void requireElevation(double deg, const char* field) {
  if (!(deg > -90.0 && deg < 90.0))
    throw InputError(std::string(field) + ": must be in (-90, 90) degrees (got " +
                     std::to_string(deg) + ")");
}
}  // namespace

double incidenceAngle(const Vec3& d) { return std::atan2(std::hypot(d.x(), d.y()), d.z()); }

OmniCamera::OmniCamera(const HyperbolicMirror& mirror, int width, int height,
                       double rimElevationDeg, double framingElevationDeg)
    : mirror_(mirror), width_(width), height_(height), xi_(mirror.xi()) {
  if (width < 2 || height < 2) throw InputError("image.size: must be at least 2 pixels");
  requireElevation(rimElevationDeg, "mirror.rim_elevation_deg");
  requireElevation(framingElevationDeg, "image.framing_elevation_deg");
  const double framingTheta = radians(90.0 + framingElevationDeg);
  if (xi_ + std::cos(framingTheta) <= 0.0)
    throw InputError("image.framing_elevation_deg: beyond what this mirror can image");
  rimTheta_ = radians(90.0 + rimElevationDeg);
  if (xi_ + std::cos(rimTheta_) <= 0.0)
    throw InputError("mirror.rim_elevation_deg: beyond what this mirror can image");
  // Near the hyperboloid's asymptote (elevation atan(sqrt(2/(k−2))) above the horizon) the rim
  // runs off to infinity: no physical mirror, and POV-Ray's and the model's images part ways.
  // A rim within 5 c of F' keeps the mirror a compact sensor (the thesis mirror's: 0.43 c).
  const auto rimPoint = mirror_.pointAlong(Vec3(std::sin(rimTheta_), 0.0, -std::cos(rimTheta_)));
  if (!rimPoint || !(rimPoint->norm() <= 5.0 * mirror_.c()))
    throw InputError("mirror.rim_elevation_deg: with k = " + std::to_string(mirror_.k()) +
                     " the rim lies more than 5 c from F' (near the mirror's asymptote): use a larger k or a lower rim");
  rimPoint_ = *rimPoint;
  const double borderRadius = 0.5 * std::min(width, height);
  gamma_ = borderRadius * (xi_ + std::cos(framingTheta)) / std::sin(framingTheta);
  rimRadius_ = radiusOfTheta(rimTheta_);

  // The physical pinhole sees the framing circle's mirror point at the image border.
  const Vec3 framingDirViewpoint(std::sin(framingTheta), 0.0, -std::cos(framingTheta));
  const auto p = mirror_.pointAlong(framingDirViewpoint);
  if (!p) throw InputError("image.framing_elevation_deg: misses the mirror");
  const Vec3 fromPinhole = *p - mirror_.pinholeInViewpoint();
  physicalFocal_ = borderRadius * fromPinhole.z() / fromPinhole.x();
}

double OmniCamera::radiusOfTheta(double theta) const {
  return gamma_ * std::sin(theta) / (xi_ + std::cos(theta));
}

std::optional<Vec2> OmniCamera::rasterFromCameraUnclipped(const Vec3& d) const {
  const double n = d.norm();
  if (!(n > 0.0)) return std::nullopt;
  const Vec3 s = d / n;
  const double denom = s.z() + xi_;
  if (!(denom > 0.0)) return std::nullopt;
  return Vec2(0.5 * width_ + gamma_ * s.x() / denom, 0.5 * height_ - gamma_ * s.y() / denom);
}

std::optional<Vec2> OmniCamera::rasterFromCamera(const Vec3& d) const {
  if (incidenceAngle(d) > rimTheta_) return std::nullopt;
  return rasterFromCameraUnclipped(d);
}

Vec3 OmniCamera::cameraFromRaster(const Vec2& raster) const {
  const double mx = (raster.x() - 0.5 * width_) / gamma_;
  const double my = -(raster.y() - 0.5 * height_) / gamma_;
  const double s = mx * mx + my * my;
  const double eta = (xi_ + std::sqrt(1.0 + (1.0 - xi_ * xi_) * s)) / (1.0 + s);
  return Vec3(eta * mx, eta * my, eta - xi_).normalized();
}

OpenCvIntrinsics OmniCamera::openCvIntrinsics() const {
  return {xi_, gamma_, -gamma_, 0.5 * width_ - 0.5, 0.5 * height_ - 0.5};
}

}  // namespace omnicam
