#pragma once
// The demo's "Time in the camera" section (docs/motion.md): one frame of the thesis loop driven
// at speed through a global and a rolling shutter, their difference, and a vibrating rig's
// per-frame perturbations plotted.
#include <string>

#include "scene.h"

namespace omnicam::cli {

// Writes motion_*.png and motion_vibration.svg into `out`; returns the section's HTML.
std::string demoMotion(const std::string& out, const Scene& arena, int spp);

}  // namespace omnicam::cli
