#pragma once
// A catadioptric camera's mirror: one of four shapes, each with only its own parameters
// (docs/physical-camera.md, "Mirror shapes"). The hyperboloid is the designed single-viewpoint
// mirror; the others are cheaper builds. Each sits level on the robot with its design point at
// rig.height: the hyperboloid's inner focus F', the paraboloid's focus, the sphere's centre, the
// cone's apex. The others' ideal pinhole sits on the axis, `cameraDistance` metres below it.
#include <variant>

#include "mirror.h"

namespace omnicam {

// The designed mirror (Baker–Nayar): its physical pinhole at the outer focus F, c below F'.
struct HyperboloidMirror {
  double k = 11.546;                  // Baker–Nayar mirror parameter, > 2
  double c = 0.02321;                 // focal distance between F and F', metres
  double rimElevationDeg = 45.0;      // the rim, degrees above the horizon
  double framingElevationDeg = 45.0;  // the direction that touches the image border
  HyperbolicMirror mirror() const { return {k, c}; }
  bool operator==(const HyperboloidMirror&) const = default;
};

// z = (r² − h²)/(2h) about its focus.
struct ParaboloidMirror {
  double h = 0.0;                 // metres
  double rimElevationDeg = 45.0;  // the rim, degrees above the horizon seen from the focus
  double cameraDistance = 0.0;    // 0: an orthographic camera looking straight up
  bool operator==(const ParaboloidMirror&) const = default;
};

// The sphere's lower cap.
struct SphereMirror {
  double radius = 0.0;         // metres
  double capAngleDeg = 60.0;   // from its lowest point up to this polar angle
  double cameraDistance = 0.0;
  bool operator==(const SphereMirror&) const = default;
};

// A cone, apex down.
struct ConeMirror {
  double halfAngleDeg = 60.0;  // apex half-angle
  double rimRadius = 0.0;      // metres
  double cameraDistance = 0.0;
  bool operator==(const ConeMirror&) const = default;
};

using MirrorShapeSpec = std::variant<HyperboloidMirror, ParaboloidMirror, SphereMirror, ConeMirror>;

// A shape's name without its parameters, for capability lists and messages; in the order of
// MirrorShapeSpec's alternatives.
enum class MirrorShape { Hyperboloid, Paraboloid, Sphere, Cone };
inline MirrorShape mirrorShapeOf(const MirrorShapeSpec& shape) { return static_cast<MirrorShape>(shape.index()); }
const char* mirrorShapeName(MirrorShape shape);
inline const char* mirrorShapeName(const MirrorShapeSpec& shape) { return mirrorShapeName(mirrorShapeOf(shape)); }

}  // namespace omnicam
