#include "euroc_files.h"

#include <cmath>
#include <sstream>

#include "intrinsics_files.h"
#include "lens_intrinsics_files.h"
#include "make_camera.h"
#include "number_format.h"

namespace omnicam {

std::string eurocDataCsv(int frames, double intervalS) {
  std::ostringstream out;
  out << "#timestamp [ns],filename\n";
  for (int i = 0; i < frames; ++i) out << frameTimestampNs(i, intervalS) << ',' << eurocImageName(i, intervalS) << '\n';
  return out.str();
}

namespace {

// Floats, as Kalibr's reader wants them ("76.0", not "76").
std::string floats(const std::vector<double>& values) {
  std::string out = "[";
  for (const double v : values) out += (out.size() > 1 ? ", " : "") + yamlFloat(v);
  return out + "]";
}

// A lens camera's sensor.yaml: Kalibr's terms where Kalibr has the model, else omnicam's own.
std::string lensSensorYaml(const DatasetCamera& mount, const LensCamera& camera, double intervalS) {
  const Rigid bodyFromSensor = worldFromModelCamera(CameraPlacement(RobotPose{}, BodyVelocity{}, mount.mount), camera);
  std::ostringstream out;
  out << "# EuRoC/ASL camera sensor written by omnicam (docs/dataset-format.md, \"EuRoC/ASL layout\").\n"
      << "# Body frame: the robot's (origin on the floor, x forward, y left, z up). Sensor frame: OpenCV's (X right,\n"
      << "# Y down, Z along the optical axis) at the lens' centre of projection. Timestamps: exposure start.\n"
      << "# Pixel centres are integers.\n"
      << "sensor_type: camera\n"
      << "comment: omnicam " << lensModelName(camera.lens().model) << " camera " << mount.name << "\n"
      << "T_BS:\n  cols: 4\n  rows: 4\n  data: [";
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out << yamlFloat(bodyFromSensor.matrix()(r, c)) << (r == 3 && c == 3 ? "]\n" : ", ");
  out << "rate_hz: " << yamlFloat(1.0 / intervalS) << "\n"
      << "resolution: [" << camera.width() << ", " << camera.height() << "]\n";
  if (const auto kalibr = kalibrLensOf(camera.lens().model)) {
    out << "camera_model: " << kalibr->cameraModel << "\n"
        << "intrinsics: " << floats(kalibr->intrinsics) << "\n"
        << "distortion_model: " << kalibr->distortionModel << "\n"
        << "distortion_coefficients: " << floats(kalibr->coefficients) << "\n";
  } else {
    out << "camera_model: " << lensModelName(camera.lens().model) << "  # no Kalibr model: the sidecar's intrinsics and rays.exr state it\n";
  }
  return out.str();
}

std::string shutterYaml(const RigSpec& rig) {
  std::ostringstream out;
  out << "exposure_s: " << yamlFloat(rig.shutter.exposureS) << "\n";
  if (rig.shutter.rolling) {
    out << "shutter: rolling\n"
        << "line_time_s: " << yamlFloat(rig.shutter.rolling->lineTimeUs / 1e6) << "\n"
        << "readout: " << readoutName(rig.shutter.rolling->readout) << "\n";
  } else {
    out << "shutter: global\n";
  }
  return out.str();
}

}  // namespace

std::string eurocSensorYaml(const DatasetCamera& mount, const RigSpec& rig, const Camera& camera, double intervalS) {
  if (const auto* lens = dynamic_cast<const LensCamera*>(&camera)) return lensSensorYaml(mount, *lens, intervalS) + shutterYaml(rig);
  const CentralModel model = centralModelOf(camera);
  const MeiIntrinsics& k = model.intrinsics;
  // The camera's place on a level robot standing at the origin (the body frame is the robot's), in
  // the frame of the rig's central model: its own, or its best fit's.
  const Rigid bodyFromSensor = worldFromModelCamera(CameraPlacement(RobotPose{}, BodyVelocity{}, mount.mount), camera);

  std::ostringstream out;
  out << "# EuRoC/ASL camera sensor written by omnicam (docs/dataset-format.md, \"EuRoC/ASL layout\").\n"
      << "# Body frame: the robot's (origin on the floor, x forward, y left, z up). Sensor frame: X forward,\n"
      << "# Y right, Z down at the mirror's effective viewpoint F' (intrinsics/*.yaml). Timestamps: exposure start.\n"
      << "# camera_model omni: the unified (Mei) model, intrinsics [xi, fu, fv, pu, pv]; fv is negative on\n"
      << "# purpose (the catadioptric image is a mirror image). Pixel centres are integers.\n";
  if (model.approximation)
    out << "# APPROXIMATE: this rig has no exact central model; these are its best-fit model's intrinsics and\n"
        << "# frame (intrinsics/opencv.yaml states the residuals; intrinsics/rays.exr the exact rays).\n";
  out << "sensor_type: camera\n"
      << "comment: omnicam catadioptric camera " << mount.name << "\n"
      << "T_BS:\n  cols: 4\n  rows: 4\n  data: [";
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out << yamlFloat(bodyFromSensor.matrix()(r, c)) << (r == 3 && c == 3 ? "]\n" : ", ");
  out << "rate_hz: " << yamlFloat(1.0 / intervalS) << "\n"
      << "resolution: [" << camera.width() << ", " << camera.height() << "]\n"
      << "camera_model: omni\n"
      << "intrinsics: [" << yamlFloat(k.xi) << ", " << yamlFloat(k.gammaX) << ", " << yamlFloat(k.gammaY) << ", "
      << yamlFloat(k.cx) << ", " << yamlFloat(k.cy) << "]\n"
      << "distortion_model: radial-tangential\n"
      << "distortion_coefficients: [" << yamlFloat(k.lens.k1) << ", " << yamlFloat(k.lens.k2) << ", "
      << yamlFloat(k.lens.p1) << ", " << yamlFloat(k.lens.p2) << "]\n";
  return out.str() + shutterYaml(rig);
}

}  // namespace omnicam
