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
#include "placement.h"

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

// The frame the intrinsics files' model lives in, placed in the world: a mirror camera's central
// model's (a physical rig's best fit has its own frame: opencv.yaml's camera_from_rig), a lens
// camera's own. Every output that gives those intrinsics with a pose — EuRoC's T_BS, Kalibr's
// T_cn_cnm1, ROS's tf — places this frame; poses.tum places the rig's camera frame.
Rigid worldFromModelCamera(const CameraPlacement& placement, const Camera& camera);

// Kalibr's camchain of `cameras` as a calibration bag shows their images (dataset/calibration_bag.h):
// a mirror camera's image flipped top to bottom, so that its omni intrinsics are
// [xi, γx, −γy, cx, H − 1 − cy] with fv > 0, as Kalibr's reader requires (same camera frame, same
// radtan distortion); a lens camera's as its kalibr.yaml. camN (N > 0) has T_cn_cnm1, the
// previous camera's frame into its own (4×4, rows). InputError naming a camera Kalibr has no
// model for (a panorama, ...).
struct KalibrChainCamera {
  std::string name;
  const Camera* camera = nullptr;
  Rigid worldFromCamera = Rigid::Identity();  // the intrinsics files' model's frame (worldFromModelCamera)
};
std::string kalibrCamchainYaml(const std::vector<KalibrChainCamera>& cameras);

// A mirror camera's files' texts, for writing and for tests.
std::string openCvIntrinsicsYaml(const Camera& camera);
std::string kalibrIntrinsicsYaml(const std::string& name, const Camera& camera);
std::string camodocalIntrinsicsYaml(const std::string& name, const Camera& camera);

}  // namespace omnicam
