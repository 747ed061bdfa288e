#include "triangulate.h"

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

}  // namespace omnicam
