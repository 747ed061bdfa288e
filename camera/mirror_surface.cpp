#include "mirror_surface.h"

#include <algorithm>
#include <cmath>

#include "errors.h"
#include "mirror.h"

namespace omnicam {

namespace {

// Real roots of A t² + B t + C = 0 in ascending order (the numerically stable pair), or the
// linear one when A vanishes; how many in `count`.
int quadraticRoots(double a, double b, double c, double roots[2]) {
  if (std::abs(a) < 1e-300) {
    if (b == 0.0) return 0;
    roots[0] = -c / b;
    return 1;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return 0;
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  roots[0] = q / a;
  roots[1] = q != 0.0 ? c / q : roots[0];
  if (roots[0] > roots[1]) std::swap(roots[0], roots[1]);
  return 2;
}

// The smallest t > 0 of the quadric along the ray whose point `valid` accepts.
template <typename Valid>
std::optional<Vec3> firstValidRoot(double a, double b, double c, const Vec3& o, const Vec3& d, Valid valid) {
  double roots[2];
  const int count = quadraticRoots(a, b, c, roots);
  for (int i = 0; i < count; ++i) {
    if (!(roots[i] > 1e-12)) continue;
    const Vec3 p = o + roots[i] * d;
    if (valid(p)) return p;
  }
  return std::nullopt;
}

class HyperboloidSurface final : public MirrorSurface {
 public:
  explicit HyperboloidSurface(const MirrorRig& rig)
      : MirrorSurface(rig.idealCamera().rimPoint().z(), rig.idealCamera().rimPoint().head<2>().norm()),
        mirror_(rig.hyperboloid().mirror()) {}
  std::optional<Vec3> firstHit(const Vec3& o, const Vec3& d) const override { return mirror_.firstHit(o, d); }
  Vec3 normalAt(const Vec3& p) const override { return mirror_.normalAt(p); }
  double implicit(const Vec3& p) const override { return mirror_.implicit(p); }
  double heightAt(double x, double y) const override { return mirror_.heightAt(x, y); }
  Vec2 slopeAt(double x, double y) const override { return mirror_.slopeAt(x, y); }
  // The central model's mirror point: exact for the ideal pinhole, close for a moved one.
  std::vector<Vec2> projectionStarts(const Vec3& p, const Vec3&) const override {
    const auto m = mirror_.pointAlong(p);
    return {m ? Vec2(m->head<2>()) : Vec2::Zero()};
  }
  nlohmann::json toJson() const override {
    return {{"shape", "hyperboloid"}, {"k", mirror_.k()}, {"c", mirror_.c()}, {"rim_z_m", rimZ()}};
  }

 private:
  HyperbolicMirror mirror_;
};

class ParaboloidSurface final : public MirrorSurface {
 public:
  // The rim where the focus sees `rimElevationDeg`: ρ = h / (1 − sin e) from the focus.
  ParaboloidSurface(double h, double rimElevationDeg)
      : MirrorSurface(rimDistance(h, rimElevationDeg) * std::sin(radians(rimElevationDeg)),
                      rimDistance(h, rimElevationDeg) * std::cos(radians(rimElevationDeg))),
        h_(h) {}
  static double rimDistance(double h, double elevationDeg) { return h / (1.0 - std::sin(radians(elevationDeg))); }
  std::optional<Vec3> firstHit(const Vec3& o, const Vec3& direction) const override {
    const Vec3 d = direction.normalized();
    const double a = d.x() * d.x() + d.y() * d.y();
    const double b = 2.0 * (o.x() * d.x() + o.y() * d.y()) - 2.0 * h_ * d.z();
    const double c = o.x() * o.x() + o.y() * o.y() - 2.0 * h_ * o.z() - h_ * h_;
    return firstValidRoot(a, b, c, o, d, [](const Vec3&) { return true; });
  }
  Vec3 normalAt(const Vec3& p) const override { return Vec3(p.x(), p.y(), -h_).normalized(); }
  double implicit(const Vec3& p) const override {
    return (p.x() * p.x() + p.y() * p.y() - 2.0 * h_ * p.z() - h_ * h_) / (h_ * h_);
  }
  double heightAt(double x, double y) const override { return (x * x + y * y - h_ * h_) / (2.0 * h_); }
  Vec2 slopeAt(double x, double y) const override { return {x / h_, y / h_}; }
  // Seen from the focus: the orthographic build's exact point, close for the others.
  std::vector<Vec2> projectionStarts(const Vec3& p, const Vec3&) const override {
    const auto m = firstHit(Vec3::Zero(), p);
    return {m ? Vec2(m->head<2>()) : Vec2::Zero()};
  }
  nlohmann::json toJson() const override {
    return {{"shape", "paraboloid"}, {"h", h_}, {"rim_z_m", rimZ()}, {"rim_radius_m", rimRadius()}};
  }

 private:
  double h_;
};

class SphereSurface final : public MirrorSurface {
 public:
  SphereSurface(double radius, double capAngleDeg)
      : MirrorSurface(-radius * std::cos(radians(capAngleDeg)), radius * std::sin(radians(capAngleDeg))), r_(radius) {}
  std::optional<Vec3> firstHit(const Vec3& o, const Vec3& direction) const override {
    const Vec3 d = direction.normalized();
    return firstValidRoot(1.0, 2.0 * o.dot(d), o.squaredNorm() - r_ * r_, o, d, [](const Vec3&) { return true; });
  }
  Vec3 normalAt(const Vec3& p) const override { return p.normalized(); }
  double implicit(const Vec3& p) const override { return (p.squaredNorm() - r_ * r_) / (r_ * r_); }
  double heightAt(double x, double y) const override { return -std::sqrt(std::max(0.0, r_ * r_ - x * x - y * y)); }
  Vec2 slopeAt(double x, double y) const override {
    const double z = std::sqrt(std::max(1e-300, r_ * r_ - x * x - y * y));
    return {x / z, y / z};
  }
  // For a distant pinhole and point the normal halves the angle between them.
  std::vector<Vec2> projectionStarts(const Vec3& p, const Vec3& pinhole) const override {
    const Vec3 n = (p.normalized() + pinhole.normalized()).normalized();
    Vec2 xy = r_ * n.head<2>();
    if (n.z() > 0.0 || xy.norm() > rimRadius()) xy *= 0.9 * rimRadius() / std::max(xy.norm(), 1e-300);
    return {xy};
  }
  nlohmann::json toJson() const override {
    return {{"shape", "sphere"}, {"radius", r_}, {"rim_z_m", rimZ()}, {"rim_radius_m", rimRadius()}};
  }

 private:
  double r_;
};

class ConeSurface final : public MirrorSurface {
 public:
  ConeSurface(double halfAngleDeg, double rimRadius)
      : MirrorSurface(rimRadius / std::tan(radians(halfAngleDeg)), rimRadius), tan_(std::tan(radians(halfAngleDeg))) {}
  std::optional<Vec3> firstHit(const Vec3& o, const Vec3& direction) const override {
    const Vec3 d = direction.normalized();
    const double t2 = tan_ * tan_;
    const double a = d.x() * d.x() + d.y() * d.y() - t2 * d.z() * d.z();
    const double b = 2.0 * (o.x() * d.x() + o.y() * d.y() - t2 * o.z() * d.z());
    const double c = o.x() * o.x() + o.y() * o.y() - t2 * o.z() * o.z();
    return firstValidRoot(a, b, c, o, d, [](const Vec3& p) { return p.z() >= 0.0; });  // the upper nappe
  }
  Vec3 normalAt(const Vec3& p) const override {
    const double r = p.head<2>().norm();
    if (!(r > 0.0)) return Vec3::UnitZ();  // the apex: a single point, no tangent plane
    return Vec3(p.x() / r, p.y() / r, -tan_).normalized();
  }
  double implicit(const Vec3& p) const override {
    return (p.x() * p.x() + p.y() * p.y() - tan_ * tan_ * p.z() * p.z()) / (rimRadius() * rimRadius());
  }
  double heightAt(double x, double y) const override { return std::hypot(x, y) / tan_; }
  Vec2 slopeAt(double x, double y) const override {
    const double r = std::hypot(x, y);
    if (!(r > 0.0)) return Vec2::Zero();
    return {x / (r * tan_), y / (r * tan_)};
  }
  // The closed form for a pinhole on the axis at the same height: exact for a pinhole on the axis,
  // close for one moved off it. Where it finds nothing, the convex search decides.
  std::vector<Vec2> projectionStarts(const Vec3& p, const Vec3& pinhole) const override {
    const auto m = *axialReflection(p, pinhole.z());
    if (!m) return {};
    return {Vec2(m->head<2>())};
  }
  std::optional<std::optional<Vec3>> axialReflection(const Vec3& p, double pinholeZ) const override {
    const double rhoP = p.head<2>().norm();
    if (!(rhoP > 0.0) || !(pinholeZ < 0.0)) return std::optional<Vec3>();  // on the axis: only the apex, no tangent plane
    const Vec2 towardP = p.head<2>() / rhoP;
    const double sinA = std::sin(std::atan(tan_)), cosA = std::cos(std::atan(tan_));
    const Vec2 camera(0.0, pinholeZ), point(rhoP, p.z());  // (ρ, z) in p's meridian plane
    // Each generator: its direction g and outer normal n (away from the body). Both the camera and
    // the point must lie on its outer side; the convex body then has one reflection point at most.
    for (const double side : {1.0, -1.0}) {
      const Vec2 g(side * sinA, cosA), n(side * cosA, -sinA);
      if (!(n.dot(camera) > 0.0 && n.dot(point) > 0.0)) continue;
      const Vec2 image = 2.0 * camera.dot(g) * g - camera;  // the camera mirrored across the generator
      const Vec2 d = point - image;
      // image + t·d on the generator's line: its component along n vanishes.
      const double across = n.dot(d);
      if (!(std::abs(across) > 0.0)) continue;
      const double t = -n.dot(image) / across;
      if (!(t > 0.0 && t < 1.0)) continue;
      const Vec2 m = image + t * d;
      const double along = m.dot(g);
      if (!(along > 0.0) || m.y() > rimZ()) return std::optional<Vec3>();  // the apex, or past the rim
      const Vec2 xy = m.x() * towardP;  // m.x(): the signed distance from the axis toward p
      return std::optional<Vec3>(Vec3(xy.x(), xy.y(), m.y()));
    }
    return std::optional<Vec3>();
  }
  bool hasApex() const override { return true; }
  nlohmann::json toJson() const override {
    return {{"shape", "cone"}, {"half_angle_deg", degrees(std::atan(tan_))}, {"rim_z_m", rimZ()}, {"rim_radius_m", rimRadius()}};
  }

 private:
  double tan_;
};

}  // namespace

std::shared_ptr<const MirrorSurface> mirrorSurfaceOf(const MirrorRig& rig) {
  return std::visit(
      Overloaded{[&](const HyperboloidMirror&) -> std::shared_ptr<const MirrorSurface> { return std::make_shared<HyperboloidSurface>(rig); },
                 [](const ParaboloidMirror& p) -> std::shared_ptr<const MirrorSurface> {
                   return std::make_shared<ParaboloidSurface>(p.h, p.rimElevationDeg);
                 },
                 [](const SphereMirror& s) -> std::shared_ptr<const MirrorSurface> {
                   return std::make_shared<SphereSurface>(s.radius, s.capAngleDeg);
                 },
                 [](const ConeMirror& c) -> std::shared_ptr<const MirrorSurface> {
                   return std::make_shared<ConeSurface>(c.halfAngleDeg, c.rimRadius);
                 }},
      rig.shape);
}

}  // namespace omnicam
