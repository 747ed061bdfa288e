#pragma once
// Baker–Nayar hyperboloidal mirror (thesis Eq. 2.1, docs/conventions.md §1) in the *viewpoint frame*:
// origin at the effective viewpoint F', z up. Surface ((z + c/2)^2)/a^2 − r^2/b^2 = 1 on the
// sheet z + c/2 ≥ a; the physical pinhole F sits at (0, 0, −c).
#include <optional>

#include "geometry.h"

namespace omnicam {

class HyperbolicMirror {
 public:
  // Throws InputError unless k > 2 and c > 0 (metres).
  HyperbolicMirror(double k, double c);

  double k() const { return k_; }
  double c() const { return c_; }
  double a2() const { return a2_; }
  double b2() const { return b2_; }
  double a() const;
  // ε = (c/2)/a and the unified-model parameter ξ = 2ε/(1+ε²).
  double eccentricity() const;
  double xi() const;
  Vec3 pinholeInViewpoint() const { return {0.0, 0.0, -c_}; }

  // The mirror point seen from F' along `direction` (any length), if the ray hits the sheet.
  std::optional<Vec3> pointAlong(const Vec3& direction) const;
  // The mirror point hit by a ray from the physical pinhole F, if any.
  std::optional<Vec3> pointFromPinhole(const Vec3& direction) const;
  // Outward unit normal (pointing away from F', toward the pinhole side) at a surface point.
  Vec3 normalAt(const Vec3& surfacePoint) const;
  // Implicit function value (0 on the surface); used by tests and exporters.
  double implicit(const Vec3& p) const;
  // The first point of the upper sheet hit by the ray origin + t·direction, t > 0.
  std::optional<Vec3> firstHit(const Vec3& origin, const Vec3& direction) const;
  // The upper sheet as a height field: z(x, y) and its gradient (∂z/∂x, ∂z/∂y).
  double heightAt(double x, double y) const;
  Vec2 slopeAt(double x, double y) const;

 private:
  double k_, c_, a2_, b2_;
};

}  // namespace omnicam
