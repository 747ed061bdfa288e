#pragma once
// Robot poses of a dataset: a scene's named path, an explicit list, or seeded random sampling
// with clearance. Random sampling draws x, y, yaw from a 64-bit Mersenne Twister seeded with the
// spec's seed, turned into doubles by bit arithmetic (not std::uniform_real_distribution, whose
// output differs between standard libraries), so a seed gives the same poses everywhere.
#include <array>
#include <vector>

#include "dataset_spec.h"
#include "scene.h"

namespace omnicam {

// The robot poses the spec asks for. Random poses with a clearance are drawn uniformly from the
// region's free space (free_space.h), four draws per pose (triangle, two for the point, yaw);
// without a clearance, uniformly from the region (three draws). InputError naming the spec's
// field for a missing path, too few frames, or a region with no free space at that clearance.
std::vector<RobotPose> datasetPoses(const DatasetSpec& spec, const Scene& scene, double topHeight);

}  // namespace omnicam
