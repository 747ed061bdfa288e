#pragma once
// The camera of a rig: the closed-form central model when the rig is ideal, else the physical
// camera traced through the mirror. `traced` asks for the physical camera even for the ideal rig
// (the check that both agree).
#include <memory>

#include "camera.h"

namespace omnicam {

std::shared_ptr<const Camera> makeCamera(const RigSpec& rig, bool traced = false);

}  // namespace omnicam
