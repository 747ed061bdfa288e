#include "mirror_mesh.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <variant>

#include "errors.h"
#include "overloaded.h"

namespace omnicam {

namespace {

// A mirror of revolution as the mesh builder sees it: its profile z(r) from the axis to the rim,
// the largest curvature of that profile, and the surface normal.
struct Profile {
  std::function<double(double)> z;
  double maxCurvature;
  double rimRadius, rimZ;
  std::function<Vec3(const Vec3&)> normal;
};

// Rings of constant height evenly spaced in arc length, sectors set by the rim circle; the chord
// sagitta of every edge below half the bound in each direction.
MirrorMesh buildRevolutionMesh(const Profile& profile, double maxDeviation) {
  const double rimRadius = profile.rimRadius;
  // The profile's sagitta over a step L is L²κ/8; a circle's is bounded by its radius, so
  // sectors are set by the rim circle. Each direction gets half of the bound.
  const double half = 0.5 * maxDeviation;
  const double maxProfileStep = std::sqrt(8.0 * half / profile.maxCurvature);
  // Profile arc length, measured numerically.
  double arc = 0.0;
  const int fine = 20000;
  for (int k = 0; k < fine; ++k) {
    const double r0 = rimRadius * k / fine, r1 = rimRadius * (k + 1) / fine;
    arc += std::hypot(r1 - r0, profile.z(r1) - profile.z(r0));
  }
  MirrorMesh out;
  out.requestedBound = maxDeviation;
  out.rings = std::max(2, static_cast<int>(std::ceil(arc / maxProfileStep)));
  out.sectors = std::max(8, static_cast<int>(std::ceil(kPi / std::acos(1.0 - half / rimRadius))));
  std::vector<double> ringRadius{0.0};
  {
    double s = 0.0, target = arc / out.rings;
    int next = 1;
    for (int k = 0; k < fine && next < out.rings; ++k) {
      const double r0 = rimRadius * k / fine, r1 = rimRadius * (k + 1) / fine;
      const double ds = std::hypot(r1 - r0, profile.z(r1) - profile.z(r0));
      while (next < out.rings && s + ds >= target * next) {
        ringRadius.push_back(r0 + (r1 - r0) * (target * next - s) / ds);
        ++next;
      }
      s += ds;
    }
    ringRadius.push_back(rimRadius);
  }
  TriangleMesh& mesh = out.mesh;
  mesh.vertices.push_back({0.0, 0.0, profile.z(0.0)});
  mesh.uvs.push_back({0.5, 0.5});
  for (size_t ring = 1; ring < ringRadius.size(); ++ring) {
    const double r = ringRadius[ring], z = ring + 1 == ringRadius.size() ? profile.rimZ : profile.z(r);
    for (int s = 0; s < out.sectors; ++s) {
      const double phi = 2.0 * kPi * s / out.sectors;
      mesh.vertices.push_back({r * std::cos(phi), r * std::sin(phi), z});
      mesh.uvs.push_back({0.5 + 0.5 * std::cos(phi) * r / rimRadius, 0.5 + 0.5 * std::sin(phi) * r / rimRadius});
    }
  }
  const int n = out.sectors;
  auto index = [n](int ring, int s) { return 1 + (ring - 1) * n + ((s % n) + n) % n; };
  // Faces are wound counter-clockwise seen from below (the camera side).
  for (int s = 0; s < n; ++s) mesh.triangles.emplace_back(0, index(1, s + 1), index(1, s));
  for (size_t ring = 1; ring + 1 < ringRadius.size(); ++ring)
    for (int s = 0; s < n; ++s) {
      const int r = static_cast<int>(ring);
      mesh.triangles.emplace_back(index(r, s), index(r, s + 1), index(r + 1, s + 1));
      mesh.triangles.emplace_back(index(r, s), index(r + 1, s + 1), index(r + 1, s));
    }
  for (const Vec3& v : mesh.vertices) out.normals.push_back(profile.normal(v));
  return out;
}

InputError uncertifiedShape(const MirrorRig& rig) {
  return InputError(std::string("rig.mirror.shape: a mesh is certified for the hyperboloid and the sphere only (got ") +
                    mirrorShapeName(rig.shape) + ")");
}

}  // namespace

MirrorMesh buildMirrorMesh(const MirrorRig& rig, double maxDeviation) {
  // The profile is most curved at the vertex: the hyperboloid's z(r) = a·sqrt(1 + r²/b²) − c/2
  // there by a/b², the sphere everywhere by 1/R.
  const double maxCurvature = std::visit(
      Overloaded{[](const HyperboloidMirror& h) {
                   const HyperbolicMirror m = h.mirror();
                   return m.a() / m.b2();
                 },
                 [](const SphereMirror& s) { return 1.0 / s.radius; },
                 // Not in kCertifiedMeshShapes: no mesh bound is proven for them.
                 [&rig](const ParaboloidMirror&) -> double { throw uncertifiedShape(rig); },
                 [&rig](const ConeMirror&) -> double { throw uncertifiedShape(rig); }},
      rig.shape);
  const std::shared_ptr<const MirrorSurface> surface = mirrorSurfaceOf(rig);
  const MirrorSurface& s = *surface;
  const Profile profile{[&s](double r) { return s.heightAt(r, 0.0); }, maxCurvature, s.rimRadius(), s.rimZ(),
                        [&s](const Vec3& p) { return s.normalAt(p); }};
  return buildRevolutionMesh(profile, maxDeviation);
}

double mirrorSurfaceDistance(const HyperbolicMirror& m, const Vec3& p) {
  // In the (r, z) half-plane the sheet is the curve (r(t), z(t)) = (b sinh t, a cosh t − c/2),
  // t ≥ 0. Minimise |(r(t), z(t)) − (ρ, ζ)|² by Newton's method on its derivative.
  const double rho = std::hypot(p.x(), p.y()), zeta = p.z();
  const double a = m.a(), b = std::sqrt(m.b2()), c2 = m.c() / 2.0;
  double t = std::asinh(rho / b);  // start at the point with the same radius
  for (int i = 0; i < 50; ++i) {
    const double r = b * std::sinh(t), z = a * std::cosh(t) - c2;
    const double dr = b * std::cosh(t), dz = a * std::sinh(t);
    const double g = (r - rho) * dr + (z - zeta) * dz;              // ½ d/dt of the squared distance
    const double h = dr * dr + dz * dz + (r - rho) * r + (z - zeta) * (z + c2);  // ½ d²/dt²
    const double step = g / h;
    t = std::max(0.0, t - step);
    if (std::abs(step) < 1e-15) break;
  }
  return std::hypot(b * std::sinh(t) - rho, a * std::cosh(t) - c2 - zeta);
}

}  // namespace omnicam
