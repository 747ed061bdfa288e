// The Embree scene far from the world's origin: it counts its 32-bit coordinates from the whole
// metre nearest the scene's start pose, so that a wall and a sphere 9 km out are hit where they
// are to well under a micrometre (from the world's origin, a float steps 1 mm there).
#include "ray_scene.h"

#include <gtest/gtest.h>

namespace omnicam {
namespace {

// A wall (normal +X) at x = x0 + 1.2345 (a value a float cannot hold 9 km out), a sphere of
// radius 0.25 centred 1.5 m along +Y and a pole of radius 0.2 centred 1.5 m along −Y, around a
// start pose at (x0 + 0.4, y0 − 0.3).
Scene farRoom(double x0, double y0) {
  Scene scene;
  scene.startPose = {x0 + 0.4, y0 - 0.3, 0.0};
  scene.materials.push_back(Material{});
  scene.objects.push_back({"wall", 0, Quad{{x0 + 1.2345, y0 - 5.0, 0.0}, {0.0, 10.0, 0.0}, {0.0, 0.0, 3.0}}, ""});
  scene.objects.push_back({"ball", 0, Sphere{{x0 + 0.4, y0 + 1.2, 0.5}, 0.25}, ""});
  scene.objects.push_back({"pole", 0, Cylinder{{x0 + 0.4, y0 - 1.8, 0.0}, {x0 + 0.4, y0 - 1.8, 1.0}, 0.2}, ""});
  return scene;
}

TEST(RayScene, CountsFromTheWholeMetreNearTheStartPoseOnlyFarOut) {
  EXPECT_EQ(RayScene(farRoom(0.0, 0.0)).embreeOrigin(), Vec3::Zero());
  EXPECT_EQ(RayScene(farRoom(60.0, 0.0)).embreeOrigin(), Vec3::Zero());  // 64 m: a float's step is 4 µm
  EXPECT_EQ(RayScene(farRoom(9000.0, -9000.0)).embreeOrigin(), Vec3(9000.0, -9000.0, 0.0));
}

TEST(RayScene, HitsSurfacesNineKilometresOutWhereTheyAre) {
  for (const double x0 : {0.0, 9000.0}) {
    const double y0 = -x0;
    const RayScene rays(farRoom(x0, y0));
    const Vec3 eye(x0 + 0.4, y0 - 0.3, 0.5);
    // The wall, along +X: 1.2345 − 0.4 = 0.8345 m.
    const auto wall = rays.intersect(eye, Vec3(1.0, 0.0, 0.0));
    ASSERT_TRUE(wall.has_value()) << x0;
    EXPECT_NEAR(wall->t, 0.8345, 1e-6) << x0;
    EXPECT_NEAR(wall->point.x(), x0 + 1.2345, 1e-6) << x0;
    EXPECT_NEAR(wall->normal.x(), 1.0, 1e-9) << x0;  // edge_u × edge_v, not yet faced toward the ray
    // The sphere, along +Y: 1.5 − 0.25 = 1.25 m.
    const auto ball = rays.intersect(eye, Vec3(0.0, 1.0, 0.0));
    ASSERT_TRUE(ball.has_value()) << x0;
    EXPECT_NEAR(ball->t, 1.25, 1e-6) << x0;
    EXPECT_NEAR(ball->point.y(), y0 + 0.95, 1e-6) << x0;
    // Occlusion on the segment, just short of and just past the wall.
    EXPECT_FALSE(rays.occluded(eye, Vec3(1.0, 0.0, 0.0), 0.0, 0.8345 - 1e-4)) << x0;
    EXPECT_TRUE(rays.occluded(eye, Vec3(1.0, 0.0, 0.0), 0.0, 0.8345 + 1e-4)) << x0;
    // A packet of rays sharing the eye gives the same answers as single rays.
    HitPacket packet;
    packet.begin(eye, 2);
    packet.setDirection(0, Eigen::Vector3f(1.0f, 0.0f, 0.0f));
    packet.setDirection(1, Eigen::Vector3f(0.0f, 1.0f, 0.0f));
    rays.intersectPacket(packet);
    ASSERT_EQ(packet.mask(), 3u) << x0;
    EXPECT_NEAR(packet.surface(0).t, 0.8345, 1e-6) << x0;
    EXPECT_NEAR(packet.surface(1).t, 1.25, 1e-6) << x0;
    // Rays that each start somewhere of their own (here halfway back along the ray, traced from
    // t = 0.5): distances from where they start.
    packet.beginEach(2);
    packet.setOrigin(0, eye - Vec3(0.5, 0.0, 0.0), 0.5f);
    packet.setDirection(0, Eigen::Vector3f(1.0f, 0.0f, 0.0f));
    packet.setOrigin(1, eye + Vec3(0.0, 0.5, 0.0), 0.5f);
    packet.setDirection(1, Eigen::Vector3f(0.0f, -1.0f, 0.0f));
    rays.intersectPacket(packet);
    ASSERT_EQ(packet.mask(), 3u) << x0;
    EXPECT_NEAR(packet.surface(0).t, 0.8345, 1e-6) << x0;
    EXPECT_NEAR(packet.surface(1).t, 1.3, 1e-6) << x0;  // the pole: 1.5 − 0.2
    // Occlusion packets: the wall is on the first segment; the pole lies past the second's end.
    const Vec3 origins[2] = {eye, eye};
    const Vec3 directions[2] = {Vec3(1.0, 0.0, 0.0), Vec3(0.0, -1.0, 0.0)};
    const double tNear[2] = {0.0, 0.0}, tFar[2] = {0.8345 + 1e-4, 1.3 - 1e-4};
    EXPECT_EQ(rays.occludedPacket(origins, directions, tNear, tFar, 3u), 1u) << x0;
    // The offset a ray leaving a surface takes is the near room's, 9 km out too.
    EXPECT_DOUBLE_EQ(rays.surfaceOffset(wall->point), 1e-5) << x0;
  }
}

}  // namespace
}  // namespace omnicam
