#pragma once
// The demo's "physical" section (docs/physical-camera.md): the ideal rig beside a misaligned one,
// POV-Ray's truth of the misaligned rig, and the best-fit central model's residual.
#include <string>

#include "scene.h"

namespace omnicam::cli {

// Writes physical_*.png into `out`; returns the section's HTML.
std::string demoPhysicalCamera(const std::string& out, const Scene& arena, int spp, bool povray);

}  // namespace omnicam::cli
