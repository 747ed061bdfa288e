#pragma once
// A mirror of revolution (the hyperboloid; the sphere) as a triangle mesh whose every point lies within a stated distance of
// the exact surface, with analytic per-vertex normals — what mesh-only renderers (Blender) get.
//
// Construction (viewpoint frame, metres): vertices on the surface on `rings` circles of constant
// height between the vertex and the rim, `sectors` vertices per circle, plus the apex. Every
// vertex is exactly on the quadric; a triangle's interior lies inside the convex sheet. Ring and
// sector counts are chosen from the surface's largest curvatures so that the chord sagitta of each
// edge is below half the requested bound; mirrorSurfaceDistance() measures the result
// independently (the test samples every triangle densely).
#include <vector>

#include "geometry.h"
#include "mirror.h"
#include "mirror_surface.h"
#include "rig.h"
#include "triangulate.h"

namespace omnicam {

struct MirrorMesh {
  TriangleMesh mesh;          // vertices in the viewpoint frame (origin F', z up)
  std::vector<Vec3> normals;  // analytic unit normals, facing the camera (downward/outward)
  double requestedBound = 0;  // metres
  int rings = 0, sectors = 0;
};

// The shapes this file certifies a mesh of (every point within the deviation asked of the
// surface): what the glTF export, and so Blender, can show.
inline constexpr MirrorShape kCertifiedMeshShapes[] = {MirrorShape::Hyperboloid, MirrorShape::Sphere};
// The rig's mirror up to its rim, its profile and normals those of mirror_surface.h (the one
// definition of each shape). InputError for a shape kCertifiedMeshShapes lacks. The sphere's
// lower cap (centre at the origin) is at distance | |p| − R | from a point.
MirrorMesh buildMirrorMesh(const MirrorRig& rig, double maxDeviation);

// Exact Euclidean distance from a point (viewpoint frame) to the mirror's upper sheet, by
// Newton iteration on the closest point of the profile hyperbola (a surface of revolution
// reduces to a 2-D problem in (r, z)).
double mirrorSurfaceDistance(const HyperbolicMirror& mirror, const Vec3& point);

}  // namespace omnicam
