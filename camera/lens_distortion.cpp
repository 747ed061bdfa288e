#include "lens_distortion.h"

#include <cmath>

namespace omnicam {

Vec2 distort(const LensDistortion& l, const Vec2& p) {
  const double x = p.x(), y = p.y(), r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (l.k1 + r2 * (l.k2 + r2 * l.k3));
  return {x * radial + 2.0 * l.p1 * x * y + l.p2 * (r2 + 2.0 * x * x),
          y * radial + l.p1 * (r2 + 2.0 * y * y) + 2.0 * l.p2 * x * y};
}

Eigen::Matrix2d distortJacobian(const LensDistortion& l, const Vec2& p) {
  const double x = p.x(), y = p.y(), r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (l.k1 + r2 * (l.k2 + r2 * l.k3));
  const double dRadialDr2 = l.k1 + r2 * (2.0 * l.k2 + 3.0 * r2 * l.k3);  // ∂radial/∂(r²)
  Eigen::Matrix2d j;
  j(0, 0) = radial + 2.0 * x * x * dRadialDr2 + 2.0 * l.p1 * y + 6.0 * l.p2 * x;
  j(0, 1) = 2.0 * x * y * dRadialDr2 + 2.0 * l.p1 * x + 2.0 * l.p2 * y;
  j(1, 0) = 2.0 * x * y * dRadialDr2 + 2.0 * l.p1 * x + 2.0 * l.p2 * y;
  j(1, 1) = radial + 2.0 * y * y * dRadialDr2 + 6.0 * l.p1 * y + 2.0 * l.p2 * x;
  return j;
}

std::optional<Vec2> undistort(const LensDistortion& lens, const Vec2& distorted) {
  if (lens.none()) return distorted;
  if (!distorted.allFinite()) return std::nullopt;
  Vec2 p = distorted;
  const double scale = 1.0 + distorted.norm();
  for (int iteration = 0; iteration < 100; ++iteration) {
    const Eigen::Matrix2d j = distortJacobian(lens, p);
    if (!(j.determinant() > 0.0)) return std::nullopt;
    const Vec2 step = j.inverse() * (distort(lens, p) - distorted);
    p -= step;
    if (!p.allFinite()) return std::nullopt;
    // Quadratic convergence: once a step is this small the next would be below rounding.
    if (step.norm() <= 1e-15 * scale) break;
  }
  if (!((distort(lens, p) - distorted).norm() <= 1e-14 * scale)) return std::nullopt;
  if (!(distortJacobian(lens, p).determinant() > 0.0)) return std::nullopt;
  return p;
}

std::optional<Vec2> distortImaged(const LensDistortion& lens, const Vec2& undistorted) {
  const Vec2 distorted = distort(lens, undistorted);
  if (lens.none()) return distorted;
  const auto back = undistort(lens, distorted);
  if (!back || (*back - undistorted).norm() > 1e-9 * (1.0 + undistorted.norm())) return std::nullopt;
  return distorted;
}

}  // namespace omnicam
