#include "mirror_mesh.h"

#include <gtest/gtest.h>

#include <cmath>

#include "errors.h"
#include "rig.h"

namespace omnicam {
namespace {

TEST(MirrorSurfaceDistance, ExactOnAndOffTheSurface) {
  const HyperbolicMirror m(11.546, 0.02321);
  for (double r = 0.0; r < 0.008; r += 0.001) {
    const Vec3 onSurface(r, 0.0, m.a() * std::sqrt(1.0 + r * r / m.b2()) - m.c() / 2.0);
    EXPECT_LT(mirrorSurfaceDistance(m, onSurface), 1e-12);
    // Moving along the normal by d gives distance d (the sheet is convex; small d).
    const Vec3 n = m.normalAt(onSurface);
    EXPECT_NEAR(mirrorSurfaceDistance(m, onSurface + 2e-6 * n), 2e-6, 1e-12);
    EXPECT_NEAR(mirrorSurfaceDistance(m, onSurface - 2e-6 * n), 2e-6, 1e-12);
  }
}

// Independent measurement: the largest exact distance to the surface at a dense barycentric grid
// on every triangle.
template <typename Distance>
double measuredDeviation(const MirrorMesh& mesh, Distance distance) {
  double worst = 0.0;
  const int n = 6;
  for (const auto& t : mesh.mesh.triangles) {
    const Vec3 &A = mesh.mesh.vertices[t[0]], &B = mesh.mesh.vertices[t[1]], &C = mesh.mesh.vertices[t[2]];
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n;
        worst = std::max(worst, distance((1 - u - v) * A + u * B + v * C));
      }
  }
  return worst;
}

TEST(MirrorMesh, MeasuredDeviationIsBelowTheCertifiedBound) {
  const RigSpec rig;
  const HyperbolicMirror m = rig.mirrorRig().hyperboloid().mirror();
  const double bound = 0.5e-6;  // 0.5 µm
  const MirrorMesh mesh = buildMirrorMesh(rig.mirrorRig(), bound);
  const double worst = measuredDeviation(mesh, [&m](const Vec3& p) { return mirrorSurfaceDistance(m, p); });
  std::printf("mirror mesh: %zu triangles (%d rings x %d sectors), measured max deviation %.4f um (bound %.2f um)\n",
              mesh.mesh.triangles.size(), mesh.rings, mesh.sectors, worst * 1e6, bound * 1e6);
  EXPECT_LT(worst, bound);
  EXPECT_GT(worst, 0.1 * bound);  // the bound is not absurdly loose either
  for (size_t k = 0; k < mesh.normals.size(); ++k) {
    EXPECT_NEAR(mesh.normals[k].norm(), 1.0, 1e-12);
    EXPECT_LT(mesh.normals[k].z(), 0.0);  // facing down, toward the camera
    EXPECT_LT(mirrorSurfaceDistance(m, mesh.mesh.vertices[k]), 1e-12);
  }
  // Faces wound counter-clockwise seen from the camera: geometric normal agrees with the analytic one.
  const auto& t = mesh.mesh.triangles[mesh.mesh.triangles.size() / 2];
  const Vec3 face = (mesh.mesh.vertices[t[1]] - mesh.mesh.vertices[t[0]]).cross(mesh.mesh.vertices[t[2]] - mesh.mesh.vertices[t[0]]);
  EXPECT_GT(face.dot(mesh.normals[t[0]]), 0.0);
  // The rim ring lies exactly at the rim direction.
  const Vec3 rimVertex = mesh.mesh.vertices.back();
  EXPECT_NEAR(incidenceAngle(unifiedCameraFromViewpoint().linear() * rimVertex), rig.camera().rimTheta(), 1e-12);
}

// The sphere's cap: its exact distance is | |p| − R |, independent of the builder.
TEST(MirrorMesh, TheSpheresCapIsCertifiedToo) {
  const double radius = 0.03, bound = 0.5e-6;
  MirrorRig sphere;
  sphere.shape = SphereMirror{radius, 60.0, 0.2};
  const MirrorMesh mesh = buildMirrorMesh(sphere, bound);
  const double worst = measuredDeviation(mesh, [radius](const Vec3& p) { return std::abs(p.norm() - radius); });
  std::printf("sphere mesh: %zu triangles (%d rings x %d sectors), measured max deviation %.4f um (bound %.2f um)\n",
              mesh.mesh.triangles.size(), mesh.rings, mesh.sectors, worst * 1e6, bound * 1e6);
  EXPECT_LT(worst, bound);
  EXPECT_GT(worst, 0.1 * bound);
  for (size_t k = 0; k < mesh.normals.size(); ++k) {
    EXPECT_LT(std::abs(mesh.mesh.vertices[k].norm() - radius), 1e-15);
    EXPECT_LT(mesh.normals[k].z(), 0.0);
  }
  const auto& t = mesh.mesh.triangles[mesh.mesh.triangles.size() / 2];
  const Vec3 face = (mesh.mesh.vertices[t[1]] - mesh.mesh.vertices[t[0]]).cross(mesh.mesh.vertices[t[2]] - mesh.mesh.vertices[t[0]]);
  EXPECT_GT(face.dot(mesh.normals[t[0]]), 0.0);
  EXPECT_NEAR(mesh.mesh.vertices.back().z(), -radius * std::cos(radians(60.0)), 1e-15);
}

// A shape without a certified mesh is refused in the library's terms, not meshed by a wrong profile.
TEST(MirrorMesh, OnlyTheCertifiedShapes) {
  MirrorRig cone;
  cone.shape = ConeMirror{45.0, 0.03, 0.12};
  try {
    buildMirrorMesh(cone, 0.5e-6);
    ADD_FAILURE() << "a cone was meshed";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "rig.mirror.shape: a mesh is certified for the hyperboloid and the sphere only (got cone)");
  }
}

}  // namespace
}  // namespace omnicam
