#include "rig_fields.h"

#include <array>
#include <string>
#include <vector>

#include "errors.h"
#include "input_limits.h"
#include "lens_fields.h"
#include "make_camera.h"
#include "mirror_surface.h"
#include "number_format.h"

namespace omnicam {

namespace {

// The physical camera block (rig.h: CameraMount); absent or all zero is the ideal camera.
CameraMount readCameraMount(JsonFields camera) {
  CameraMount mount;
  const auto triple = [&](const char* key, const JsonFields::Range& range) {
    const std::vector<double> v = camera.numbers(key, {0.0, 0.0, 0.0}, range);
    return std::array<double, 3>{v[0], v[1], v[2]};
  };
  mount.offsetMm = triple("offset_mm", {-limits::kMaxCameraOffsetMm, limits::kMaxCameraOffsetMm, false, "mm"});
  mount.rotationDeg = triple("rotation_deg", {-limits::kMaxCameraRotationDeg, limits::kMaxCameraRotationDeg, false, "degrees"});
  if (auto lens = camera.optionalObject("distortion")) {
    const JsonFields::Range radial{-limits::kMaxDistortion, limits::kMaxDistortion};
    const JsonFields::Range tangential{-limits::kMaxTangentialDistortion, limits::kMaxTangentialDistortion};
    mount.distortion.k1 = lens->number("k1", 0.0, radial);
    mount.distortion.k2 = lens->number("k2", 0.0, radial);
    mount.distortion.p1 = lens->number("p1", 0.0, tangential);
    mount.distortion.p2 = lens->number("p2", 0.0, tangential);
    mount.distortion.k3 = lens->number("k3", 0.0, radial);
    lens->finish();
  }
  const std::vector<double> pp = camera.numbers(
      "principal_point_offset_px", {0.0, 0.0},
      {-limits::kMaxPrincipalPointOffsetPx, limits::kMaxPrincipalPointOffsetPx, false, "pixels"});
  mount.principalPointOffsetPx = {pp[0], pp[1]};
  camera.finish();
  return mount;
}

// rig.shutter (shutter.h): absent is an instant.
Shutter readShutter(JsonFields fields) {
  Shutter shutter;
  shutter.exposureS = fields.number("exposure_s", 0.0, {0.0, limits::kMaxExposureS, false, "s"});
  if (auto rolling = fields.optionalObject("rolling")) {
    RollingShutter r;
    r.lineTimeUs = rolling->number("line_time_us", {0.0, limits::kMaxLineTimeUs, true, "microseconds"});
    const std::string readout = rolling->string("readout", readoutName(r.readout));
    const auto named = readoutNamed(readout);
    if (!named) rolling->fail("readout", "must be top-to-bottom, bottom-to-top, left-to-right or right-to-left (got " + quote(readout) + ")");
    r.readout = *named;
    rolling->finish();
    shutter.rolling = r;
  }
  shutter.timeSamples = fields.integer("time_samples", 0, 0, limits::kMaxTimeSamples);
  fields.finish();
  return shutter;
}

// rig.mirror: the shape and its parameters (docs/scene-format.md); each shape takes only its own.
void readMirror(JsonFields& mirror, MirrorRig& spec, double height) {
  const std::string shape = mirror.string("shape", "hyperboloid");
  MirrorShapeSpec& s = spec.shape;
  const JsonFields::Range size{limits::kMinMirrorSize, limits::kMaxMirrorSize, false, "m"};
  const auto rimElevation = [&] {
    spec.rimElevationDeg = mirror.number("rim_elevation_deg", spec.rimElevationDeg);
    if (!(spec.rimElevationDeg > -60.0 && spec.rimElevationDeg < 80.0))
      mirror.fail("rim_elevation_deg", "must be in (-60, 80) degrees");
  };
  // The ideal camera's distance below the design point: above the floor, below the mirror.
  const auto cameraDistance = [&](double fallback, double below) {
    s.cameraDistance = mirror.number("camera_distance_m", fallback, {0.0, limits::kMaxCameraDistance, false, "m"});
    if (s.cameraDistance != 0.0 && !(s.cameraDistance > below))
      mirror.fail("camera_distance_m", "puts the camera on or above the mirror (it must exceed " + shortNumber(below) + " m)");
    if (!(s.cameraDistance < height))
      mirror.fail("camera_distance_m", "must be smaller than rig.height (the camera sits above the floor)");
  };
  // Another shape's field is a likely slip (a forgotten or misspelt "shape"): say so.
  const std::pair<const char*, const char*> owners[] = {
      {"k", "hyperboloid"}, {"c", "hyperboloid"}, {"h", "paraboloid"}, {"radius", "sphere"}, {"cap_angle_deg", "sphere"},
      {"half_angle_deg", "cone"}, {"rim_radius", "cone"}, {"camera_distance_m", "paraboloid, sphere and cone"}};
  const bool known = shape == "hyperboloid" || shape == "paraboloid" || shape == "sphere" || shape == "cone";
  for (const auto& [key, owner] : owners)
    if (known && mirror.has(key) && std::string(owner).find(shape) == std::string::npos)
      mirror.fail(key, std::string("belongs to the ") + owner + " shape, not to " + quote(shape) +
                           (mirror.has("shape") ? "" : " (the default; give \"shape\")"));
  if (shape == "hyperboloid") {
    spec.k = mirror.number("k", spec.k, {limits::kMinMirrorK, limits::kMaxMirrorK, true});
    spec.c = mirror.number("c", spec.c, {limits::kMinMirrorC, limits::kMaxMirrorC, false, "m"});
    if (!(spec.c < height))
      mirror.fail("c", "must be smaller than rig.height (the camera sits c below F', above the floor)");
    rimElevation();
  } else if (shape == "paraboloid") {
    s.shape = MirrorShape::Paraboloid;
    s.parabolaH = mirror.number("h", size);
    rimElevation();
    if (!(spec.rimElevationDeg < 60.0)) mirror.fail("rim_elevation_deg", "must be below 60 degrees for a paraboloid");
    cameraDistance(0.0, 0.5 * s.parabolaH);
  } else if (shape == "sphere") {
    s.shape = MirrorShape::Sphere;
    s.sphereRadius = mirror.number("radius", size);
    s.capAngleDeg = mirror.number("cap_angle_deg", 60.0, {10.0, 90.0, false, "degrees"});
    cameraDistance(mirror.number("camera_distance_m"), s.sphereRadius);
  } else if (shape == "cone") {
    s.shape = MirrorShape::Cone;
    s.coneHalfAngleDeg = mirror.number("half_angle_deg", 60.0, {10.0, 80.0, false, "degrees"});
    s.coneRimRadius = mirror.number("rim_radius", size);
    cameraDistance(mirror.number("camera_distance_m"), 0.0);
  } else {
    mirror.fail("shape", quote(shape) + " is not a mirror shape omnicam models (hyperboloid, paraboloid, sphere, cone)");
  }
  if (s.shape == MirrorShape::Sphere || s.shape == MirrorShape::Cone) {
    if (s.cameraDistance == 0.0) mirror.fail("camera_distance_m", "must be positive: a perspective camera below the mirror");
  }
  // The image is framed on the rim: the ideal camera must see it, not the mirror's edge in front
  // of it (a sphere's cap beyond its tangent circle, a paraboloid seen from too close).
  if (s.shape != MirrorShape::Hyperboloid && s.cameraDistance > 0.0) {
    const auto surface = mirrorSurfaceOf(spec);
    const Vec3 camera(0.0, 0.0, -s.cameraDistance), rim(surface->rimRadius(), 0.0, surface->rimZ());
    const auto seen = surface->firstHit(camera, rim - camera);
    if (!seen || (*seen - rim).norm() > 1e-9 * surface->rimRadius())
      mirror.fail("camera_distance_m", "hides the rim behind the mirror's edge (the image is framed on the rim): "
                                       "move the camera further away, or make the mirror's rim lower");
  }
}

// A lens camera's rig: its height, lens, shutter and tilt; a mirror's fields are refused.
RigSpec readLensRig(JsonFields& rig, RigSpec spec) {
  for (const char* mirrorOnly : {"mirror", "camera", "image"})
    if (rig.has(mirrorOnly))
      rig.fail(mirrorOnly, "a lens camera (rig.lens) has no mirror: its image size and intrinsics are rig.lens's");
  spec.kind = readLensCamera(rig.object("lens"));
  if (auto shutter = rig.optionalObject("shutter")) spec.shutter = readShutter(*shutter);
  const std::vector<double> tilt = rig.numbers("tilt_deg", {0.0, 0.0}, {-limits::kMaxRigTiltDeg, limits::kMaxRigTiltDeg, false, "degrees"});
  spec.tiltDeg = {tilt[0], tilt[1]};
  rig.finish();
  return spec;
}

}  // namespace

RigSpec readRig(JsonFields rig) {
  RigSpec spec;
  spec.height = rig.number("height", spec.height, {limits::kMinRigHeight, limits::kMaxRigHeight, false, "m"});
  if (rig.has("lens")) return readLensRig(rig, spec);
  MirrorRig& mirrorRig = spec.mirrorRig();
  if (auto mirror = rig.optionalObject("mirror")) {
    readMirror(*mirror, mirrorRig, spec.height);
    mirror->finish();
  }
  if (auto camera = rig.optionalObject("camera")) mirrorRig.mount = readCameraMount(*camera);
  if (auto shutter = rig.optionalObject("shutter")) spec.shutter = readShutter(*shutter);
  const std::vector<double> tilt = rig.numbers("tilt_deg", {0.0, 0.0}, {-limits::kMaxRigTiltDeg, limits::kMaxRigTiltDeg, false, "degrees"});
  spec.tiltDeg = {tilt[0], tilt[1]};
  if (auto image = rig.optionalObject("image")) {
    mirrorRig.imageSize = image->integer("size", mirrorRig.imageSize, limits::kMinImageSize, limits::kMaxImageSize);
    if (mirrorRig.shape.shape != MirrorShape::Hyperboloid && image->has("framing_elevation_deg"))
      image->fail("framing_elevation_deg", "only for the hyperboloid: the other shapes' images frame their rim");
    mirrorRig.framingElevationDeg = image->number("framing_elevation_deg", mirrorRig.rimElevationDeg);
    if (!(mirrorRig.framingElevationDeg > -60.0 && mirrorRig.framingElevationDeg <= mirrorRig.rimElevationDeg))
      image->fail("framing_elevation_deg", "must be in (-60, rim_elevation_deg] degrees");
    image->finish();
  } else {
    mirrorRig.framingElevationDeg = mirrorRig.rimElevationDeg;
  }
  if (!rig.has("mirror") && !(mirrorRig.c < spec.height))
    rig.fail("height", "must be larger than the mirror's c = " + shortNumber(mirrorRig.c) + " m");
  rig.finish();
  try {
    if (mirrorRig.shape.shape == MirrorShape::Hyperboloid) (void)mirrorRig.idealCamera();  // it must image the rim and framing
    (void)makeCamera(spec);    // and the camera must sit below the mirror
  } catch (const InputError& e) {
    throw InputError(showPath(rig.file()) + ": " + rig.where() + "." + e.what());
  }
  return spec;
}

}  // namespace omnicam
