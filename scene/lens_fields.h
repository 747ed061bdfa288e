#pragma once
// The scene format's `rig.lens` (docs/scene-format.md, "Lens cameras"): a camera without a mirror,
// read strictly (each model takes only its own fields, each range-checked) and written back in
// the same shape, so a sidecar's rig reads as the scene's did.
#include <nlohmann/json.hpp>

#include "json_fields.h"
#include "rig.h"

namespace omnicam {

// The lens camera of `lens`; fails on the field at fault (JsonFields::fail).
LensCameraSpec readLensCamera(JsonFields lens);
// `lens` in the scene format (readLensCamera reads it back to an equal spec: angles are written
// as the degrees that convert back to the very same radians).
nlohmann::json lensCameraToJson(const LensCameraSpec& lens);
// True when the lens images at least one pixel centre. Exact for every model whose image is a
// disc about its centre in pixels scaled by (fx, fy) (lensCentre, imagesADisc), with or without
// the centre itself; for a pinhole with distortion, a 64 × 64 grid of pixel centres besides.
bool imagesSomePixel(const LensCameraSpec& lens);

}  // namespace omnicam
