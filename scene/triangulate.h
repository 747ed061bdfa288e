#pragma once
// Planar shapes as triangles with UVs. Shared by the fast renderer and the exporters so that
// every engine sees the same triangles.
#include <optional>
#include <vector>

#include "scene.h"

namespace omnicam {

struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<Eigen::Vector2d> uvs;  // one per vertex
  std::vector<Eigen::Vector3i> triangles;
};

TriangleMesh triangulate(const Box& box);
TriangleMesh triangulate(const Quad& quad);
TriangleMesh triangulate(const Mesh& mesh);
// The triangles of a planar shape (box, quad, mesh); nullopt for curved ones (sphere,
// cylinder, disc), which every engine intersects exactly.
std::optional<TriangleMesh> triangulatePlanar(const Shape& shape);
// Any shape as triangles: planar ones exactly, curved ones with vertices on the surface and
// chords within `chordTolerance` (metres) of it, UVs as the analytic intersections define them.
TriangleMesh tessellate(const Shape& shape, double chordTolerance);
// Segments a circle of `radius` needs so that its chords stay within `chordTolerance`.
int segmentsForCircle(double radius, double chordTolerance);

}  // namespace omnicam
