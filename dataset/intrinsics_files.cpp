#include "intrinsics_files.h"

#include <filesystem>
#include <functional>
#include <opencv2/core.hpp>
#include <sstream>

#include "atomic_file.h"
#include "number_format.h"

namespace omnicam {

namespace {

constexpr const char* kSignNote =
    "gamma_y (fv) is negative on purpose: the catadioptric image is a mirror image of the world; with "
    "the camera frame X forward, Y right, Z down at the mirror's effective viewpoint F' (right-handed), "
    "v grows along -Y. Pixel centres are integers (cx = W/2 - 0.5).";

// cv::FileStorage writes in memory; every number it writes round-trips (%.17g).
std::string fileStorageText(const std::function<void(cv::FileStorage&)>& write) {
  cv::FileStorage fs("intrinsics.yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  write(fs);
  return fs.releaseAndGetString();
}

}  // namespace

std::string openCvIntrinsicsYaml(const OmniCamera& camera) {
  const OpenCvIntrinsics k = camera.openCvIntrinsics();
  return fileStorageText([&](cv::FileStorage& fs) {
    fs.writeComment("cv::omnidir (Mei unified model) intrinsics written by omnicam: load with cv::FileStorage, "
                    "use with cv::omnidir::projectPoints / undistortImage.");
    fs.writeComment(kSignNote);
    fs << "camera_model" << "omnidir";
    fs << "image_width" << camera.width() << "image_height" << camera.height();
    fs << "K" << (cv::Mat_<double>(3, 3) << k.gamma_x, 0.0, k.cx, 0.0, k.gamma_y, k.cy, 0.0, 0.0, 1.0);
    fs << "xi" << k.xi;
    fs << "D" << cv::Mat_<double>(1, 4, 0.0);
    fs << "rim_radius_px" << camera.rimRadius();
  });
}

std::string camodocalIntrinsicsYaml(const std::string& name, const OmniCamera& camera) {
  const OpenCvIntrinsics k = camera.openCvIntrinsics();
  return fileStorageText([&](cv::FileStorage& fs) {
    fs.writeComment("camodocal MEI camera written by omnicam (CameraFactory::generateCameraFromYamlFile).");
    fs.writeComment(kSignNote);
    fs << "model_type" << "MEI" << "camera_name" << name;
    fs << "image_width" << camera.width() << "image_height" << camera.height();
    fs << "mirror_parameters" << "{" << "xi" << k.xi << "}";
    fs << "distortion_parameters" << "{" << "k1" << 0.0 << "k2" << 0.0 << "p1" << 0.0 << "p2" << 0.0 << "}";
    fs << "projection_parameters" << "{" << "gamma1" << k.gamma_x << "gamma2" << k.gamma_y << "u0" << k.cx
       << "v0" << k.cy << "}";
  });
}

std::string kalibrIntrinsicsYaml(const std::string& name, const OmniCamera& camera) {
  const OpenCvIntrinsics k = camera.openCvIntrinsics();
  std::ostringstream out;
  out << "# Kalibr camchain entry written by omnicam: camera_model omni (Mei unified model),\n"
      << "# intrinsics [xi, fu, fv, pu, pv], radtan distortion (none).\n"
      << "# " << kSignNote << "\n"
      << "cam0:\n"
      << "  camera_model: omni\n"
      << "  intrinsics: [" << roundTrip(k.xi) << ", " << roundTrip(k.gamma_x) << ", " << roundTrip(k.gamma_y) << ", "
      << roundTrip(k.cx) << ", " << roundTrip(k.cy) << "]\n"
      << "  distortion_model: radtan\n"
      << "  distortion_coeffs: [0.0, 0.0, 0.0, 0.0]\n"
      << "  resolution: [" << camera.width() << ", " << camera.height() << "]\n"
      << "  rostopic: /omnicam/" << name << "/image_raw\n";
  return out.str();
}

void writeIntrinsicsFiles(const std::string& dir, const std::string& name, const OmniCamera& camera) {
  const std::filesystem::path folder(dir);
  writeTextAtomically((folder / "opencv.yaml").string(), openCvIntrinsicsYaml(camera));
  writeTextAtomically((folder / "kalibr.yaml").string(), kalibrIntrinsicsYaml(name, camera));
  writeTextAtomically((folder / "camodocal.yaml").string(), camodocalIntrinsicsYaml(name, camera));
}

}  // namespace omnicam
