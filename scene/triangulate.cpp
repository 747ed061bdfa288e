#include "triangulate.h"

#include <algorithm>
#include <cmath>

namespace omnicam {

namespace {
void appendQuad(TriangleMesh& m, const Vec3& origin, const Vec3& edgeU, const Vec3& edgeV) {
  const int base = static_cast<int>(m.vertices.size());
  m.vertices.insert(m.vertices.end(), {origin, origin + edgeU, origin + edgeU + edgeV, origin + edgeV});
  m.uvs.insert(m.uvs.end(), {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}});
  m.triangles.emplace_back(base, base + 1, base + 2);
  m.triangles.emplace_back(base, base + 2, base + 3);
}
}  // namespace

TriangleMesh triangulate(const Quad& quad) {
  TriangleMesh m;
  appendQuad(m, quad.origin, quad.edgeU, quad.edgeV);
  return m;
}

TriangleMesh triangulate(const Box& box) {
  // Faces as quads in the box frame, each with UV (0,0)–(1,1) seen from outside.
  const Eigen::AngleAxisd yaw(radians(box.yawDeg), Vec3::UnitZ());
  const Vec3 h = 0.5 * box.size;
  const Vec3 x = yaw * Vec3(box.size.x(), 0, 0), y = yaw * Vec3(0, box.size.y(), 0),
             z = yaw * Vec3(0, 0, box.size.z());
  const Vec3 corner = box.center + yaw * Vec3(-h.x(), -h.y(), -h.z());  // (−,−,−)
  TriangleMesh m;
  appendQuad(m, corner, y, x);                  // bottom (−z), outward normal −z
  appendQuad(m, corner + z, x, y);              // top (+z)
  appendQuad(m, corner, x, z);                  // −y face
  appendQuad(m, corner + y + x, -x, z);         // +y face
  appendQuad(m, corner + y, -y, z);             // −x face
  appendQuad(m, corner + x, y, z);              // +x face
  return m;
}

TriangleMesh triangulate(const Mesh& mesh) {
  TriangleMesh m;
  m.vertices = mesh.vertices;
  m.triangles = mesh.triangles;
  m.uvs = mesh.uvs.empty() ? std::vector<Eigen::Vector2d>(mesh.vertices.size(), Eigen::Vector2d::Zero())
                           : mesh.uvs;
  return m;
}

std::optional<TriangleMesh> triangulatePlanar(const Shape& shape) {
  return std::visit(
      [](const auto& s) -> std::optional<TriangleMesh> {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, Box> || std::is_same_v<T, Quad> || std::is_same_v<T, Mesh>)
          return triangulate(s);
        else
          return std::nullopt;
      },
      shape);
}

// At most 1024 segments: the tolerance holds up to radii of ~100 m (0.5 mm) and ~40 m (0.2 mm);
// beyond, a kilometre-sized sphere would otherwise become 10⁸ triangles.
int segmentsForCircle(double radius, double chordTolerance) {
  if (chordTolerance >= radius) return 8;
  const double segments = std::ceil(kPi / std::acos(1.0 - chordTolerance / radius));
  return std::clamp(static_cast<int>(std::min(segments, 1024.0)), 8, 1024);
}

namespace {

TriangleMesh tessellateSphere(const Sphere& s, double tol) {
  const int lon = segmentsForCircle(s.radius, tol), lat = std::max(4, lon / 2);
  TriangleMesh m;
  for (int j = 0; j <= lat; ++j) {
    const double polar = kPi * j / lat;  // 0 at the bottom pole, as the analytic v
    for (int i = 0; i <= lon; ++i) {
      const double phi = 2.0 * kPi * i / lon;
      const Vec3 n(std::sin(polar) * std::cos(phi), std::sin(polar) * std::sin(phi), -std::cos(polar));
      m.vertices.push_back(s.center + s.radius * n);
      m.uvs.emplace_back(static_cast<double>(i) / lon, static_cast<double>(j) / lat);
    }
  }
  for (int j = 0; j < lat; ++j)
    for (int i = 0; i < lon; ++i) {
      const int a = j * (lon + 1) + i, b = a + 1, c = a + lon + 1, d = c + 1;
      if (j > 0) m.triangles.emplace_back(a, c, b);
      if (j + 1 < lat) m.triangles.emplace_back(b, c, d);
    }
  return m;
}

void appendRing(TriangleMesh& m, const Vec3& centre, const Vec3& e1, const Vec3& e2, double inner, double outer,
                int n, double v, bool flip) {
  const int base = static_cast<int>(m.vertices.size());
  for (int i = 0; i <= n; ++i) {
    const double phi = 2.0 * kPi * i / n;
    const Vec3 dir = std::cos(phi) * e1 + std::sin(phi) * e2;
    m.vertices.push_back(centre + inner * dir);
    m.vertices.push_back(centre + outer * dir);
    m.uvs.emplace_back(static_cast<double>(i) / n, v);
    m.uvs.emplace_back(static_cast<double>(i) / n, v);
  }
  for (int i = 0; i < n; ++i) {
    const int a = base + 2 * i, b = a + 1, c = a + 2, d = a + 3;
    if (flip) {
      m.triangles.emplace_back(a, c, b), m.triangles.emplace_back(b, c, d);
    } else {
      m.triangles.emplace_back(a, b, c), m.triangles.emplace_back(b, d, c);
    }
  }
}

TriangleMesh tessellateCylinder(const Cylinder& c, double tol) {
  const Vec3 axis = c.top - c.base;
  const auto [e1, e2] = perpendicularFrame(axis);
  const int n = segmentsForCircle(c.radius, tol);
  TriangleMesh m;
  for (int i = 0; i <= n; ++i) {
    const double phi = 2.0 * kPi * i / n;
    const Vec3 dir = std::cos(phi) * e1 + std::sin(phi) * e2;
    m.vertices.push_back(c.base + c.radius * dir);
    m.vertices.push_back(c.top + c.radius * dir);
    m.uvs.emplace_back(static_cast<double>(i) / n, 0.0);
    m.uvs.emplace_back(static_cast<double>(i) / n, 1.0);
  }
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i, b = a + 1, cc = a + 2, d = a + 3;
    m.triangles.emplace_back(a, cc, b), m.triangles.emplace_back(b, cc, d);
  }
  if (c.caps) {
    appendRing(m, c.base, e1, e2, 0.0, c.radius, n, 0.0, true);
    appendRing(m, c.top, e1, e2, 0.0, c.radius, n, 1.0, false);
  }
  return m;
}

TriangleMesh tessellateDisc(const Disc& d, double tol) {
  const auto [e1, e2] = perpendicularFrame(d.normal);
  TriangleMesh m;
  appendRing(m, d.center, e1, e2, d.innerRadius, d.radius, segmentsForCircle(d.radius, tol), 0.0, false);
  // Planar UV as the analytic disc: the bounding square mapped to [0, 1]².
  for (size_t k = 0; k < m.vertices.size(); ++k) {
    const Vec3 r = m.vertices[k] - d.center;
    m.uvs[k] = {0.5 + r.dot(e1) / (2.0 * d.radius), 0.5 + r.dot(e2) / (2.0 * d.radius)};
  }
  return m;
}

}  // namespace

TriangleMesh tessellate(const Shape& shape, double chordTolerance) {
  if (auto planar = triangulatePlanar(shape)) return *planar;
  if (auto s = std::get_if<Sphere>(&shape)) return tessellateSphere(*s, chordTolerance);
  if (auto c = std::get_if<Cylinder>(&shape)) return tessellateCylinder(*c, chordTolerance);
  return tessellateDisc(std::get<Disc>(shape), chordTolerance);
}

}  // namespace omnicam
