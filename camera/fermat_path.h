#pragma once
// World → pixel as a convex problem, the guarantee behind PhysicalCamera::project.
//
// Every mirror here bounds a convex body K = {(x, y, z): |(x, y)| ≤ rim radius, z(x, y) ≤ z ≤ rimZ}
// (the region above a convex height field, cut by the rim plane). For a camera and a point P
// outside K, the path length L(X) = (camera to X) + |X − P| is a convex function of X. So:
//  - a physical reflection point (the reflection law, camera and P both on the mirror's outer
//    side) is a minimiser of L over K: K lies behind the tangent plane there, while the region
//    L < L(X), an ellipsoid of revolution about camera and P, lies in front of it;
//  - when the straight path from camera to P misses K, the minimiser is unique, and one on the
//    mirror where it has a tangent plane (not its rim's edge, not the cone's apex) obeys the
//    reflection law (its optimality condition): there is at most one reflection point, and
//    exactly one when the minimiser lies there. When the straight path meets K, every point of
//    it inside K is a minimiser, and none reflects.
// minimiseFermatPath finds a minimiser by a search that always converges: ψ(x, y) = min over z
// of L on K's vertical slice is convex on the rim's disc (partial minimisation keeps convexity),
// so nested golden-section searches over x and y close in on its minimum. docs/physical-camera.md
// has the argument in full.
#include "geometry.h"
#include "mirror_surface.h"
#include "pinhole.h"

namespace omnicam {

struct FermatMinimum {
  Vec3 point;  // a minimiser of the path length over the mirror's body, viewpoint frame
  // Where it lies. Mirror: on the mirror where it has a tangent plane, the reflection point.
  // Corner: within the search's accuracy of the rim's edge or the cone's apex, where it may be a
  // reflection point nearby or a corner of the body that reflects nothing (Newton's method and
  // the reflection law's checks decide). RimPlane, or Inside (the straight path from camera to
  // the point meets the body, or the point is inside it): no mirror point reflects the point.
  enum class On { Mirror, Corner, RimPlane, Inside } on;
};

// A minimiser of camera → X → p over the mirror's body, to about 10⁻⁵ of the rim radius (where
// rounding hides the rise of the path length; a start for Newton's method, which polishes it).
// `camera` is the traced pinhole (its distance from the point, or for an orthographic camera the
// length along its axis).
FermatMinimum minimiseFermatPath(const MirrorSurface& mirror, const Pinhole& camera, const Vec3& p);

}  // namespace omnicam
