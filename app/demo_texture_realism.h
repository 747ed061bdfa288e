#pragma once
// The demo's texture-realism frame (part of the "robot" section, docs/experiments.md): the hall
// with real-photo walls, beacons found by classifiers trained on the plain hall.
#include <string>

namespace omnicam::cli {

// Writes hall_detections.png (and the hall's renders under `out`/hall); returns the HTML.
std::string demoTexturedHall(const std::string& out, const std::string& scenePath);

}  // namespace omnicam::cli
