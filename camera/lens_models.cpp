#include "lens_models.h"

#include <cmath>
#include <type_traits>

#include "lens_distortion.h"

namespace omnicam {

namespace {

constexpr int kNewtonSteps = 50;
constexpr double kNewtonTolerance = 1e-15;

// Solves g(t) = target for t ≥ 0 by Newton's method from `start`, where g grows (dg > 0);
// nullopt when it does not converge or g stops growing on the way.
template <class G, class DG>
std::optional<double> solveIncreasing(const G& g, const DG& dg, double target, double start) {
  double t = start;
  for (int step = 0; step < kNewtonSteps; ++step) {
    const double slope = dg(t);
    if (!(slope > 0.0)) return std::nullopt;
    const double next = std::max(0.0, t - (g(t) - target) / slope);
    if (std::abs(next - t) <= kNewtonTolerance * std::max(1.0, std::abs(t))) return next;
    t = next;
  }
  return std::nullopt;
}

// The ray at angle θ from the axis towards the image offset (dx, dy) (any length > 0).
Vec3 rayAt(double theta, double dx, double dy) {
  const double r = std::hypot(dx, dy);
  if (r == 0.0) return Vec3(0.0, 0.0, 1.0);
  return Vec3(std::sin(theta) * dx / r, std::sin(theta) * dy / r, std::cos(theta));
}

// --- Kannala–Brandt -------------------------------------------------------------------------------

double kbDistort(const KannalaBrandt& m, double theta) {
  const double t2 = theta * theta;
  return theta * (1.0 + t2 * (m.k[0] + t2 * (m.k[1] + t2 * (m.k[2] + t2 * m.k[3]))));
}

std::optional<Vec2> project(const KannalaBrandt& m, const Vec3& p) {
  const double r = std::hypot(p.x(), p.y());
  if (!(p.norm() > 0.0)) return std::nullopt;
  const double theta = std::atan2(r, p.z());
  if (theta > m.maxThetaRad) return std::nullopt;
  // On the axis: straight ahead is the centre; straight behind (a lens of 360°) is every point of
  // the θ = π circle, given at azimuth 0, never the centre.
  if (r == 0.0) return p.z() > 0.0 ? Vec2(m.cx, m.cy) : Vec2(m.cx + m.fx * kbDistort(m, theta), m.cy);
  const double scale = kbDistort(m, theta) / r;
  return Vec2(m.fx * scale * p.x() + m.cx, m.fy * scale * p.y() + m.cy);
}

std::optional<Vec3> direction(const KannalaBrandt& m, const Vec2& pixel) {
  const double mx = (pixel.x() - m.cx) / m.fx, my = (pixel.y() - m.cy) / m.fy;
  const double thetaD = std::hypot(mx, my);
  const std::optional<double> theta = solveIncreasing([&](double t) { return kbDistort(m, t); },
                                                      [&](double t) { return kbSlope(m, t); }, thetaD, thetaD);
  if (!theta || *theta > m.maxThetaRad) return std::nullopt;
  return rayAt(*theta, mx, my);
}

// --- double sphere --------------------------------------------------------------------------------

// The double sphere images a direction d (unit) only where d.z > −w2 (the paper's Eq. 43):
// beyond, the projection folds back.
bool imagedByDoubleSphere(const DoubleSphere& m, const Vec3& unit) {
  const double w1 = m.alpha <= 0.5 ? m.alpha / (1.0 - m.alpha) : (1.0 - m.alpha) / m.alpha;
  const double w2 = (w1 + m.xi) / std::sqrt(2.0 * w1 * m.xi + m.xi * m.xi + 1.0);
  return unit.z() > -w2;
}

std::optional<Vec2> project(const DoubleSphere& m, const Vec3& p) {
  const double d1 = p.norm();
  if (!(d1 > 0.0) || !imagedByDoubleSphere(m, p / d1)) return std::nullopt;
  const double k = m.xi * d1 + p.z();
  const double d2 = std::hypot(p.x(), p.y(), k);
  const double n = m.alpha * d2 + (1.0 - m.alpha) * k;
  if (!(n > 0.0)) return std::nullopt;
  return Vec2(m.fx * p.x() / n + m.cx, m.fy * p.y() / n + m.cy);
}

std::optional<Vec3> direction(const DoubleSphere& m, const Vec2& pixel) {
  const double mx = (pixel.x() - m.cx) / m.fx, my = (pixel.y() - m.cy) / m.fy, r2 = mx * mx + my * my;
  if (m.alpha > 0.5 && r2 >= 1.0 / (2.0 * m.alpha - 1.0)) return std::nullopt;
  const double mz = (1.0 - m.alpha * m.alpha * r2) / (m.alpha * std::sqrt(1.0 - (2.0 * m.alpha - 1.0) * r2) + 1.0 - m.alpha);
  const double discriminant = mz * mz + (1.0 - m.xi * m.xi) * r2;
  if (!(discriminant >= 0.0)) return std::nullopt;
  const double k = (mz * m.xi + std::sqrt(discriminant)) / (mz * mz + r2);
  const Vec3 d = Vec3(k * mx, k * my, k * mz - m.xi).normalized();
  if (!imagedByDoubleSphere(m, d)) return std::nullopt;  // a pixel of the folded part: not imaged
  return d;
}

// --- extended unified -----------------------------------------------------------------------------

// EUCM images a point only where z > −w·ρ (Khomenko et al.): beyond, the projection folds back.
bool imagedByExtendedUnified(const ExtendedUnified& m, const Vec3& p, double rho) {
  const double w = m.alpha > 0.5 ? (1.0 - m.alpha) / m.alpha : m.alpha / (1.0 - m.alpha);
  return p.z() > -w * rho;
}

std::optional<Vec2> project(const ExtendedUnified& m, const Vec3& p) {
  const double rho = std::sqrt(m.beta * (p.x() * p.x() + p.y() * p.y()) + p.z() * p.z());
  if (!(rho > 0.0) || !imagedByExtendedUnified(m, p, rho)) return std::nullopt;
  const double n = m.alpha * rho + (1.0 - m.alpha) * p.z();
  if (!(n > 0.0)) return std::nullopt;
  return Vec2(m.fx * p.x() / n + m.cx, m.fy * p.y() / n + m.cy);
}

std::optional<Vec3> direction(const ExtendedUnified& m, const Vec2& pixel) {
  const double mx = (pixel.x() - m.cx) / m.fx, my = (pixel.y() - m.cy) / m.fy, r2 = mx * mx + my * my;
  const double stretch = (2.0 * m.alpha - 1.0) * m.beta;
  if (m.alpha > 0.5 && r2 >= 1.0 / stretch) return std::nullopt;
  const double mz = (1.0 - m.alpha * m.alpha * m.beta * r2) / (m.alpha * std::sqrt(1.0 - stretch * r2) + 1.0 - m.alpha);
  const Vec3 d = Vec3(mx, my, mz).normalized();
  if (!imagedByExtendedUnified(m, d, std::sqrt(m.beta * (d.x() * d.x() + d.y() * d.y()) + d.z() * d.z()))) return std::nullopt;
  return d;
}

// --- f-θ lenses -----------------------------------------------------------------------------------


std::optional<double> radiusAt(const FThetaLens& m, double theta) {
  switch (m.kind) {
    case FThetaLens::Kind::Equidistant: return m.f * theta;
    case FThetaLens::Kind::Equisolid: return 2.0 * m.f * std::sin(theta / 2.0);
    case FThetaLens::Kind::Polynomial:
      if (theta < m.k[0]) return std::nullopt;
      return solveIncreasing([&](double r) { return polynomialTheta(m, r); }, [&](double r) { return polynomialSlope(m, r); }, theta,
                             m.k[1] > 0.0 ? (theta - m.k[0]) / m.k[1] : 0.0);
  }
  return std::nullopt;
}

std::optional<double> thetaAt(const FThetaLens& m, double r) {
  switch (m.kind) {
    case FThetaLens::Kind::Equidistant: return r / m.f;
    case FThetaLens::Kind::Equisolid:
      if (r > 2.0 * m.f) return std::nullopt;
      return 2.0 * std::asin(r / (2.0 * m.f));
    case FThetaLens::Kind::Polynomial:
      if (!(polynomialSlope(m, r) > 0.0)) return std::nullopt;  // the lens no longer images outward
      return polynomialTheta(m, r);
  }
  return std::nullopt;
}

std::optional<Vec2> project(const FThetaLens& m, const Vec3& p) {
  if (!(p.norm() > 0.0)) return std::nullopt;
  const double rho = std::hypot(p.x(), p.y());
  const double theta = std::atan2(rho, p.z());
  if (theta > m.maxThetaRad) return std::nullopt;
  const std::optional<double> r = radiusAt(m, theta);
  if (!r) return std::nullopt;
  if (rho == 0.0) return p.z() > 0.0 ? Vec2(m.cx, m.cy) : Vec2(m.cx + *r, m.cy);  // behind: as Kannala–Brandt
  return Vec2(m.cx + *r * p.x() / rho, m.cy + *r * p.y() / rho);
}

std::optional<Vec3> direction(const FThetaLens& m, const Vec2& pixel) {
  const double dx = pixel.x() - m.cx, dy = pixel.y() - m.cy;
  const std::optional<double> theta = thetaAt(m, std::hypot(dx, dy));
  if (!theta || *theta < 0.0 || *theta > m.maxThetaRad) return std::nullopt;
  if (dx == 0.0 && dy == 0.0 && *theta != 0.0) return std::nullopt;  // a polynomial with k0 > 0: its centre sees a cone, no one ray
  return rayAt(*theta, dx, dy);
}

// --- equirectangular ------------------------------------------------------------------------------

std::optional<Vec2> project(const Equirectangular& m, const Vec3& p) {
  if (!(p.norm() > 0.0)) return std::nullopt;
  const double lon = std::atan2(p.x(), p.z()), lat = std::atan2(-p.y(), std::hypot(p.x(), p.z()));
  if (lon < m.lonMinRad || lon > m.lonMaxRad || lat < m.latMinRad || lat > m.latMaxRad) return std::nullopt;
  return Vec2((lon - m.lonMinRad) / (m.lonMaxRad - m.lonMinRad) * m.width - 0.5,
              (m.latMaxRad - lat) / (m.latMaxRad - m.latMinRad) * m.height - 0.5);
}

std::optional<Vec3> direction(const Equirectangular& m, const Vec2& pixel) {
  const double u = (pixel.x() + 0.5) / m.width, v = (pixel.y() + 0.5) / m.height;
  if (u < 0.0 || u > 1.0 || v < 0.0 || v > 1.0) return std::nullopt;
  const double lon = m.lonMinRad + u * (m.lonMaxRad - m.lonMinRad), lat = m.latMaxRad - v * (m.latMaxRad - m.latMinRad);
  return Vec3(std::cos(lat) * std::sin(lon), -std::sin(lat), std::cos(lat) * std::cos(lon));
}

// --- pinhole with radial-tangential distortion ----------------------------------------------------

std::optional<Vec2> project(const PinholeRadTan& m, const Vec3& p) {
  if (!(p.z() > 0.0)) return std::nullopt;
  const auto distorted = distortImaged(m.distortion, Vec2(p.x() / p.z(), p.y() / p.z()));
  if (!distorted) return std::nullopt;
  return Vec2(m.fx * distorted->x() + m.cx, m.fy * distorted->y() + m.cy);
}

std::optional<Vec3> direction(const PinholeRadTan& m, const Vec2& pixel) {
  const auto undistorted = undistort(m.distortion, Vec2((pixel.x() - m.cx) / m.fx, (pixel.y() - m.cy) / m.fy));
  if (!undistorted) return std::nullopt;
  return Vec3(undistorted->x(), undistorted->y(), 1.0).normalized();
}

// c' of a pixel coordinate c when the image grows `scale` times (pixel centres at integers).
double scaledCentre(double c, double scale) { return (c + 0.5) * scale - 0.5; }

template <class M>
M scaledFocal(M m, double scale) {
  m.fx *= scale, m.fy *= scale;
  m.cx = scaledCentre(m.cx, scale), m.cy = scaledCentre(m.cy, scale);
  return m;
}

LensModel scaled(const KannalaBrandt& m, double s) { return scaledFocal(m, s); }
LensModel scaled(const DoubleSphere& m, double s) { return scaledFocal(m, s); }
LensModel scaled(const ExtendedUnified& m, double s) { return scaledFocal(m, s); }
LensModel scaled(const PinholeRadTan& m, double s) { return scaledFocal(m, s); }
LensModel scaled(const Equirectangular& m, double s) {
  Equirectangular out = m;
  out.width = static_cast<int>(std::lround(m.width * s)), out.height = static_cast<int>(std::lround(m.height * s));
  return out;
}
LensModel scaled(const FThetaLens& m, double s) {
  FThetaLens out = m;
  out.f *= s;
  out.cx = scaledCentre(m.cx, s), out.cy = scaledCentre(m.cy, s);
  for (size_t i = 1; i < out.k.size(); ++i) out.k[i] /= std::pow(s, static_cast<double>(i));  // θ(r) with r in pixels
  return out;
}

const char* name(const KannalaBrandt&) { return "kannala_brandt"; }
const char* name(const DoubleSphere&) { return "double_sphere"; }
const char* name(const ExtendedUnified&) { return "eucm"; }
const char* name(const Equirectangular&) { return "equirectangular"; }
const char* name(const PinholeRadTan&) { return "pinhole"; }
const char* name(const FThetaLens& m) {
  switch (m.kind) {
    case FThetaLens::Kind::Equidistant: return "fisheye_equidistant";
    case FThetaLens::Kind::Equisolid: return "fisheye_equisolid";
    case FThetaLens::Kind::Polynomial: return "fisheye_polynomial";
  }
  return "fisheye";
}

}  // namespace

double kbSlope(const KannalaBrandt& m, double theta) {
  const double t2 = theta * theta;
  return 1.0 + t2 * (3.0 * m.k[0] + t2 * (5.0 * m.k[1] + t2 * (7.0 * m.k[2] + t2 * 9.0 * m.k[3])));
}

double polynomialTheta(const FThetaLens& m, double r) {
  return m.k[0] + r * (m.k[1] + r * (m.k[2] + r * (m.k[3] + r * m.k[4])));
}

double polynomialSlope(const FThetaLens& m, double r) {
  return m.k[1] + r * (2.0 * m.k[2] + r * (3.0 * m.k[3] + r * 4.0 * m.k[4]));
}

std::string lensModelName(const LensModel& lens) {
  return std::visit([](const auto& m) { return std::string(name(m)); }, lens);
}

LensModel scaledLens(const LensModel& lens, double scale) {
  return std::visit([&](const auto& m) { return scaled(m, scale); }, lens);
}

Vec2 lensCentre(const LensModel& lens) {
  return std::visit([](const auto& m) -> Vec2 {
    if constexpr (std::is_same_v<std::decay_t<decltype(m)>, Equirectangular>) return Vec2((m.width - 1) / 2.0, (m.height - 1) / 2.0);
    else return Vec2(m.cx, m.cy);
  }, lens);
}

bool radiallySymmetric(const LensModel& lens) {
  const auto* pinhole = std::get_if<PinholeRadTan>(&lens);
  return !pinhole || (pinhole->distortion.p1 == 0.0 && pinhole->distortion.p2 == 0.0);
}

std::optional<Vec2> lensProject(const LensModel& lens, const Vec3& pointCamera) {
  return std::visit([&](const auto& m) { return project(m, pointCamera); }, lens);
}

std::optional<Vec3> lensDirection(const LensModel& lens, const Vec2& pixel) {
  return std::visit([&](const auto& m) { return direction(m, pixel); }, lens);
}

}  // namespace omnicam
