#include "rig.h"

#include <numeric>
#include <utility>

#include "errors.h"
#include "input_limits.h"

namespace omnicam {

void checkImageSize(int size, const std::string& what) {
  if (size < limits::kMinImageSize || size > limits::kMaxImageSize)
    throw InputError(what + ": must be in [" + std::to_string(limits::kMinImageSize) + ", " +
                     std::to_string(limits::kMaxImageSize) + "] (got " + std::to_string(size) + ")");
}

const HyperboloidMirror& MirrorRig::hyperboloid(const std::string& why) const {
  if (const auto* h = std::get_if<HyperboloidMirror>(&shape)) return *h;
  throw InputError("rig.mirror.shape: this needs the hyperboloid (" + why + "); a " + mirrorShapeName(shape) +
                   " mirror is traced physically only");
}

HyperboloidMirror& MirrorRig::hyperboloid(const std::string& why) {
  return const_cast<HyperboloidMirror&>(std::as_const(*this).hyperboloid(why));
}

OmniCamera MirrorRig::idealCamera() const {
  const HyperboloidMirror& h = hyperboloid();
  return {h.mirror(), imageSize, imageSize, h.rimElevationDeg, h.framingElevationDeg};
}

int RigSpec::imageWidth() const {
  return std::visit(Overloaded{[](const MirrorRig& m) { return m.imageSize; }, [](const LensCameraSpec& l) { return l.width; }},
                    kind);
}

int RigSpec::imageHeight() const {
  return std::visit(Overloaded{[](const MirrorRig& m) { return m.imageSize; }, [](const LensCameraSpec& l) { return l.height; }},
                    kind);
}

std::string RigSpec::imageSizeText() const {
  return std::visit(Overloaded{[](const MirrorRig& m) { return std::to_string(m.imageSize) + "^2"; },
                               [](const LensCameraSpec& l) { return std::to_string(l.width) + "x" + std::to_string(l.height); }},
                    kind);
}

const MirrorRig& RigSpec::mirrorRig(const std::string& what) const {
  if (const MirrorRig* mirror = std::get_if<MirrorRig>(&kind)) return *mirror;
  throw InputError(what + ": a lens camera (rig.lens) has no mirror");
}

MirrorRig& RigSpec::mirrorRig(const std::string& what) {
  return const_cast<MirrorRig&>(std::as_const(*this).mirrorRig(what));
}

bool RigSpec::ideal() const {
  return std::visit(Overloaded{[](const MirrorRig& m) { return m.ideal(); }, [](const LensCameraSpec&) { return false; }},
                    kind);
}

RigSpec RigSpec::resized(int size, const std::string& what) const {
  checkImageSize(size, what);
  RigSpec r = *this;
  std::visit(Overloaded{[&](MirrorRig& m) {
                          const double scale = static_cast<double>(size) / m.imageSize;
                          m.imageSize = size;
                          for (double& offset : m.mount.principalPointOffsetPx) offset *= scale;
                        },
                        [&](LensCameraSpec& l) { l = resizedLens(l, size, what); }},
             r.kind);
  return r;
}

RigSpec RigSpec::idealized() const {
  RigSpec r = *this;
  std::visit(Overloaded{[](MirrorRig& m) { m.mount = {}; }, [](LensCameraSpec&) {}}, r.kind);
  return r;
}

OmniCamera RigSpec::camera() const {
  const MirrorRig* mirror = std::get_if<MirrorRig>(&kind);
  if (mirror) (void)mirror->hyperboloid("the central (Mei) model's mirror");
  if (!ideal())  // a lens camera included: no central (Mei) model describes it
    throw InputError(
        "rig.camera: this needs the central (Mei) model, which describes only the ideal camera "
        "(zero offset, rotation, distortion and principal point offset)");
  return mirror->idealCamera();
}

Rigid cameraFromViewpoint(const RigSpec& rig) {
  return std::visit(Overloaded{[](const MirrorRig&) { return unifiedCameraFromViewpoint(); },
                               [](const LensCameraSpec& lens) {
                                 Rigid t = Rigid::Identity();
                                 t.linear() = viewpointFromLens(lens).transpose();
                                 return t;
                               }},
                    rig.kind);
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
