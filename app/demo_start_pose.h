#pragma once
// The demo's "start-pose" section: the open field from the thesis' start pose by every engine,
// unlit and lit; the incidence-angle rings (thesis Figs. 3.11-3.12) measured in each engine's
// render; the thesis' cube-map method (Fig. 3.4) against the exact model; the views of §3.2.1.
#include <string>
#include <vector>

namespace omnicam::cli {

// Each engine's ring RMS against the exact model, as the start-pose section measured them.
struct RingSummary {
  std::string engine;
  double rmsPxExact = 0.0;
};

// Writes robocup2006_*.png, rings_*, method_*.png and the views into `out`, and the rings'
// summary into `out`/sections; returns the section's HTML.
std::string demoStartPose(const std::string& out, int spp, bool povray, bool blender);

// The rings the last start-pose section measured in `out`; none if it has not run.
std::vector<RingSummary> readRingSummary(const std::string& out);

}  // namespace omnicam::cli
