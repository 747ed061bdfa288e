#pragma once
// The scene format's `rig` (docs/scene-format.md): a mirror and the camera below it, or a lens
// camera (lens_fields.h); either with its shutter and tilt. Read strictly, each range checked.
#include "json_fields.h"
#include "rig.h"

namespace omnicam {

// The rig of `rig`; fails on the field at fault (JsonFields::fail), or with InputError when the
// fields are each fine but give no camera (its rim or framing not imaged, the camera not below
// the mirror).
RigSpec readRig(JsonFields rig);

}  // namespace omnicam
