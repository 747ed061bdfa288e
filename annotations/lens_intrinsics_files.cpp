#include "lens_intrinsics_files.h"

#include <functional>
#include <opencv2/core.hpp>
#include <sstream>

#include "number_format.h"
#include "opencv_yaml.h"

namespace omnicam {

namespace {

constexpr const char* kFrameNote =
    "Camera frame: X right, Y down, Z along the optical axis, at the lens' centre of projection; pixel centres "
    "are integers (cx = (W - 1)/2 at the image centre).";

cv::Mat cameraMatrix(double fx, double fy, double cx, double cy) {
  return (cv::Mat_<double>(3, 3) << fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0);
}

}  // namespace

std::optional<KannalaBrandt> asKannalaBrandt(const LensModel& model) {
  if (const auto* kb = std::get_if<KannalaBrandt>(&model)) return *kb;
  if (const auto* f = std::get_if<FThetaLens>(&model); f && f->kind == FThetaLens::Kind::Equidistant)
    return KannalaBrandt{f->f, f->f, f->cx, f->cy, {0.0, 0.0, 0.0, 0.0}, f->maxThetaRad};
  return std::nullopt;
}

const PinholeRadTan* asFourCoefficientPinhole(const LensModel& model) {
  const auto* p = std::get_if<PinholeRadTan>(&model);
  return p && p->distortion.k3 == 0.0 ? p : nullptr;
}

std::optional<KalibrLens> kalibrLensOf(const LensModel& model) {
  if (const auto kb = asKannalaBrandt(model))
    return KalibrLens{"pinhole", {kb->fx, kb->fy, kb->cx, kb->cy}, "equidistant", {kb->k[0], kb->k[1], kb->k[2], kb->k[3]}};
  if (const auto* ds = std::get_if<DoubleSphere>(&model))
    return KalibrLens{"ds", {ds->xi, ds->alpha, ds->fx, ds->fy, ds->cx, ds->cy}, "none", {}};
  if (const auto* eucm = std::get_if<ExtendedUnified>(&model))
    return KalibrLens{"eucm", {eucm->alpha, eucm->beta, eucm->fx, eucm->fy, eucm->cx, eucm->cy}, "none", {}};
  if (const auto* p = asFourCoefficientPinhole(model)) {
    const LensDistortion& d = p->distortion;
    return KalibrLens{"pinhole", {p->fx, p->fy, p->cx, p->cy}, "radtan", {d.k1, d.k2, d.p1, d.p2}};
  }
  return std::nullopt;
}

std::optional<std::string> openCvLensYaml(const LensCamera& camera) {
  const LensModel& model = camera.lens().model;
  if (const auto kb = asKannalaBrandt(model)) {
    return fileStorageText([&](cv::FileStorage& fs) {
      fs.writeComment("cv::fisheye (Kannala-Brandt) intrinsics written by omnicam: load with cv::FileStorage, use with "
                      "cv::fisheye::projectPoints / undistortImage. OpenCV images directions up to 90 degrees from the axis "
                      "only; the lens sees up to max_theta_deg.");
      fs.writeComment(kFrameNote);
      fs << "camera_model" << "fisheye";
      fs << "image_width" << camera.width() << "image_height" << camera.height();
      fs << "K" << cameraMatrix(kb->fx, kb->fy, kb->cx, kb->cy);
      fs << "D" << (cv::Mat_<double>(1, 4) << kb->k[0], kb->k[1], kb->k[2], kb->k[3]);
      fs << "max_theta_deg" << degrees(kb->maxThetaRad);
    });
  }
  if (const auto* p = std::get_if<PinholeRadTan>(&model)) {
    const LensDistortion& d = p->distortion;
    return fileStorageText([&](cv::FileStorage& fs) {
      fs.writeComment("OpenCV pinhole intrinsics written by omnicam: use with cv::projectPoints / undistort.");
      fs.writeComment(kFrameNote);
      fs << "camera_model" << "pinhole";
      fs << "image_width" << camera.width() << "image_height" << camera.height();
      fs << "K" << cameraMatrix(p->fx, p->fy, p->cx, p->cy);
      fs << "D" << (cv::Mat_<double>(1, 5) << d.k1, d.k2, d.p1, d.p2, d.k3);
    });
  }
  return std::nullopt;
}

std::optional<std::string> kalibrLensYaml(const std::string& name, const LensCamera& camera) {
  const LensModel& model = camera.lens().model;
  const std::optional<KalibrLens> kalibr = kalibrLensOf(model);
  if (!kalibr) return std::nullopt;
  std::ostringstream out;
  out << "# Kalibr camchain entry written by omnicam (" << lensModelName(model) << " lens).\n"
      << "# " << kFrameNote << "\n"
      << "cam0:\n"
      << "  camera_model: " << kalibr->cameraModel << "\n"
      << "  intrinsics: " << yamlFloatList(kalibr->intrinsics) << "\n"
      << "  distortion_model: " << kalibr->distortionModel << "\n"
      << "  distortion_coeffs: " << yamlFloatList(kalibr->coefficients) << "\n"
      << "  resolution: [" << camera.width() << ", " << camera.height() << "]\n"
      << "  rostopic: /" << name << "/image_raw\n";
  return out.str();
}

std::optional<std::string> camodocalLensYaml(const std::string& name, const LensCamera& camera) {
  const LensModel& model = camera.lens().model;
  if (const auto kb = asKannalaBrandt(model)) {
    return fileStorageText([&](cv::FileStorage& fs) {
      fs.writeComment("camodocal KANNALA_BRANDT camera written by omnicam (its k2..k5 are OpenCV's k1..k4).");
      fs.writeComment(kFrameNote);
      fs << "model_type" << "KANNALA_BRANDT" << "camera_name" << name;
      fs << "image_width" << camera.width() << "image_height" << camera.height();
      fs << "projection_parameters" << "{" << "k2" << kb->k[0] << "k3" << kb->k[1] << "k4" << kb->k[2] << "k5" << kb->k[3]
         << "mu" << kb->fx << "mv" << kb->fy << "u0" << kb->cx << "v0" << kb->cy << "}";
    });
  }
  if (const auto* p = asFourCoefficientPinhole(model)) {
    return fileStorageText([&](cv::FileStorage& fs) {
      fs.writeComment("camodocal PINHOLE camera written by omnicam.");
      fs.writeComment(kFrameNote);
      fs << "model_type" << "PINHOLE" << "camera_name" << name;
      fs << "image_width" << camera.width() << "image_height" << camera.height();
      fs << "distortion_parameters" << "{" << "k1" << p->distortion.k1 << "k2" << p->distortion.k2 << "p1" << p->distortion.p1
         << "p2" << p->distortion.p2 << "}";
      fs << "projection_parameters" << "{" << "fx" << p->fx << "fy" << p->fy << "cx" << p->cx << "cy" << p->cy << "}";
    });
  }
  return std::nullopt;
}

}  // namespace omnicam
