#pragma once
// A camera's frames in the EuRoC/ASL layout (docs/dataset-format.md, "EuRoC/ASL layout"), what
// visual(-inertial) odometry loaders read: <camera>/data/<t_ns>.png, <camera>/data.csv (one row
// per frame: "<t_ns>,<t_ns>.png") and <camera>/sensor.yaml (T_BS, the camera's omni intrinsics,
// rate, resolution and shutter). t_ns is the frame's timestamp, its exposure start, in integer
// nanoseconds.
#include <cstdint>
#include <string>

#include "camera.h"
#include "dataset_spec.h"
#include "output_kinds.h"

namespace omnicam {

// The frames' names (frameTimestampNs, eurocImageName) are the layout's: output_kinds.h.
// The text of <camera>/data.csv for frames [0, frames).
std::string eurocDataCsv(int frames, double intervalS);
// The text of <camera>/sensor.yaml: T_BS maps the sensor frame (the intrinsics files' camera
// frame: X forward, Y right, Z down at F'; for a non-central rig, its best-fit model's frame)
// into the body frame (the robot's: origin on the floor, x forward, y left, z up).
std::string eurocSensorYaml(const DatasetCamera& mount, const RigSpec& rig, const Camera& camera, double intervalS);

}  // namespace omnicam
