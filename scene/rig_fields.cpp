#include "rig_fields.h"

#include <array>
#include <optional>
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

// The fields another shape owns: one of them is a likely slip (a forgotten or misspelt "shape").
void refuseOtherShapesFields(JsonFields& mirror, const std::string& shape) {
  const std::pair<const char*, const char*> owners[] = {
      {"k", "hyperboloid"}, {"c", "hyperboloid"}, {"h", "paraboloid"}, {"radius", "sphere"}, {"cap_angle_deg", "sphere"},
      {"half_angle_deg", "cone"}, {"rim_radius", "cone"}, {"camera_distance_m", "paraboloid, sphere and cone"}};
  for (const auto& [key, owner] : owners)
    if (mirror.has(key) && std::string(owner).find(shape) == std::string::npos)
      mirror.fail(key, std::string("belongs to the ") + owner + " shape, not to " + quote(shape) +
                           (mirror.has("shape") ? "" : " (the default; give \"shape\")"));
}

double rimElevation(JsonFields& mirror, double fallback) {
  const double deg = mirror.number("rim_elevation_deg", fallback);
  if (!(deg > -60.0 && deg < 80.0)) mirror.fail("rim_elevation_deg", "must be in (-60, 80) degrees (got " + shortNumber(deg) + ")");
  return deg;
}

// The ideal camera's distance below the design point: above the floor, below the mirror
// (beyond `below`); 0 (orthographic) only where `fallback` is.
double cameraDistance(JsonFields& mirror, std::optional<double> fallback, double below, double height) {
  const JsonFields::Range range{0.0, limits::kMaxCameraDistance, false, "m"};
  const double d = fallback ? mirror.number("camera_distance_m", *fallback, range) : mirror.number("camera_distance_m", range);
  if (!fallback && d == 0.0) mirror.fail("camera_distance_m", "must be positive: a perspective camera below the mirror");
  if (d != 0.0 && !(d > below))
    mirror.fail("camera_distance_m", "puts the camera on or above the mirror (it must exceed " + shortNumber(below) + " m)");
  if (!(d < height)) mirror.fail("camera_distance_m", "must be smaller than rig.height (the camera sits above the floor)");
  return d;
}

MirrorShapeSpec readShape(JsonFields& mirror, const std::string& shape, double height) {
  const JsonFields::Range size{limits::kMinMirrorSize, limits::kMaxMirrorSize, false, "m"};
  if (shape == "hyperboloid") {
    HyperboloidMirror h;
    h.k = mirror.number("k", h.k, {limits::kMinMirrorK, limits::kMaxMirrorK, true});
    h.c = mirror.number("c", h.c, {limits::kMinMirrorC, limits::kMaxMirrorC, false, "m"});
    if (!(h.c < height)) mirror.fail("c", "must be smaller than rig.height (the camera sits c below F', above the floor)");
    h.rimElevationDeg = rimElevation(mirror, h.rimElevationDeg);
    return h;
  }
  if (shape == "paraboloid") {
    ParaboloidMirror p;
    p.h = mirror.number("h", size);
    p.rimElevationDeg = rimElevation(mirror, p.rimElevationDeg);
    if (!(p.rimElevationDeg < 60.0)) mirror.fail("rim_elevation_deg", "must be below 60 degrees for a paraboloid (got " + shortNumber(p.rimElevationDeg) + ")");
    p.cameraDistance = cameraDistance(mirror, 0.0, 0.5 * p.h, height);
    return p;
  }
  if (shape == "sphere") {
    SphereMirror s;
    s.radius = mirror.number("radius", size);
    s.capAngleDeg = mirror.number("cap_angle_deg", s.capAngleDeg, {10.0, 90.0, false, "degrees"});
    s.cameraDistance = cameraDistance(mirror, std::nullopt, s.radius, height);
    return s;
  }
  if (shape == "cone") {
    ConeMirror c;
    c.halfAngleDeg = mirror.number("half_angle_deg", c.halfAngleDeg, {10.0, 80.0, false, "degrees"});
    c.rimRadius = mirror.number("rim_radius", size);
    c.cameraDistance = cameraDistance(mirror, std::nullopt, 0.0, height);
    return c;
  }
  mirror.fail("shape", quote(shape) + " is not a mirror shape omnicam models (hyperboloid, paraboloid, sphere, cone)");
}

// The image is framed on the rim: a perspective camera must see it, not the mirror's edge in
// front of it (a sphere's cap beyond its tangent circle, a paraboloid seen from too close).
void requireRimInView(JsonFields& mirror, const MirrorRig& spec, double cameraDistance) {
  if (cameraDistance == 0.0) return;
  const auto surface = mirrorSurfaceOf(spec);
  const Vec3 camera(0.0, 0.0, -cameraDistance), rim(surface->rimRadius(), 0.0, surface->rimZ());
  const auto seen = surface->firstHit(camera, rim - camera);
  if (!seen || (*seen - rim).norm() > 1e-9 * surface->rimRadius())
    mirror.fail("camera_distance_m", "hides the rim behind the mirror's edge (the image is framed on the rim): "
                                     "move the camera further away, or make the mirror's rim lower");
}

// rig.mirror: the shape and its parameters (docs/scene-format.md); each shape takes only its own.
void readMirror(JsonFields& mirror, MirrorRig& spec, double height) {
  const std::string shape = mirror.string("shape", "hyperboloid");
  const bool known = shape == "hyperboloid" || shape == "paraboloid" || shape == "sphere" || shape == "cone";
  if (known) refuseOtherShapesFields(mirror, shape);
  spec.shape = readShape(mirror, shape, height);
  std::visit(Overloaded{[](const HyperboloidMirror&) {},
                        [&](const auto& other) { requireRimInView(mirror, spec, other.cameraDistance); }},
             spec.shape);
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
  HyperboloidMirror* hyperboloid = std::get_if<HyperboloidMirror>(&mirrorRig.shape);
  if (hyperboloid) hyperboloid->framingElevationDeg = hyperboloid->rimElevationDeg;
  if (auto image = rig.optionalObject("image")) {
    mirrorRig.imageSize = image->integer("size", mirrorRig.imageSize, limits::kMinImageSize, limits::kMaxImageSize);
    if (!hyperboloid && image->has("framing_elevation_deg"))
      image->fail("framing_elevation_deg", "only for the hyperboloid: the other shapes' images frame their rim");
    if (hyperboloid) {
      hyperboloid->framingElevationDeg = image->number("framing_elevation_deg", hyperboloid->rimElevationDeg);
      if (!(hyperboloid->framingElevationDeg > -60.0 && hyperboloid->framingElevationDeg <= hyperboloid->rimElevationDeg))
        image->fail("framing_elevation_deg", "must be in (-60, rim_elevation_deg] degrees (rim_elevation_deg " +
                                                 shortNumber(hyperboloid->rimElevationDeg) + "; got " +
                                                 shortNumber(hyperboloid->framingElevationDeg) + ")");
    }
    image->finish();
  }
  if (!rig.has("mirror") && !(hyperboloid->c < spec.height))
    rig.fail("height", "must be larger than the mirror's c = " + shortNumber(hyperboloid->c) + " m");
  rig.finish();
  try {
    if (hyperboloid) (void)mirrorRig.idealCamera();  // it must image the rim and framing
    (void)makeCamera(spec);    // and the camera must sit below the mirror
  } catch (const InputError& e) {
    throw InputError(showPath(rig.file()) + ": " + rig.where() + "." + e.what());
  }
  return spec;
}

}  // namespace omnicam
