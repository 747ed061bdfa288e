#include "analytic_shapes.h"

#include <cmath>

namespace omnicam {

namespace {

// Both roots of A t² + B t + C = 0 in ascending order (numerically stable); false if none.
bool solveQuadratic(double A, double B, double C, double& t0, double& t1) {
  const double disc = B * B - 4.0 * A * C;
  if (disc < 0.0 || A == 0.0) return false;
  const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
  t0 = q / A;
  t1 = q != 0.0 ? C / q : t0;
  if (t0 > t1) std::swap(t0, t1);
  return true;
}

double azimuthFraction(const Vec3& radial, const Vec3& e1, const Vec3& e2) {
  double phi = std::atan2(radial.dot(e2), radial.dot(e1));
  if (phi < 0.0) phi += 2.0 * kPi;
  return phi / (2.0 * kPi);
}

}  // namespace

std::optional<ShapeHit> intersect(const Sphere& s, const Vec3& o, const Vec3& d, double tNear, double tFar) {
  const Vec3 oc = o - s.center;
  double t0, t1;
  if (!solveQuadratic(d.dot(d), 2.0 * oc.dot(d), oc.dot(oc) - s.radius * s.radius, t0, t1))
    return std::nullopt;
  for (double t : {t0, t1}) {
    if (t <= tNear || t >= tFar) continue;
    const Vec3 n = (oc + t * d) / s.radius;
    double u = std::atan2(n.y(), n.x()) / (2.0 * kPi);
    if (u < 0.0) u += 1.0;
    const double v = std::acos(std::clamp(-n.z(), -1.0, 1.0)) / kPi;  // 0 at the bottom pole
    return ShapeHit{t, n.normalized(), {u, v}};
  }
  return std::nullopt;
}

std::optional<ShapeHit> intersect(const Cylinder& c, const Vec3& o, const Vec3& d, double tNear, double tFar) {
  const Vec3 axisVec = c.top - c.base;
  const double height = axisVec.norm();
  const Vec3 a = axisVec / height;
  const auto [e1, e2] = perpendicularFrame(a);
  const Vec3 ob = o - c.base;
  const double oa = ob.dot(a), da = d.dot(a);
  const Vec3 op = ob - oa * a, dp = d - da * a;
  std::optional<ShapeHit> best;
  double t0, t1;
  if (solveQuadratic(dp.dot(dp), 2.0 * op.dot(dp), op.dot(op) - c.radius * c.radius, t0, t1)) {
    for (double t : {t0, t1}) {
      if (t <= tNear || t >= tFar) continue;
      const double h = oa + t * da;
      if (h < 0.0 || h > height) continue;
      const Vec3 radial = op + t * dp;
      best = ShapeHit{t, radial.normalized(), {azimuthFraction(radial, e1, e2), h / height}};
      break;
    }
  }
  if (c.caps && da != 0.0) {
    for (double capHeight : {0.0, height}) {
      const double t = (capHeight - oa) / da;
      if (t <= tNear || t >= tFar || (best && t >= best->t)) continue;
      const Vec3 radial = op + t * dp;
      if (radial.squaredNorm() > c.radius * c.radius) continue;
      best = ShapeHit{t, capHeight == 0.0 ? Vec3(-a) : a,
                      {azimuthFraction(radial, e1, e2), capHeight == 0.0 ? 0.0 : 1.0}};
    }
  }
  return best;
}

std::optional<ShapeHit> intersect(const Disc& disc, const Vec3& o, const Vec3& d, double tNear, double tFar) {
  const double dn = d.dot(disc.normal);
  if (dn == 0.0) return std::nullopt;
  const double t = (disc.center - o).dot(disc.normal) / dn;
  if (t <= tNear || t >= tFar) return std::nullopt;
  const Vec3 radial = o + t * d - disc.center;
  const double r2 = radial.squaredNorm();
  if (r2 > disc.radius * disc.radius || r2 < disc.innerRadius * disc.innerRadius) return std::nullopt;
  const auto [e1, e2] = perpendicularFrame(disc.normal);
  // Planar UV: the disc's bounding square mapped to [0, 1]².
  const Eigen::Vector2d uv(0.5 + radial.dot(e1) / (2.0 * disc.radius), 0.5 + radial.dot(e2) / (2.0 * disc.radius));
  return ShapeHit{t, disc.normal, uv};
}

std::pair<Vec3, Vec3> bounds(const Sphere& s) {
  return {s.center - Vec3::Constant(s.radius), s.center + Vec3::Constant(s.radius)};
}

std::pair<Vec3, Vec3> bounds(const Cylinder& c) {
  const Vec3 r = Vec3::Constant(c.radius);
  return {c.base.cwiseMin(c.top) - r, c.base.cwiseMax(c.top) + r};
}

std::pair<Vec3, Vec3> bounds(const Disc& d) {
  const Vec3 r = Vec3::Constant(d.radius);
  return {d.center - r, d.center + r};
}

}  // namespace omnicam
