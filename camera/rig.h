#pragma once
// The camera rig on the robot. Its frames (the chain world ← robot ← viewpoint ← camera is
// composed by motion/placement.h):
//   viewpoint: origin at F' = robot origin + (0, 0, height), robot axes — on a level rig; tiltDeg
//              turns it about the floor point below (robotFromViewpoint).
//   camera:    unified-model frame at F' (see omni_camera.h).
//   pinhole:   the physical camera below the mirror (physical_camera.h): origin at its pinhole,
//              x = image u, y = image v, z = optical axis; the ideal pinhole sits at F with its
//              axes along robot x, y, z.
#include <array>
#include <string>
#include <variant>

#include "geometry.h"
#include "overloaded.h"
#include "lens_models.h"
#include "mirror_shape.h"
#include "omni_camera.h"
#include "shutter.h"

namespace omnicam {

// The physical camera below the mirror, as built rather than as designed. All zero: the ideal
// pinhole at the mirror's outer focus F, looking straight up, distortion-free.
struct CameraMount {
  std::array<double, 3> offsetMm{0.0, 0.0, 0.0};     // pinhole minus its ideal position, robot axes
  std::array<double, 3> rotationDeg{0.0, 0.0, 0.0};  // about the pinhole: axes = Rx·Ry·Rz · ideal axes
  LensDistortion distortion;
  std::array<double, 2> principalPointOffsetPx{0.0, 0.0};
  bool ideal() const { return *this == CameraMount{}; }
  bool operator==(const CameraMount&) const = default;
};

// A camera without a mirror (issue #37): a central lens model (lens_models.h) whose centre of
// projection is the viewpoint F', looking along robot +x with its image's right along robot −y
// and its image's down along robot −z, then turned by rotationDeg = [roll, pitch, yaw] about
// robot x, y, z: viewpointFromLens = Rz(yaw)·Ry(pitch)·Rx(roll) · that forward camera (pitch −90
// looks straight up, +90 straight down).
struct LensCameraSpec {
  LensModel model;
  int width = 0, height = 0;
  std::array<double, 3> rotationDeg{0.0, 0.0, 0.0};
  bool operator==(const LensCameraSpec&) const = default;
};
Eigen::Matrix3d viewpointFromLens(const LensCameraSpec& lens);
// The lens imaging `width` pixels across, its height keeping the aspect exactly: InputError
// naming `what` (the width's name) and the widths that do, for one that does not (or a height
// outside the limits).
LensCameraSpec resizedLens(const LensCameraSpec& lens, int width, const std::string& what = "image size");

// InputError("<what>: must be in [8, 16384] (got N)") for an image size outside the limits.
void checkImageSize(int size, const std::string& what);

// A camera that sees the scene in a mirror: the mirror, and the physical camera below it that
// images it onto a square image.
struct MirrorRig {
  MirrorShapeSpec shape;  // the hyperboloid unless it says otherwise
  CameraMount mount;      // the physical camera's misalignment and lens
  int imageSize = 360;    // square image, pixels
  bool operator==(const MirrorRig&) const = default;

  MirrorShape shapeKind() const { return mirrorShapeOf(shape); }
  // The hyperboloid's parameters; InputError("rig.mirror.shape: this needs the hyperboloid
  // (<why>); a <shape> mirror ...") for another shape.
  const HyperboloidMirror& hyperboloid(const std::string& why = "the central model's mirror") const;
  HyperboloidMirror& hyperboloid(const std::string& why = "the central model's mirror");
  // True when the camera sits exactly where the mirror was designed for: the image is then the
  // central (Mei) model's, in closed form.
  bool ideal() const { return std::holds_alternative<HyperboloidMirror>(shape) && mount.ideal(); }
  // The hyperboloid's central model, as its mirror and framing give it whatever the mount says.
  OmniCamera idealCamera() const;
};

// What a rig's camera is: a mirror with its camera, or a lens without one. Code outside camera/
// asks RigSpec, or visits this (std::visit with Overloaded, overloaded.h), rather than testing which it holds.
using CameraKind = std::variant<MirrorRig, LensCameraSpec>;

struct RigSpec {
  double height = 0.40;            // F' above the floor, metres
  Shutter shutter;                 // an instant unless it says otherwise (docs/motion.md)
  // The whole rig (mirror and camera) tilted on its mount, as a robot rocking on its wheels
  // tilts it, about the point on the floor below F': robotFromViewpoint = Rx(roll)·Ry(pitch)·
  // T(0, 0, height), i.e. roll about the mount's x axis, then pitch about the rolled y axis.
  // Level unless it says otherwise.
  std::array<double, 2> tiltDeg{0.0, 0.0};
  CameraKind kind;                 // the hyperboloid rig unless it says otherwise
  bool tilted() const { return tiltDeg != std::array<double, 2>{0.0, 0.0}; }

  int imageWidth() const;
  int imageHeight() const;
  // The image's pixels as messages count them: "360^2" for a mirror rig's square image, "640x480"
  // for a lens'.
  std::string imageSizeText() const;

  // The camera's own parameters. mirrorRig(): InputError("<what>: a lens camera (rig.lens) has
  // no mirror") for a lens rig; lensCamera(): std::bad_variant_access for a mirror rig (only
  // camera/'s LensCamera, built for lens rigs, asks).
  const MirrorRig& mirrorRig(const std::string& what = "rig") const;
  MirrorRig& mirrorRig(const std::string& what = "rig");
  const LensCameraSpec& lensCamera() const { return std::get<LensCameraSpec>(kind); }
  LensCameraSpec& lensCamera() { return std::get<LensCameraSpec>(kind); }

  // The one definition of rig equality: every cache keyed on a rig compares with it, so a new
  // field can never leave a stale table behind.
  bool operator==(const RigSpec&) const = default;

  // True for a mirror rig whose camera sits exactly where the mirror was designed for.
  bool ideal() const;
  // The same camera imaging at another size: the focal length scales with the image, and so does
  // the principal point's offset (given in pixels of imageSize), so only the pixel size changes.
  // A lens camera's `size` is its width; its height keeps the aspect exactly (else InputError:
  // one scale for both axes keeps its pixels square).
  // InputError unless `size` is within limits::kMinImageSize … kMaxImageSize; `what` names the
  // size in messages (the CLI's "--size", a spec's file and field).
  RigSpec resized(int size, const std::string& what = "image size") const;
  // What shapes the camera's rays in the viewpoint frame: this rig without its shutter (when
  // rays are taken) and its tilt (where the viewpoint frame sits on the robot).
  RigSpec imaging() const {
    RigSpec r = *this;
    r.shutter = {};
    r.tiltDeg = {0.0, 0.0};
    return r;
  }
  // This rig with its camera put back where it belongs (a mirror rig's mount made ideal; a lens
  // is where its rotation says).
  RigSpec idealized() const;

  // The central model of this rig; InputError for a rig whose camera is not ideal, which no
  // central model describes exactly (make_camera.h gives the camera of any rig).
  OmniCamera camera() const;
};

// The last link of the frame chain (motion/placement.h composes the chain): the camera frame of
// this rig's camera, the unified model's (unifiedCameraFromViewpoint, omni_camera.h) for a mirror
// rig, or a lens camera's OpenCV frame (X image right, Y image down, Z its optical axis;
// viewpointFromLens).
Rigid cameraFromViewpoint(const RigSpec& rig);

}  // namespace omnicam
