#pragma once
// A calibration sequence's images in one ROS 1 bag for Kalibr (docs/calibration.md, "Calibration
// sequences"): DIR/kalibr.bag, every camera's frames on /<camera>/image_raw (rgb8, header.stamp =
// the frame's timestamp), a mirror camera's flipped top to bottom so that Kalibr's omni model
// describes it with fv > 0 (DIR/kalibr_camchain.yaml, annotations/intrinsics_files.h), written once
// every frame is there (the end of a complete run, or a merge) when the spec asks for it
// (calibration.rosbag). Streamed: one image in memory at a time (rosbag_file.h).
#include "manifest.h"
#include "safe_files.h"

namespace omnicam {

// Writes the bag when the header asks for one and lists it (calibration.files.rosbag). The
// frames' PNGs are read inside the folder and must hash to the manifest's.
void writeCalibrationBag(const SafeFolder& dir, DatasetManifest& manifest);

}  // namespace omnicam
