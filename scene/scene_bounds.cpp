#include "scene_bounds.h"

#include <algorithm>
#include <cmath>

namespace omnicam {

namespace {

struct Extent {
  double xMin = INFINITY, yMin = INFINITY, xMax = -INFINITY, yMax = -INFINITY;
  void add(double x, double y) {
    xMin = std::min(xMin, x), yMin = std::min(yMin, y), xMax = std::max(xMax, x), yMax = std::max(yMax, y);
  }
  void add(const Vec3& p) { add(p.x(), p.y()); }
  // A disc of `radius` about `center` with unit normal `n`: along a floor axis e, its rim reaches
  // radius·sqrt(1 − (n·e)²) from the centre.
  void addDisc(const Vec3& center, const Vec3& n, double radius) {
    const double dx = radius * std::sqrt(std::max(0.0, 1.0 - n.x() * n.x()));
    const double dy = radius * std::sqrt(std::max(0.0, 1.0 - n.y() * n.y()));
    add(center.x() - dx, center.y() - dy);
    add(center.x() + dx, center.y() + dy);
  }

  void operator()(const Box& b) {
    const double c = std::cos(b.yawDeg * M_PI / 180.0), s = std::sin(b.yawDeg * M_PI / 180.0);
    for (const double u : {-0.5, 0.5})
      for (const double v : {-0.5, 0.5})
        add(b.center.x() + c * u * b.size.x() - s * v * b.size.y(), b.center.y() + s * u * b.size.x() + c * v * b.size.y());
  }
  void operator()(const Cylinder& c) {
    const Vec3 axis = (c.top - c.base).normalized();
    addDisc(c.base, axis, c.radius);
    addDisc(c.top, axis, c.radius);
  }
  void operator()(const Sphere& s) {
    add(s.center.x() - s.radius, s.center.y() - s.radius);
    add(s.center.x() + s.radius, s.center.y() + s.radius);
  }
  void operator()(const Quad& q) {
    add(q.origin);
    add(q.origin + q.edgeU);
    add(q.origin + q.edgeV);
    add(q.origin + q.edgeU + q.edgeV);
  }
  void operator()(const Disc& d) { addDisc(d.center, d.normal.normalized(), d.radius); }
  void operator()(const Mesh& m) {
    for (const Vec3& v : m.vertices) add(v);
  }
};

}  // namespace

std::optional<FloorRect> sceneFloorExtent(const Scene& scene) {
  Extent extent;
  for (const SceneObject& object : scene.objects) std::visit(extent, object.shape);
  if (!(extent.xMin <= extent.xMax)) return std::nullopt;
  return FloorRect{extent.xMin, extent.yMin, extent.xMax, extent.yMax};
}

}  // namespace omnicam
