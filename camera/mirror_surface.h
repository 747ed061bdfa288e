#pragma once
// The mirror as a surface the physical camera traces (physical_camera.h): one interface, one
// implementation per shape (rig.h's MirrorShape). Everything is in the viewpoint frame (origin
// at the shape's design point, z up); every mirror is a surface of revolution about the z axis,
// convex toward the camera below it, a height field z(x, y) over its disc, cut by the rim plane
// z = rimZ (the mirror is where z ≤ rimZ).
//
//   hyperboloid  (z + c/2)²/a² − r²/b² = 1, upper sheet (mirror.h); design point F'
//   paraboloid   z = (r² − h²)/(2h); design point its focus
//   sphere       |p| = R, lower cap up to polar angle `cap` from its lowest point; design point its centre
//   cone         r = z·tan α, z ≥ 0, apex down; design point its apex
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "geometry.h"
#include "rig.h"

namespace omnicam {

class MirrorSurface {
 public:
  virtual ~MirrorSurface() = default;

  // The first point of the surface (whole, rim ignored) hit by origin + t·direction, t > 0.
  virtual std::optional<Vec3> firstHit(const Vec3& origin, const Vec3& direction) const = 0;
  // Unit normal at a surface point (either orientation: reflection does not care).
  virtual Vec3 normalAt(const Vec3& surfacePoint) const = 0;
  // 0 on the surface; for tests and exporters.
  virtual double implicit(const Vec3& p) const = 0;
  // The surface as a height field and its gradient (∂z/∂x, ∂z/∂y).
  virtual double heightAt(double x, double y) const = 0;
  virtual Vec2 slopeAt(double x, double y) const = 0;
  // Where the world → pixel solver starts for a point p seen from a pinhole at `pinhole`: the
  // (x, y) of a mirror point near the reflection point, then fallbacks tried in order if the
  // solver does not reach the physical root from it.
  virtual std::vector<Vec2> projectionStarts(const Vec3& p, const Vec3& pinhole) const = 0;
  // The reflection point of p seen from a perspective pinhole on the axis at height pinholeZ, in
  // closed form where the shape has one (the cone: in p's meridian plane its generators are
  // straight lines, so the camera's mirror image across one, joined to p, crosses it there).
  // nullopt: no closed form for this shape; an empty inner value: no mirror point reflects p.
  virtual std::optional<std::optional<Vec3>> axialReflection(const Vec3& /*p*/, double /*pinholeZ*/) const {
    return std::nullopt;
  }
  // Whether the surface has an apex on its axis, a point without a tangent plane (the cone's).
  virtual bool hasApex() const { return false; }
  // The shape and its parameters, for sidecars.
  virtual nlohmann::json toJson() const = 0;

  double rimZ() const { return rimZ_; }
  double rimRadius() const { return rimRadius_; }
  bool insideRim(const Vec3& surfacePoint) const { return surfacePoint.z() <= rimZ_; }

 protected:
  MirrorSurface(double rimZ, double rimRadius) : rimZ_(rimZ), rimRadius_(rimRadius) {}

 private:
  double rimZ_, rimRadius_;
};

// The mirror of a rig. Throws InputError (naming the mirror's fields) for a shape whose
// parameters describe no mirror.
std::shared_ptr<const MirrorSurface> mirrorSurfaceOf(const MirrorRig& rig);

}  // namespace omnicam
