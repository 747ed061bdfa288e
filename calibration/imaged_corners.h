#pragma once
// Where a calibration target's corners are imaged: each corner's exact raster point through the
// camera's own project() (non-central rigs included) and whether the camera sees it there.
#include <cmath>
#include <string>
#include <vector>

#include "calibration_target.h"
#include "camera.h"
#include "ray_scene.h"
#include "scene.h"

namespace omnicam {

enum class CornerSight {
  Seen,
  BeyondRim,     // not imaged: behind the model, beyond the mirror's rim or a lens' field of view
  OutsideImage,  // imaged outside the image rectangle
  BackFacing,    // the camera sees the board's back
  Occluded,      // something else is in front of it
};
const char* cornerSightName(CornerSight sight);

struct ImagedCorner {
  int index = 0;       // in targetCorners' order
  Vec2 raster = Vec2::Constant(NAN);  // omnicam raster (pixel centres at +0.5); NaN when not imaged
  CornerSight sight = CornerSight::BeyondRim;
};

// A corner whose camera ray meets the board this close to it (metres) is seen.
inline constexpr double kCornerHitTolerance = 1e-4;

// Every corner of `target`, seen by `camera` placed at worldFromViewpoint in the scene `rays`
// traces (the target one of its calibration targets); `rays` null: the board alone, nothing
// occludes it.
std::vector<ImagedCorner> imagedCorners(const Camera& camera, const Rigid& worldFromViewpoint, const RayScene* rays,
                                        const CalibrationTarget& target);

}  // namespace omnicam
