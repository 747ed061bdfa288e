// Tessellation stays within its chord tolerance for ordinary objects and bounded for huge ones.
#include "triangulate.h"

#include <gtest/gtest.h>

#include <cmath>

namespace omnicam {
namespace {

double maxChordError(const TriangleMesh& ring, const Vec3& centre, double radius) {
  // Midpoints of consecutive rim vertices of a disc: their distance below the circle.
  double worst = 0.0;
  for (const auto& t : ring.triangles)
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = ring.vertices[t[k]], b = ring.vertices[t[(k + 1) % 3]];
      if (std::abs((a - centre).norm() - radius) > 1e-9 || std::abs((b - centre).norm() - radius) > 1e-9) continue;
      worst = std::max(worst, radius - (0.5 * (a + b) - centre).norm());
    }
  return worst;
}

TEST(Tessellation, HoldsTheChordToleranceUpToAHundredMetres) {
  for (double radius : {0.05, 1.0, 100.0}) {
    const Disc disc{{0, 0, 0}, {0, 0, 1}, radius, 0.0};
    const double error = maxChordError(tessellate(disc, 0.5e-3), disc.center, radius);
    EXPECT_LE(error, 0.5e-3) << radius;
    EXPECT_GT(error, 0.0) << radius << ": no rim edges found";
  }
}

TEST(Tessellation, AKilometreSphereStaysBounded) {
  // Unbounded, a 20 km sphere at 0.2 mm would be ~10^8 triangles; capped at 1024 segments.
  const TriangleMesh m = tessellate(Sphere{{0, 0, 0}, 2e4}, 0.2e-3);
  EXPECT_LE(m.triangles.size(), 1024u * 512u * 2u);
  EXPECT_GT(m.triangles.size(), 1000u);
}

}  // namespace
}  // namespace omnicam
