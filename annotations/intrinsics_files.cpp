#include "intrinsics_files.h"

#include <filesystem>
#include <functional>
#include <opencv2/core.hpp>
#include <sstream>

#include "atomic_file.h"
#include "errors.h"
#include "lens_camera.h"
#include "lens_intrinsics_files.h"
#include "make_camera.h"
#include "number_format.h"
#include "opencv_yaml.h"

namespace omnicam {

namespace {

constexpr const char* kSignNote =
    "gamma_y (fv) is negative on purpose: the catadioptric image is a mirror image of the world; with "
    "the camera frame X forward, Y right, Z down at the mirror's effective viewpoint F' (right-handed), "
    "v grows along -Y. Pixel centres are integers (cx = W/2 - 0.5).";

// What the files say of a model that is not exact (one line; empty for an exact model).
std::string approximationNote(const CentralModel& model) {
  if (!model.approximation) return "";
  std::ostringstream out;
  out << "APPROXIMATE: no unified (Mei) model describes this rig exactly (its mirror shape or camera, "
         "rig.mirror / rig.camera); this is its best-fit central model. Reprojection rms / max px:";
  for (const auto& r : model.approximation->residuals)
    out << " " << (r.distanceM == 0.0 ? std::string("infinity") : roundTrip(r.distanceM) + " m") << " "
        << roundTrip(r.rmsPx) << " / " << roundTrip(r.maxPx) << ";";
  out << " the exact ray of every pixel is in rays.exr.";
  return out.str();
}

std::string distortionText(const LensDistortion& l) {
  return yamlFloatList({l.k1, l.k2, l.p1, l.p2});
}

}  // namespace

std::string openCvIntrinsicsYaml(const Camera& camera) {
  const CentralModel model = centralModelOf(camera);
  const MeiIntrinsics& k = model.intrinsics;
  return fileStorageText([&](cv::FileStorage& fs) {
    fs.writeComment("cv::omnidir (Mei unified model) intrinsics written by omnicam: load with cv::FileStorage, "
                    "use with cv::omnidir::projectPoints / undistortImage.");
    fs.writeComment(kSignNote);
    if (model.approximation)
      fs.writeComment(approximationNote(model) +
                      " The fitted camera frame: camera_from_rig_R, camera_from_rig_t map a point of the rig's "
                      "camera frame (poses.tum) into it.");
    fs << "camera_model" << "omnidir";
    fs << "exact" << static_cast<int>(!model.approximation);
    fs << "image_width" << camera.width() << "image_height" << camera.height();
    fs << "K" << (cv::Mat_<double>(3, 3) << k.gammaX, 0.0, k.cx, 0.0, k.gammaY, k.cy, 0.0, 0.0, 1.0);
    fs << "xi" << k.xi;
    fs << "D" << (cv::Mat_<double>(1, 4) << k.lens.k1, k.lens.k2, k.lens.p1, k.lens.p2);
    if (model.rimRadiusPx) fs << "rim_radius_px" << *model.rimRadiusPx;
    if (model.approximation) {
      // The rig's camera frame is unifiedCameraFromViewpoint() applied to the viewpoint frame.
      const Rigid fromRig = model.approximation->cameraFromViewpoint * unifiedCameraFromViewpoint().inverse();
      cv::Mat r(3, 3, CV_64F), t(3, 1, CV_64F);
      for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 3; ++col) r.at<double>(row, col) = fromRig.linear()(row, col);
        t.at<double>(row) = fromRig.translation()[row];
      }
      fs << "camera_from_rig_R" << r << "camera_from_rig_t" << t;
    }
  });
}

std::string camodocalIntrinsicsYaml(const std::string& name, const Camera& camera) {
  const CentralModel model = centralModelOf(camera);
  const MeiIntrinsics& k = model.intrinsics;
  return fileStorageText([&](cv::FileStorage& fs) {
    fs.writeComment("camodocal MEI camera written by omnicam (CameraFactory::generateCameraFromYamlFile).");
    fs.writeComment(kSignNote);
    if (model.approximation) fs.writeComment(approximationNote(model));
    fs << "model_type" << "MEI" << "camera_name" << name;
    fs << "image_width" << camera.width() << "image_height" << camera.height();
    fs << "mirror_parameters" << "{" << "xi" << k.xi << "}";
    fs << "distortion_parameters" << "{" << "k1" << k.lens.k1 << "k2" << k.lens.k2 << "p1" << k.lens.p1 << "p2"
       << k.lens.p2 << "}";
    fs << "projection_parameters" << "{" << "gamma1" << k.gammaX << "gamma2" << k.gammaY << "u0" << k.cx
       << "v0" << k.cy << "}";
  });
}

std::string kalibrIntrinsicsYaml(const std::string& name, const Camera& camera) {
  const CentralModel model = centralModelOf(camera);
  const MeiIntrinsics& k = model.intrinsics;
  std::ostringstream out;
  out << "# Kalibr camchain entry written by omnicam: camera_model omni (Mei unified model),\n"
      << "# intrinsics [xi, fu, fv, pu, pv], radtan distortion [k1, k2, p1, p2].\n"
      << "# " << kSignNote << "\n";
  if (model.approximation) out << "# " << approximationNote(model) << "\n";
  out << "cam0:\n"
      << "  camera_model: omni\n"
      << "  intrinsics: " << yamlFloatList({k.xi, k.gammaX, k.gammaY, k.cx, k.cy}) << "\n"
      << "  distortion_model: radtan\n"
      << "  distortion_coeffs: " << distortionText(k.lens) << "\n"
      << "  resolution: [" << camera.width() << ", " << camera.height() << "]\n"
      << "  rostopic: /" << name << "/image_raw\n";  // the calibration bag's topic (calibration_bag.h)
  return out.str();
}

Rigid worldFromModelCamera(const CameraPlacement& placement, const Camera& camera) {
  if (dynamic_cast<const LensCamera*>(&camera)) return placement.worldFromCamera(camera.rig());
  return placement.worldFromViewpoint(camera.rig()) * centralModelOf(camera).cameraFromViewpoint().inverse();
}

std::string kalibrCamchainYaml(const std::vector<KalibrChainCamera>& cameras) {
  std::ostringstream out;
  out << "# Kalibr camchain written by omnicam for its calibration bag (kalibr.bag), every camera's images on its rostopic.\n"
      << "# A mirror camera's images are flipped top to bottom in the bag (a catadioptric image is a mirror image):\n"
      << "# its omni intrinsics [xi, fu, fv, pu, pv] describe the flipped image, fv > 0, pv = H - 1 - cy of intrinsics/kalibr.yaml.\n";
  for (size_t n = 0; n < cameras.size(); ++n) {
    const KalibrChainCamera& c = cameras[n];
    KalibrLens model;
    if (const auto* lens = dynamic_cast<const LensCamera*>(c.camera)) {
      const std::optional<KalibrLens> kalibr = kalibrLensOf(lens->lens().model);
      if (!kalibr) throw InputError("camera " + quote(c.name) + ": Kalibr has no camera model for its lens (" + lensModelName(lens->lens().model) + ")");
      model = *kalibr;
    } else {
      const CentralModel central = centralModelOf(*c.camera);
      const MeiIntrinsics& k = central.intrinsics;
      if (central.approximation) out << "# cam" << n << " (" << c.name << "): " << approximationNote(central) << "\n";
      model = {"omni", {k.xi, k.gammaX, -k.gammaY, k.cx, c.camera->height() - 1.0 - k.cy}, "radtan",
               {k.lens.k1, k.lens.k2, k.lens.p1, k.lens.p2}};
    }
    out << "cam" << n << ":\n"
        << "  camera_model: " << model.cameraModel << "\n"
        << "  intrinsics: " << yamlFloatList(model.intrinsics) << "\n"
        << "  distortion_model: " << model.distortionModel << "\n"
        << "  distortion_coeffs: " << yamlFloatList(model.coefficients) << "\n"
        << "  resolution: [" << c.camera->width() << ", " << c.camera->height() << "]\n"
        << "  rostopic: /" << c.name << "/image_raw\n";
    if (n > 0) {
      const Eigen::Matrix4d t = (c.worldFromCamera.inverse() * cameras[n - 1].worldFromCamera).matrix();
      out << "  T_cn_cnm1:\n";
      for (int row = 0; row < 4; ++row) out << "  - " << yamlFloatList({t(row, 0), t(row, 1), t(row, 2), t(row, 3)}) << "\n";
    }
  }
  return out.str();
}

std::vector<IntrinsicsFile> intrinsicsFiles(const std::string& name, const Camera& camera) {
  if (const auto* lens = dynamic_cast<const LensCamera*>(&camera)) {
    std::vector<IntrinsicsFile> files;
    const auto add = [&](const char* kind, const char* fileName, const std::optional<std::string>& text) {
      if (text) files.push_back({kind, fileName, *text});
    };
    add("intrinsics_opencv", "opencv.yaml", openCvLensYaml(*lens));
    add("intrinsics_kalibr", "kalibr.yaml", kalibrLensYaml(name, *lens));
    add("intrinsics_camodocal", "camodocal.yaml", camodocalLensYaml(name, *lens));
    return files;
  }
  return {{"intrinsics_opencv", "opencv.yaml", openCvIntrinsicsYaml(camera)},
          {"intrinsics_kalibr", "kalibr.yaml", kalibrIntrinsicsYaml(name, camera)},
          {"intrinsics_camodocal", "camodocal.yaml", camodocalIntrinsicsYaml(name, camera)}};
}

void writeIntrinsicsFiles(const std::string& dir, const std::string& name, const Camera& camera) {
  const std::filesystem::path folder(dir);
  for (const IntrinsicsFile& file : intrinsicsFiles(name, camera)) writeTextAtomically((folder / file.fileName).string(), file.text);
}

}  // namespace omnicam
