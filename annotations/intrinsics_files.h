#pragma once
// The camera's intrinsics in the files other tools read: OpenCV's cv::omnidir (FileStorage YAML:
// K, xi, D), Kalibr's camchain (camera_model omni) and camodocal's MEI model. All three describe
// the same unified (Mei) model as the sidecar's "intrinsics", in OpenCV's pixel convention
// (centres at integers: cx = W/2 − 0.5), with γ_y < 0: the catadioptric image is a mirror image,
// so a right-handed camera frame (X forward, Y right, Z down at F') needs one axis flipped.
//
// A physical rig's files hold the exact Mei model where it has one (make_camera.h's
// centralModelOf); a non-central rig's hold the best-fit central model, marked approximate in a
// comment with its residuals, and its fitted camera frame (OpenCV's file only: there is no field
// for it in the other two). The exact rays are in the camera's rays.exr.
//
// A lens camera (lens_camera.h) gets the files of lens_intrinsics_files.h that exist for its model.
#include <string>
#include <vector>

#include "camera.h"

namespace omnicam {

struct IntrinsicsFile {
  std::string kind;      // "intrinsics_opencv", "intrinsics_kalibr", "intrinsics_camodocal" (manifest kinds)
  std::string fileName;  // "opencv.yaml", "kalibr.yaml", "camodocal.yaml"
  std::string text;
};
// The files that describe `camera` (called `name`): all three for a mirror camera, those that
// exist for a lens camera's model (none for some: its sidecar and rays.exr state it).
std::vector<IntrinsicsFile> intrinsicsFiles(const std::string& name, const Camera& camera);

// Writes intrinsicsFiles() into DIR (each atomically).
void writeIntrinsicsFiles(const std::string& dir, const std::string& name, const Camera& camera);

// A mirror camera's files' texts, for writing and for tests.
std::string openCvIntrinsicsYaml(const Camera& camera);
std::string kalibrIntrinsicsYaml(const std::string& name, const Camera& camera);
std::string camodocalIntrinsicsYaml(const std::string& name, const Camera& camera);

}  // namespace omnicam
