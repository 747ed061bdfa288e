#pragma once
// The demo's "Lens cameras" section (docs/lens-cameras.md): one pose through the mirror, a fisheye
// and a 360° panorama, the fisheye's depth along its rays, and each lens against the ground truths
// that have its camera.
#include <string>

#include "scene.h"

namespace omnicam::cli {

// Writes lens_*.png into `out`; returns the section's HTML.
std::string demoLenses(const std::string& out, const Scene& arena, int spp, bool povray, bool blender);

}  // namespace omnicam::cli
