#pragma once
// World → pixel as a convex problem, the guarantee behind PhysicalCamera::project.
//
// Every mirror here bounds a convex body K = {(x, y, z): |(x, y)| ≤ rim radius, z(x, y) ≤ z ≤ rimZ}
// (the region above a convex height field, cut by the rim plane). For a camera and a point P
// outside K, the path length L(X) = (camera to X) + |X − P| is a convex function of X. So:
//  - a physical reflection point (the reflection law, camera and P both on the mirror's outer
//    side) is a minimiser of L over K: K lies behind the tangent plane there, while the region
//    L < L(X), an ellipsoid of revolution about camera and P, lies in front of it;
//  - the minimiser is unique, and a minimiser on the mirror (below the rim) obeys the reflection
//    law (its optimality condition), so there is at most one reflection point, and exactly one
//    when the minimiser lies on the mirror.
// minimiseFermatPath finds that minimiser by a search that always converges: ψ(x, y) = min over z
// of L on K's vertical slice is convex on the rim's disc (partial minimisation keeps convexity),
// so nested golden-section searches over x and y close in on its minimum. docs/physical-camera.md
// has the argument in full.
#include "geometry.h"
#include "mirror_surface.h"
#include "physical_camera.h"

namespace omnicam {

struct FermatMinimum {
  Vec3 point;                 // the minimiser of the path length over the mirror's body, viewpoint frame
  // Where it lies. Only on the mirror is it a reflection point; at the rim's edge (within the
  // search's accuracy of it) it may be one just inside the rim, or a corner of the body that
  // reflects nothing; on the rim plane or inside the body it is none.
  enum class On { Mirror, RimEdge, RimPlane, Inside } on;
};

// The minimiser of camera → X → p over the mirror's body, to about 1e-8 of the rim radius (a
// start for Newton's method, which polishes it). `camera` is the traced pinhole (its distance
// from the point, or for an orthographic camera the length along its axis).
FermatMinimum minimiseFermatPath(const MirrorSurface& mirror, const Pinhole& camera, const Vec3& p);

}  // namespace omnicam
