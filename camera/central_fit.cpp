#include "central_fit.h"

#include <unsupported/Eigen/NonLinearOptimization>
#include <unsupported/Eigen/NumericalDiff>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "lens_distortion.h"

namespace omnicam {

std::optional<Vec2> MeiIntrinsics::raster(const Vec3& pointCamera) const {
  const double n = pointCamera.norm();
  if (!(n > 0.0)) return std::nullopt;
  const Vec3 s = pointCamera / n;
  const double denom = s.z() + xi;
  if (!(denom > 0.0)) return std::nullopt;
  const Vec2 d = distort(lens, Vec2(s.x() / denom, s.y() / denom));
  return Vec2(gammaX * d.x() + cx + 0.5, gammaY * d.y() + cy + 0.5);
}

nlohmann::json MeiIntrinsics::toJson() const {
  return {{"model", "mei_unified"}, {"xi", xi}, {"gamma_x", gammaX}, {"gamma_y", gammaY}, {"cx", cx}, {"cy", cy},
          {"pixel_centre", "integer"}, {"distortion", {lens.k1, lens.k2, lens.p1, lens.p2}}};
}

std::optional<Vec3> MeiIntrinsics::direction(const Vec2& raster) const {
  const Vec2 distorted((raster.x() - 0.5 - cx) / gammaX, (raster.y() - 0.5 - cy) / gammaY);
  const std::optional<Vec2> m = undistort(lens, distorted);
  if (!m) return std::nullopt;
  // The unit-sphere point s with (s.x, s.y) / (s.z + ξ) = m: s = λ(m, 1) − (0, 0, ξ),
  // λ = (ξ + sqrt(1 + (1 − ξ²) r²)) / (1 + r²).
  const double r2 = m->squaredNorm(), discriminant = 1.0 + (1.0 - xi * xi) * r2;
  if (!(discriminant >= 0.0)) return std::nullopt;
  const double lambda = (xi + std::sqrt(discriminant)) / (1.0 + r2);
  const Vec3 s(lambda * m->x(), lambda * m->y(), lambda - xi);
  // The projection's own condition: in front of the model (z_s + ξ > 0).
  if (!(s.z() + xi > 0.0)) return std::nullopt;
  return s.normalized();
}

Vec3 pointAtDistance(const CameraRay& ray, const Vec3& centre, double distance) {
  const Vec3 fromCentre = ray.origin - centre;
  const double b = ray.direction.dot(fromCentre);
  const double t = -b + std::sqrt(std::max(0.0, b * b - (fromCentre.squaredNorm() - distance * distance)));
  return ray.origin + t * ray.direction;
}

namespace {

struct GridRay {
  Vec2 raster;
  CameraRay ray;
};

std::vector<GridRay> gridRays(const Camera& camera, int gridSize) {
  const int strideX = std::max(1, camera.width() / gridSize), strideY = std::max(1, camera.height() / gridSize);
  std::vector<GridRay> rays;
  for (int j = strideY / 2; j < camera.height(); j += strideY)
    for (int i = strideX / 2; i < camera.width(); i += strideX) {
      const Vec2 centre(i + 0.5, j + 0.5);
      if (const auto ray = camera.generateRay({centre})) rays.push_back({centre, *ray});
    }
  return rays;
}

// The point nearest all rays: argmin Σ |(I − d dᵀ)(x − o)|², a 3×3 linear system.
Vec3 nearestPointToRays(const std::vector<GridRay>& rays) {
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Vec3 b = Vec3::Zero();
  for (const GridRay& g : rays) {
    const Eigen::Matrix3d p = Eigen::Matrix3d::Identity() - g.ray.direction * g.ray.direction.transpose();
    a += p;
    b += p * g.ray.origin;
  }
  return a.ldlt().solve(b);
}

// Parameters: ξ, γx, γy, cx, cy, k1, k2, p1, p2, rotation vector (3).
constexpr int kParameters = 12;

MeiIntrinsics intrinsicsOf(const Eigen::VectorXd& x) {
  MeiIntrinsics k;
  k.xi = x[0], k.gammaX = x[1], k.gammaY = x[2], k.cx = x[3], k.cy = x[4];
  k.lens.k1 = x[5], k.lens.k2 = x[6], k.lens.p1 = x[7], k.lens.p2 = x[8];
  return k;
}

Eigen::Matrix3d rotationOf(const Vec3& rotationVector) {
  const double angle = rotationVector.norm();
  if (angle == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, rotationVector / angle).toRotationMatrix();
}

// Reprojection residuals of every ray's direction (a point at infinity) for Eigen's
// Levenberg–Marquardt. A direction behind the model costs a fixed large residual.
struct DirectionResiduals {
  using Scalar = double;
  using InputType = Eigen::VectorXd;
  using ValueType = Eigen::VectorXd;
  using JacobianType = Eigen::MatrixXd;
  enum { InputsAtCompileTime = Eigen::Dynamic, ValuesAtCompileTime = Eigen::Dynamic };

  const std::vector<GridRay>* rays = nullptr;
  Eigen::Matrix3d idealCameraFromViewpoint;

  int inputs() const { return kParameters; }
  int values() const { return 2 * static_cast<int>(rays->size()); }
  int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& residual) const {
    const MeiIntrinsics k = intrinsicsOf(x);
    const Eigen::Matrix3d r = rotationOf(x.segment<3>(9)) * idealCameraFromViewpoint;
    for (size_t n = 0; n < rays->size(); ++n) {
      const GridRay& g = (*rays)[n];
      const auto p = k.raster(r * g.ray.direction);
      residual.segment<2>(2 * static_cast<Eigen::Index>(n)) = p ? Vec2(*p - g.raster) : Vec2(1e3, 1e3);
    }
    return 0;
  }
};

// The fit's reprojection error for the point of `g`'s ray at `distance` from the fitted viewpoint
// (the ray starts within it); 0 = infinity, where the model sees the ray's direction.
double reprojectionError(const CentralApproximation& fit, const GridRay& g, double distance) {
  const std::optional<Vec2> p = distance == 0.0 ? fit.intrinsics.raster(fit.cameraFromViewpoint.linear() * g.ray.direction)
                                                : fit.raster(pointAtDistance(g.ray, fit.viewpoint, distance));
  return p ? (*p - g.raster).norm() : std::numeric_limits<double>::infinity();
}

// The angle between the model's ray of the pixel and the direction from its viewpoint to the
// true point (the true ray's direction at infinity).
double rayError(const CentralApproximation& fit, const GridRay& g, double distance) {
  const std::optional<Vec3> model = fit.direction(g.raster);
  if (!model) return std::numeric_limits<double>::infinity();
  const Vec3 truth = distance == 0.0 ? g.ray.direction : (pointAtDistance(g.ray, fit.viewpoint, distance) - fit.viewpoint).normalized();
  return std::atan2(model->cross(truth).norm(), model->dot(truth));
}

CentralApproximation::Residual residualAt(const CentralApproximation& fit, const std::vector<GridRay>& rays, double distance) {
  CentralApproximation::Residual r;
  r.distanceM = distance;
  double sumSquares = 0.0;
  for (const GridRay& g : rays) {
    const double error = reprojectionError(fit, g, distance);
    sumSquares += error * error;
    r.maxPx = std::max(r.maxPx, error);
  }
  r.rmsPx = std::sqrt(sumSquares / static_cast<double>(rays.size()));
  return r;
}

// Where the fit starts: the hyperboloid's own unified model; for the other shapes the parabolic
// one (ξ = 1) centred in the image, its γx, γy by linear least squares on the rays.
Eigen::VectorXd initialGuess(const Camera& camera, const std::vector<GridRay>& rays, const Eigen::Matrix3d& cameraFromViewpoint) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(kParameters);
  const MirrorRig& rig = camera.rig().mirrorRig();
  if (std::holds_alternative<HyperboloidMirror>(rig.shape)) {
    const OpenCvIntrinsics ideal = rig.idealCamera().openCvIntrinsics();
    x[0] = ideal.xi, x[1] = ideal.gamma_x, x[2] = ideal.gamma_y, x[3] = ideal.cx, x[4] = ideal.cy;
    return x;
  }
  x[0] = 1.0;
  x[3] = 0.5 * camera.width() - 0.5;
  x[4] = 0.5 * camera.height() - 0.5;
  Vec2 um = Vec2::Zero(), mm = Vec2::Zero();
  for (const GridRay& g : rays) {
    const Vec3 s = (cameraFromViewpoint * g.ray.direction).normalized();
    if (s.z() + 1.0 < 1e-3) continue;
    const Vec2 m(s.x() / (s.z() + 1.0), s.y() / (s.z() + 1.0));
    const Vec2 u(g.raster.x() - 0.5 - x[3], g.raster.y() - 0.5 - x[4]);
    um += u.cwiseProduct(m);
    mm += m.cwiseProduct(m);
  }
  x[1] = mm.x() > 0.0 ? um.x() / mm.x() : 1.0;
  x[2] = mm.y() > 0.0 ? um.y() / mm.y() : -1.0;
  return x;
}

}  // namespace

CentralApproximation fitCentralApproximation(const Camera& camera, const std::vector<double>& distancesM, int gridSize) {
  const std::vector<GridRay> rays = gridRays(camera, gridSize);
  if (rays.empty()) throw std::runtime_error("central fit: the camera images no pixel of the grid");
  CentralApproximation fit;
  fit.rays = static_cast<int>(rays.size());
  fit.viewpoint = nearestPointToRays(rays);

  DirectionResiduals residuals;
  residuals.rays = &rays;
  residuals.idealCameraFromViewpoint = omnicam::unifiedCameraFromViewpoint().linear();
  Eigen::VectorXd x = initialGuess(camera, rays, residuals.idealCameraFromViewpoint);
  Eigen::NumericalDiff<DirectionResiduals, Eigen::Central> differentiated(residuals);
  Eigen::LevenbergMarquardt<Eigen::NumericalDiff<DirectionResiduals, Eigen::Central>> solver(differentiated);
  solver.parameters.maxfev = 2000;
  solver.parameters.xtol = 1e-15;
  solver.parameters.ftol = 1e-15;
  solver.minimize(x);

  fit.intrinsics = intrinsicsOf(x);
  fit.rotationVector = x.segment<3>(9);
  const Eigen::Matrix3d cameraFromViewpointRotation = rotationOf(fit.rotationVector) * residuals.idealCameraFromViewpoint;
  fit.cameraFromViewpoint.linear() = cameraFromViewpointRotation;
  fit.cameraFromViewpoint.translation() = -(cameraFromViewpointRotation * fit.viewpoint);

  fit.residuals.push_back(residualAt(fit, rays, 0.0));  // at infinity: the fit itself
  for (double d : distancesM) fit.residuals.push_back(residualAt(fit, rays, d));
  return fit;
}

PixelRays pixelRays(const Camera& camera) {
  PixelRays out;
  out.width = camera.width(), out.height = camera.height();
  out.rays.reserve(static_cast<size_t>(out.width) * out.height);
  for (int j = 0; j < out.height; ++j)
    for (int i = 0; i < out.width; ++i) out.rays.push_back(camera.generateRay({pixelCentre(i, j)}));
  return out;
}

namespace {

// `error` of every pixel centre's true ray, row-major; NaN where the camera images nothing.
template <class Error>
std::vector<float> pixelMap(const PixelRays& rays, const Error& error) {
  std::vector<float> map(rays.rays.size(), std::numeric_limits<float>::quiet_NaN());
  for (int j = 0; j < rays.height; ++j)
    for (int i = 0; i < rays.width; ++i) {
      const size_t k = static_cast<size_t>(j) * rays.width + i;
      if (const std::optional<CameraRay>& ray = rays.rays[k]) map[k] = static_cast<float>(error(GridRay{pixelCentre(i, j), *ray}));
    }
  return map;
}

}  // namespace

std::vector<float> centralResidualMap(const PixelRays& rays, const CentralApproximation& fit, double distanceM) {
  return pixelMap(rays, [&](const GridRay& g) { return reprojectionError(fit, g, distanceM); });
}

std::vector<float> centralResidualMap(const Camera& camera, const CentralApproximation& fit, double distanceM) {
  return centralResidualMap(pixelRays(camera), fit, distanceM);
}

std::vector<float> centralRayErrorMap(const PixelRays& rays, const CentralApproximation& fit, double distanceM) {
  return pixelMap(rays, [&](const GridRay& g) { return rayError(fit, g, distanceM); });
}

std::vector<float> centralRayErrorMap(const Camera& camera, const CentralApproximation& fit, double distanceM) {
  return centralRayErrorMap(pixelRays(camera), fit, distanceM);
}

nlohmann::json toJson(const CentralApproximation& fit) {
  const MeiIntrinsics& k = fit.intrinsics;
  nlohmann::json residuals = nlohmann::json::array();
  for (const auto& r : fit.residuals)
    residuals.push_back({{"distance_m", r.distanceM == 0.0 ? nlohmann::json("infinity") : nlohmann::json(r.distanceM)},
                         {"rms_px", r.rmsPx},
                         {"max_px", r.maxPx}});
  nlohmann::json j = k.toJson();
  j.update({{"viewpoint_m", {fit.viewpoint.x(), fit.viewpoint.y(), fit.viewpoint.z()}},
            {"rotation_vector", {fit.rotationVector.x(), fit.rotationVector.y(), fit.rotationVector.z()}},
          {"rays", fit.rays},
          {"residual_px", residuals},
          {"note",
           "best-fit central model, not exact: viewpoint = the point nearest all rays (viewpoint frame); camera "
           "frame = the unified model's (X forward, Y right, Z down) turned by rotation_vector; intrinsics "
           "fitted to the rays' directions (points at infinity); residual_px: its reprojection error for "
           "points at each distance from the viewpoint along the true rays"}});
  return j;
}

}  // namespace omnicam
