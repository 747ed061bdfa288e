#include "rig.h"

#include <numeric>

#include "errors.h"
#include "input_limits.h"

namespace omnicam {

void checkImageSize(int size, const std::string& what) {
  if (size < limits::kMinImageSize || size > limits::kMaxImageSize)
    throw InputError(what + ": must be in [" + std::to_string(limits::kMinImageSize) + ", " +
                     std::to_string(limits::kMaxImageSize) + "] (got " + std::to_string(size) + ")");
}

const char* mirrorShapeName(MirrorShape shape) {
  switch (shape) {
    case MirrorShape::Hyperboloid: return "hyperboloid";
    case MirrorShape::Paraboloid: return "paraboloid";
    case MirrorShape::Sphere: return "sphere";
    case MirrorShape::Cone: return "cone";
  }
  return "?";
}

OmniCamera RigSpec::camera() const {
  if (shape.shape != MirrorShape::Hyperboloid)
    throw InputError(std::string("rig.mirror.shape: this needs the central (Mei) model of the hyperboloid; a ") +
                     mirrorShapeName(shape.shape) + " mirror is traced physically only");
  if (!ideal())
    throw InputError(
        "rig.camera: this needs the central (Mei) model, which describes only the ideal camera "
        "(zero offset, rotation, distortion and principal point offset)");
  return idealCamera();
}

Rigid cameraFromViewpoint(const RigSpec& rig) {
  if (!rig.lens) return unifiedCameraFromViewpoint();
  Rigid t = Rigid::Identity();
  t.linear() = viewpointFromLens(*rig.lens).transpose();
  return t;
}

LensCameraSpec resizedLens(const LensCameraSpec& lens, int width, const std::string& what) {
  const std::string camera = "a lens camera of " + std::to_string(lens.width) + "x" + std::to_string(lens.height);
  const int64_t scaledHeight = int64_t{lens.height} * width;
  if (scaledHeight % lens.width != 0) {
    const int64_t step = lens.width / std::gcd(lens.width, lens.height);
    throw InputError(what + ": " + camera + " keeps its aspect only at widths that are multiples of " + std::to_string(step) +
                     " (got " + std::to_string(width) + ")");
  }
  LensCameraSpec out = lens;
  out.width = width;
  out.height = static_cast<int>(scaledHeight / lens.width);
  checkImageSize(out.height, what + ": " + camera + " is " + std::to_string(out.height) + " pixels high at width " +
                                 std::to_string(width) + "; its height");
  out.model = scaledLens(lens.model, static_cast<double>(width) / lens.width);
  return out;
}

Eigen::Matrix3d viewpointFromLens(const LensCameraSpec& lens) {
  Eigen::Matrix3d forward;  // columns: image right, image down, optical axis (OpenCV's X, Y, Z)
  forward.col(0) = -Vec3::UnitY();
  forward.col(1) = -Vec3::UnitZ();
  forward.col(2) = Vec3::UnitX();
  const Eigen::Matrix3d turn = (Eigen::AngleAxisd(radians(lens.rotationDeg[2]), Vec3::UnitZ()) *
                                Eigen::AngleAxisd(radians(lens.rotationDeg[1]), Vec3::UnitY()) *
                                Eigen::AngleAxisd(radians(lens.rotationDeg[0]), Vec3::UnitX()))
                                   .toRotationMatrix();
  return turn * forward;
}

}  // namespace omnicam
