// The convex route of world → pixel (fermat_path.h): the minimum of the path length over the
// mirror's body is the mirror point the forward trace reflects from (the trace intersects the
// quadric in closed form; the search never sees it), points no mirror point reflects have their
// minimum off the mirror, and the route alone round-trips pixels as exactly as project must.
#include "fermat_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "physical_camera.h"
#include "test_rigs.h"

namespace omnicam {
namespace {

// Every shape and build, its camera moved 2 mm and turned 1°; the hyperboloid 3 mm and 2°.
std::vector<RigSpec> everyShape() {
  return {test::misaligned(3.0, 2.0), test::shaped(MirrorShape::Paraboloid, 0.0), test::shaped(MirrorShape::Paraboloid, 0.15),
          test::shaped(MirrorShape::Sphere, 0.12), test::shaped(MirrorShape::Cone, 0.05)};
}

const char* nameOf(const RigSpec& rig) {
  if (const auto* paraboloid = std::get_if<ParaboloidMirror>(&rig.mirrorRig().shape))
    return paraboloid->cameraDistance == 0.0 ? "orthographic paraboloid" : "perspective paraboloid";
  return mirrorShapeName(rig.mirrorRig().shape);
}

TEST(FermatPath, ItsMinimumIsTheMirrorPointTheTraceReflectsFrom) {
  for (const RigSpec& rig : everyShape()) {
    const PhysicalCamera camera(rig);
    const double r = camera.mirror().rimRadius();
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> coord(0.0, rig.mirrorRig().imageSize), logDepth(std::log(0.1), std::log(100.0));
    double worst = 0.0;
    int atTheEdge = 0;
    for (int done = 0; done < 2000;) {
      const auto ray = camera.generateRay({Vec2(coord(rng), coord(rng))});
      if (!ray) continue;
      ++done;
      const FermatMinimum minimum = minimiseFermatPath(camera.mirror(), camera.pinhole(), ray->origin + std::exp(logDepth(rng)) * ray->direction);
      if (minimum.on == FermatMinimum::On::Corner) {
        ++atTheEdge;
        continue;
      }
      ASSERT_EQ(minimum.on, FermatMinimum::On::Mirror) << nameOf(rig);
      worst = std::max(worst, (minimum.point - ray->origin).norm() / r);
    }
    std::printf("%s: minimum within %.3g rim radii of the traced mirror point; %d of 2000 at a corner\n",
                nameOf(rig), worst, atTheEdge);
    EXPECT_LE(atTheEdge, 20) << nameOf(rig);  // within 10⁻⁴ rim radii of the rim (or the cone's apex)
    // Golden-section searches locate a smooth minimum only to where rounding hides the rise of
    // the path length (~10⁻⁵ rim radii here): a start for Newton's method, which polishes it.
    EXPECT_LE(worst, 1e-4) << nameOf(rig);
  }
}

TEST(FermatPath, PointsNoMirrorPointReflectsHaveTheirMinimumOffTheMirror) {
  for (const RigSpec& rig : everyShape()) {
    const PhysicalCamera camera(rig);
    const MirrorSurface& mirror = camera.mirror();
    const double r = mirror.rimRadius();
    // The straight path runs through the mirror's body: straight above it, or inside it.
    for (const Vec3& p : {Vec3(0.001, 0.002, 0.5),
                          Vec3(0.1 * r, -0.05 * r, 0.5 * (mirror.heightAt(0.1 * r, -0.05 * r) + mirror.rimZ()))}) {
      EXPECT_EQ(minimiseFermatPath(mirror, camera.pinhole(), p).on, FermatMinimum::On::Inside) << nameOf(rig) << " " << p.transpose();
      EXPECT_FALSE(camera.project(p)) << nameOf(rig) << " " << p.transpose();
    }
    // Above every shape's rim horizon (at most 45° here), all round; and for the cone, straight
    // below (its apex hides the nadir).
    std::vector<Vec3> unseen;
    for (double elevation : {70.0, 80.0})
      for (int k = 0; k < 8; ++k) {
        const double e = radians(elevation), a = kPi * k / 4.0;
        unseen.push_back(5.0 * Vec3(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)));
      }
    if (std::holds_alternative<ConeMirror>(rig.mirrorRig().shape)) {
      unseen.push_back(Vec3(0.001, 0.002, -5.0));
      EXPECT_EQ(minimiseFermatPath(mirror, camera.pinhole(), unseen.back()).on, FermatMinimum::On::Corner);
    }
    for (const Vec3& p : unseen) {
      EXPECT_NE(minimiseFermatPath(mirror, camera.pinhole(), p).on, FermatMinimum::On::Mirror) << nameOf(rig) << " " << p.transpose();
      EXPECT_FALSE(camera.project(p)) << nameOf(rig) << " " << p.transpose();
    }
  }
}

TEST(FermatPath, TheConvexRouteAloneRoundTripsEveryShape) {
  for (const RigSpec& rig : everyShape()) {
    const PhysicalCamera camera(rig);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> coord(0.0, rig.mirrorRig().imageSize), logDepth(std::log(0.1), std::log(100.0));
    double worst = 0.0;
    int lost = 0;
    for (int done = 0; done < 3000;) {
      const Vec2 pixel(coord(rng), coord(rng));
      const auto ray = camera.generateRay({pixel});
      if (!ray) continue;
      ++done;
      const auto back = camera.projectFromFermatMinimum(ray->origin + std::exp(logDepth(rng)) * ray->direction);
      if (!back) {
        ++lost;
        continue;
      }
      worst = std::max(worst, (*back - pixel).norm());
    }
    std::printf("%s: convex route, 3000 round trips, worst %.3g px, %d not projected\n", nameOf(rig), worst, lost);
    EXPECT_EQ(lost, 0) << nameOf(rig);
    EXPECT_LE(worst, 1e-6) << nameOf(rig);
  }
}

// project (with its quick answers) against the convex search alone, for `count` points in every
// direction, 5 cm to 1 km from the design point: how many are seen, on how many the two routes
// disagree about whether they are, and the largest pixel distance between their answers.
struct RouteAgreement {
  int seen = 0, disagree = 0;
  double worstPx = 0.0;
};
RouteAgreement projectAgainstSearch(const PhysicalCamera& camera, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> logDistance(std::log(0.05), std::log(1000.0));
  RouteAgreement out;
  for (int k = 0; k < count; ++k) {
    const Vec3 p = std::exp(logDistance(rng)) * Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    const auto quick = camera.project(p);
    const auto searched = camera.projectFromFermatMinimum(p);
    if (quick.has_value() != searched.has_value()) ++out.disagree;
    else if (quick) ++out.seen, out.worstPx = std::max(out.worstPx, (*quick - *searched).norm());
  }
  return out;
}

// The cone seen from a pinhole on its axis is a plane problem (mirror_surface.h's
// axialReflection): its closed form is project's whole answer there, "not seen" included. It must
// agree with the convex search — which never uses it — on every point: seen or not, and where.
// (Its round trips: PhysicalCamera.RoundTripsOfAConeFromItsAxis.)
TEST(FermatPath, TheConesClosedFormAgreesWithTheConvexSearch) {
  RigSpec centred = test::shaped(MirrorShape::Cone, 0.05);
  centred.mirrorRig().mount = CameraMount{};
  RigSpec movedAlongAxisAndTurned = centred;
  movedAlongAxisAndTurned.mirrorRig().mount.offsetMm = {0.0, 0.0, -4.0};
  movedAlongAxisAndTurned.mirrorRig().mount.rotationDeg = {1.0, -0.6, 0.8};
  for (const RigSpec& rig : {centred, movedAlongAxisAndTurned}) {
    const PhysicalCamera camera(rig);
    ASSERT_EQ(camera.pinhole().position.head<2>().norm(), 0.0);
    const RouteAgreement a = projectAgainstSearch(camera, 4000, 5);
    std::printf("cone on its axis: 4000 points, %d seen, %d disagree on whether, worst %.3g px\n", a.seen, a.disagree, a.worstPx);
    EXPECT_GT(a.seen, 400);
    EXPECT_EQ(a.disagree, 0);
    EXPECT_LE(a.worstPx, 1e-6);
  }
}

// project's quick answers — the shape's starts, the straight path through the body, the minimum
// proven at a corner (rim edge, apex) — against the convex search alone, on every shape and
// build: the same points seen, at the same pixels, near and a kilometre away.
TEST(FermatPath, TheQuickAnswersAgreeWithTheConvexSearchOnEveryShape) {
  std::vector<RigSpec> rigs = everyShape();
  RigSpec turnedCone = test::shaped(MirrorShape::Cone, 0.05);
  turnedCone.mirrorRig().mount.offsetMm = {-6.0, 4.0, -3.0};
  turnedCone.mirrorRig().mount.rotationDeg = {-4.0, 3.0, 10.0};
  rigs.push_back(turnedCone);
  for (const RigSpec& rig : rigs) {
    const RouteAgreement a = projectAgainstSearch(PhysicalCamera(rig), 3000, 17);
    std::printf("%s: 3000 points, %d seen, %d disagree on whether, worst %.3g px\n", nameOf(rig), a.seen, a.disagree, a.worstPx);
    EXPECT_GT(a.seen, 300) << nameOf(rig);
    EXPECT_EQ(a.disagree, 0) << nameOf(rig);
    EXPECT_LE(a.worstPx, 1e-6) << nameOf(rig);
  }
}

}  // namespace
}  // namespace omnicam
