#include "mirror.h"

#include <cmath>
#include <string>

#include "errors.h"

namespace omnicam {

HyperbolicMirror::HyperbolicMirror(double k, double c) : k_(k), c_(c) {
  if (!(k > 2.0)) throw InputError("mirror.k: must be > 2 (got " + std::to_string(k) + ")");
  if (!(c > 0.0)) throw InputError("mirror.c: must be > 0 metres (got " + std::to_string(c) + ")");
  a2_ = (c * c / 4.0) * (k - 2.0) / k;
  b2_ = (c * c / 4.0) * (2.0 / k);
}

double HyperbolicMirror::a() const { return std::sqrt(a2_); }
double HyperbolicMirror::eccentricity() const { return (c_ / 2.0) / a(); }
double HyperbolicMirror::xi() const {
  const double e = eccentricity();
  return 2.0 * e / (1.0 + e * e);
}

double HyperbolicMirror::implicit(const Vec3& p) const {
  const double zc = p.z() + c_ / 2.0;
  return zc * zc / a2_ - (p.x() * p.x() + p.y() * p.y()) / b2_ - 1.0;
}

std::optional<Vec3> HyperbolicMirror::firstHit(const Vec3& origin, const Vec3& direction) const {
  // Substitute p = o + t d into the quadric; keep the smallest t > 0 on the upper sheet.
  const Vec3 d = direction.normalized();
  const double oz = origin.z() + c_ / 2.0;
  const double A = d.z() * d.z() / a2_ - (d.x() * d.x() + d.y() * d.y()) / b2_;
  const double B = 2.0 * (oz * d.z() / a2_ - (origin.x() * d.x() + origin.y() * d.y()) / b2_);
  const double C = oz * oz / a2_ - (origin.x() * origin.x() + origin.y() * origin.y()) / b2_ - 1.0;
  double roots[2];
  int count = 0;
  if (std::abs(A) < 1e-300) {
    if (B == 0.0) return std::nullopt;
    roots[count++] = -C / B;
  } else {
    const double disc = B * B - 4.0 * A * C;
    if (disc < 0.0) return std::nullopt;
    // Numerically stable pair of roots.
    const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
    roots[count++] = q / A;
    if (q != 0.0) roots[count++] = C / q;
  }
  std::optional<Vec3> best;
  double bestT = INFINITY;
  for (int i = 0; i < count; ++i) {
    const double t = roots[i];
    if (!(t > 0.0) || t >= bestT) continue;
    const Vec3 p = origin + t * d;
    // The other sheet lies below the centre (z + c/2 ≤ −a), this one above (≥ a): the sign tells
    // them apart where a comparison with a would drop the vertex itself to rounding.
    if (!(p.z() + c_ / 2.0 > 0.0)) continue;
    bestT = t;
    best = p;
  }
  return best;
}

std::optional<Vec3> HyperbolicMirror::pointAlong(const Vec3& direction) const {
  return firstHit(Vec3::Zero(), direction);
}

std::optional<Vec3> HyperbolicMirror::pointFromPinhole(const Vec3& direction) const {
  return firstHit(pinholeInViewpoint(), direction);
}

double HyperbolicMirror::heightAt(double x, double y) const {
  return -c_ / 2.0 + a() * std::sqrt(1.0 + (x * x + y * y) / b2_);
}

Vec2 HyperbolicMirror::slopeAt(double x, double y) const {
  const double s = a() / (b2_ * std::sqrt(1.0 + (x * x + y * y) / b2_));
  return {s * x, s * y};
}

Vec3 HyperbolicMirror::normalAt(const Vec3& p) const {
  // Gradient of the implicit function points away from the sheet's interior (toward F').
  const Vec3 gradient(-2.0 * p.x() / b2_, -2.0 * p.y() / b2_, 2.0 * (p.z() + c_ / 2.0) / a2_);
  return -gradient.normalized();
}

}  // namespace omnicam
