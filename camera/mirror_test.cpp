#include "mirror.h"

#include <gtest/gtest.h>

#include <cmath>

#include "errors.h"

namespace omnicam {
namespace {

TEST(HyperbolicMirror, ThesisParametersGiveCorrectedA2AndB2) {
  const HyperbolicMirror m(11.546, 0.02321);
  // docs/conventions.md §1: a² = 1.11347 cm², b² = 0.23329 cm² (the thesis' printed 1.1357 is a slip).
  EXPECT_NEAR(m.a2() * 1e4, 1.11347, 1e-5);
  EXPECT_NEAR(m.b2() * 1e4, 0.23329, 1e-5);
  EXPECT_NEAR(m.xi(), 0.995494, 1e-6);
  // Foci of a hyperbola: c/2 = sqrt(a² + b²).
  EXPECT_NEAR(std::sqrt(m.a2() + m.b2()), 0.02321 / 2, 1e-12);
}

TEST(HyperbolicMirror, RejectsNonPhysicalParameters) {
  EXPECT_THROW(HyperbolicMirror(2.0, 0.02), InputError);
  EXPECT_THROW(HyperbolicMirror(5.0, 0.0), InputError);
  EXPECT_THROW(HyperbolicMirror(5.0, -1.0), InputError);
}

TEST(HyperbolicMirror, PinholeRaysReflectThroughTheEffectiveViewpoint) {
  // The single-viewpoint property, checked by the law of reflection on the exact quadric.
  const HyperbolicMirror m(11.546, 0.02321);
  int checked = 0;
  for (double tilt = 0.0; tilt < 0.23; tilt += 0.01) {
    for (double az = 0.0; az < 6.28; az += 0.7) {
      const Vec3 d(std::sin(tilt) * std::cos(az), std::sin(tilt) * std::sin(az), std::cos(tilt));
      const auto hit = m.pointFromPinhole(d);
      if (!hit) continue;
      EXPECT_NEAR(m.implicit(*hit), 0.0, 1e-9);
      const Vec3 n = m.normalAt(*hit);
      const Vec3 reflected = d - 2.0 * d.dot(n) * n;
      // Light from the world arrives along −reflected; extended past the mirror point it
      // must head straight for F' (the origin).
      const Vec3 toViewpoint = (-*hit).normalized();
      EXPECT_GT((-reflected).dot(toViewpoint), 1.0 - 1e-12) << tilt << " " << az;
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}

}  // namespace
}  // namespace omnicam
