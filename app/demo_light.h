#pragma once
// The demo's "light" section (docs/path-tracing.md): the fast renderer's path shading as a dataset
// renders it beside Cycles' frame of the same textured hall, and the PSNR between them.
#include <string>

namespace omnicam::cli {

// Writes light_*.png into `out` from the hall at `scenePath`; returns the section's HTML.
std::string demoLight(const std::string& out, const std::string& scenePath, bool blender);

}  // namespace omnicam::cli
