#pragma once
// Where a moving camera images a world point (docs/motion.md): each readout line sees the scene at
// its own time, so the point is imaged on the line whose time puts the robot where that line sees
// it. That line is the fixed point of line → time → pose → raster point → line.
#include <optional>

#include "camera.h"
#include "placement.h"

namespace omnicam {

struct TimedProjection {
  Vec2 raster;           // continuous raster coordinates
  double seconds = 0.0;  // after the exposure start: mid-exposure of the raster point's line
};

// The projection of world point `p` by `camera` (its rig's shutter) at `placement`. A global
// shutter images every point at mid-exposure. A rolling one iterates from the middle line until
// the line repeats (nullopt where the point is not imaged at a line's time). A cycle between two
// neighbouring lines (a point on their boundary moving against the readout, at any speed) takes
// the one of them imaging it nearer to itself. When the motion is so fast that the lines cycle
// further apart, every line is tried in readout order: the first whose own time images the point
// on itself wins, or, where none does, the one imaging it nearest to itself.
std::optional<TimedProjection> projectAtReadout(const Camera& camera, const CameraPlacement& placement, const Vec3& p);

}  // namespace omnicam
