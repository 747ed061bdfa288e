#pragma once
// Range and bearing of a landmark from where it appears in the omni image (thesis §3.4.1): the
// pixel gives the viewing ray from F'; a landmark band at a known height above the floor meets
// that ray at one point. The thesis inverted its bird's-eye equations (3.3–3.5); this inverts
// the exact model.
#include <optional>

#include "ekf.h"
#include "rig.h"

namespace omnicam {

// Range (metres, horizontal from F') and bearing (radians CCW from the camera's forward axis) of
// the point at height `pointHeight` above the floor seen at continuous raster position `raster`
// (centres at +0.5) by a camera with `rig`. nullopt when the ray never reaches that height
// (the point would be at or beyond the horizon).
std::optional<RangeBearing> rangeBearingFromRaster(const RigSpec& rig, const Vec2& raster, double pointHeight);

}  // namespace omnicam
