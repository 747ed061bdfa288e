#pragma once
// The demo's reference dataset (part of the "robot" section): two cameras along the thesis loop,
// every output, its depth, instances, classes and annotations shown.
#include <string>

namespace omnicam::cli {

// Writes dataset_spec.json, dataset/ and dataset_*.png into `out`; returns the section's HTML.
std::string demoDataset(const std::string& out, const std::string& scenePath);

}  // namespace omnicam::cli
