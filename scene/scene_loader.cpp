#include "scene_loader.h"

#include "make_camera.h"
#include "mirror_surface.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "camera_path.h"
#include "errors.h"
#include "number_format.h"
#include "file_confinement.h"
#include "gltf_import.h"
#include "input_limits.h"
#include "json_fields.h"
#include "lens_fields.h"
#include "sha256.h"

namespace omnicam {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

constexpr const char* kFormat = "omnicam-scene/1";

struct Context {
  std::string file;
  fs::path folder;  // textures resolve relative to, and must stay inside, this folder
  SceneLoadOptions options;
  std::map<std::string, int> materialIndex;
};

std::string indexed(const std::string& array, size_t i) {
  return array + "[" + std::to_string(i) + "]";
}

const json& requireArray(JsonFields& fields, const std::string& key, bool allowMissing,
                         const json& empty) {
  if (!fields.has(key) && allowMissing) {
    fields.number(key, 0.0);  // marks as read
    return empty;
  }
  const json& v = fields.raw(key);
  if (!v.is_array()) fields.fail(key, "must be an array (got " + jsonTypeName(v) + ")");
  return v;
}

// A file named in the scene: relative to the scene's folder, which it must not leave.
fs::path resolveInside(const Context& ctx, const JsonFields& fields, const std::string& key, const std::string& name) {
  std::string why;
  const auto resolved = resolveConfined(ctx.folder, name, ctx.options.allowOutsideFolder, why);
  if (!resolved) fields.fail(key, why);
  return *resolved;
}

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
void readMirror(JsonFields& mirror, RigSpec& spec) {
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
    if (!(s.cameraDistance < spec.height))
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
    if (!(spec.c < spec.height))
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
  spec.lens = readLensCamera(rig.object("lens"));
  spec.imageSize = spec.lens->width;
  if (auto shutter = rig.optionalObject("shutter")) spec.shutter = readShutter(*shutter);
  const std::vector<double> tilt = rig.numbers("tilt_deg", {0.0, 0.0}, {-limits::kMaxRigTiltDeg, limits::kMaxRigTiltDeg, false, "degrees"});
  spec.tiltDeg = {tilt[0], tilt[1]};
  rig.finish();
  return spec;
}

RigSpec readRig(JsonFields rig) {
  RigSpec spec;
  spec.height = rig.number("height", spec.height, {limits::kMinRigHeight, limits::kMaxRigHeight, false, "m"});
  if (rig.has("lens")) return readLensRig(rig, spec);
  if (auto mirror = rig.optionalObject("mirror")) {
    readMirror(*mirror, spec);
    mirror->finish();
  }
  if (auto camera = rig.optionalObject("camera")) spec.mount = readCameraMount(*camera);
  if (auto shutter = rig.optionalObject("shutter")) spec.shutter = readShutter(*shutter);
  const std::vector<double> tilt = rig.numbers("tilt_deg", {0.0, 0.0}, {-limits::kMaxRigTiltDeg, limits::kMaxRigTiltDeg, false, "degrees"});
  spec.tiltDeg = {tilt[0], tilt[1]};
  if (auto image = rig.optionalObject("image")) {
    spec.imageSize = image->integer("size", spec.imageSize, limits::kMinImageSize, limits::kMaxImageSize);
    if (spec.shape.shape != MirrorShape::Hyperboloid && image->has("framing_elevation_deg"))
      image->fail("framing_elevation_deg", "only for the hyperboloid: the other shapes' images frame their rim");
    spec.framingElevationDeg = image->number("framing_elevation_deg", spec.rimElevationDeg);
    if (!(spec.framingElevationDeg > -60.0 && spec.framingElevationDeg <= spec.rimElevationDeg))
      image->fail("framing_elevation_deg", "must be in (-60, rim_elevation_deg] degrees");
    image->finish();
  } else {
    spec.framingElevationDeg = spec.rimElevationDeg;
  }
  if (!rig.has("mirror") && !(spec.c < spec.height))
    rig.fail("height", "must be larger than the mirror's c = " + shortNumber(spec.c) + " m");
  rig.finish();
  try {
    if (spec.shape.shape == MirrorShape::Hyperboloid) (void)spec.idealCamera();  // it must image the rim and framing
    (void)makeCamera(spec);    // and the camera must sit below the mirror
  } catch (const InputError& e) {
    throw InputError(showPath(rig.file()) + ": " + rig.where() + "." + e.what());
  }
  return spec;
}

// Names reach glTF nodes and Blender objects: unique, printable, at most 63 bytes (Blender's
// limit; longer ones it truncates silently).
// Returns what is wrong with `name`, or "" if nothing.
std::string nameProblem(const std::string& name) {
  if (name.empty() || name.size() > 63) return "must be 1 to 63 bytes long (got " + std::to_string(name.size()) + ")";
  for (unsigned char ch : name)
    if (ch < 0x20 || ch == 0x7F) return "must not contain control characters (got " + quote(name) + ")";
  return {};
}

void checkName(JsonFields& fields, const std::string& key, const std::string& name) {
  if (const std::string problem = nameProblem(name); !problem.empty()) fields.fail(key, problem);
}

RobotPose readPose(const json& v, const std::string& file, const std::string& path) {
  const Vec3 p = jsonVec3(v, file, path);
  return {p.x(), p.y(), p.z()};
}

// A "class" (semantic label for datasets): a name like any other, optional.
std::string readClass(JsonFields& fields) {
  if (!fields.has("class")) return {};
  const std::string cls = fields.string("class");
  checkName(fields, "class", cls);
  return cls;
}

Material readMaterial(const std::string& name, JsonFields m, const Context& ctx) {
  Material mat;
  // The name is the key, which m.where() already shows.
  if (const std::string problem = nameProblem(name); !problem.empty())
    throw InputError(showPath(ctx.file) + ": " + m.where() + ": material names " + problem);
  mat.name = name;
  mat.color = m.colour("color", mat.color, 1.0);
  mat.emission = m.colour("emission", mat.emission, 1e6);  // as a light's intensity
  mat.ambient = static_cast<float>(m.nonNegative("ambient", mat.ambient));
  mat.diffuse = static_cast<float>(m.nonNegative("diffuse", mat.diffuse));
  mat.semanticClass = readClass(m);
  if (auto tex = m.optionalObject("texture")) {
    mat.texturePath = tex->string("file");
    const fs::path resolved = resolveInside(ctx, *tex, "file", mat.texturePath);
    try {
      mat.texture = Texture::load(resolved.string());
    } catch (const InputError& e) {
      tex->fail("file", e.what());
    }
    if (tex->has("scale")) {
      const json& s = tex->raw("scale");
      if (!s.is_array() || s.size() != 2 || !s[0].is_number() || !s[1].is_number() ||
          !(s[0].get<double>() > 0.0) || !(s[1].get<double>() > 0.0))
        tex->fail("scale", "must be [su, sv] with both > 0");
      mat.textureScale = {s[0].get<double>(), s[1].get<double>()};
    }
    tex->finish();
  }
  m.finish();
  return mat;
}

// A primitive's length: at least a micrometre, at most the world's extent.
double length(JsonFields& o, const std::string& key) { return o.number(key, {limits::kMinLength, limits::kMaxLength, false, "m"}); }

Shape readShape(const std::string& type, JsonFields& o) {
  if (type == "box") {
    Box b{o.vec3("center"), o.vec3("size"), o.number("yaw_deg", 0.0)};
    for (int i = 0; i < 3; ++i)
      if (!(b.size[i] >= limits::kMinLength && b.size[i] <= limits::kMaxLength))
        o.fail("size", "all sizes must be in [" + shortNumber(limits::kMinLength) + ", " + shortNumber(limits::kMaxLength) + "] m");
    return b;
  }
  if (type == "cylinder") {
    Cylinder c{o.vec3("base"), o.vec3("top"), length(o, "radius"), o.boolean("caps", true)};
    if ((c.top - c.base).norm() <= 0.0) o.fail("top", "must differ from base");
    return c;
  }
  if (type == "sphere") return Sphere{o.vec3("center"), length(o, "radius")};
  if (type == "quad") {
    Quad q{o.vec3("origin"), o.vec3("edge_u"), o.vec3("edge_v")};
    if (q.edgeU.cross(q.edgeV).norm() <= 0.0) o.fail("edge_v", "edges must not be parallel or zero");
    return q;
  }
  if (type == "disc") {
    Disc d{o.vec3("center"), o.vec3("normal", Vec3::UnitZ()), length(o, "radius"),
           o.nonNegative("inner_radius", 0.0)};
    if (d.normal.norm() <= 0.0) o.fail("normal", "must not be zero");
    d.normal.normalize();
    if (d.innerRadius >= d.radius) o.fail("inner_radius", "must be smaller than radius");
    return d;
  }
  if (type == "mesh") {
    Mesh m;
    static const json empty = json::array();
    const json& vertices = requireArray(o, "vertices", false, empty);
    for (size_t i = 0; i < vertices.size(); ++i)
      m.vertices.push_back(jsonVec3(vertices[i], o.file(), o.path(indexed("vertices", i))));
    const json& triangles = requireArray(o, "triangles", false, empty);
    for (size_t i = 0; i < triangles.size(); ++i) {
      const json& t = triangles[i];
      const std::string where = indexed("triangles", i);
      if (!t.is_array() || t.size() != 3) o.fail(where, "must be [i, j, k]");
      Eigen::Vector3i tri;
      for (int k = 0; k < 3; ++k) {
        const auto index = integerInRange(t[k], 0, static_cast<int64_t>(m.vertices.size()) - 1);
        if (!index) o.fail(where, "vertex indices must be integers in [0, " + std::to_string(m.vertices.size()) + ")");
        tri[k] = static_cast<int>(*index);
      }
      m.triangles.push_back(tri);
    }
    if (m.triangles.empty()) o.fail("triangles", "must not be empty");
    const json& uvs = requireArray(o, "uvs", true, empty);
    for (size_t i = 0; i < uvs.size(); ++i) {
      const json& uv = uvs[i];
      if (!uv.is_array() || uv.size() != 2 || !uv[0].is_number() || !uv[1].is_number())
        o.fail(indexed("uvs", i), "must be [u, v]");
      m.uvs.emplace_back(uv[0].get<double>(), uv[1].get<double>());
    }
    if (!m.uvs.empty() && m.uvs.size() != m.vertices.size())
      o.fail("uvs", "must have one entry per vertex");
    return m;
  }
  o.fail("type", "unknown object type " + quote(type) + " (box, cylinder, sphere, quad, disc, mesh, gltf, calibration_target)");
}

CameraPath readPath(JsonFields p, const std::string& file) {
  CameraPath path;
  path.name = p.string("name");
  if (p.has("poses")) {
    const json& poses = p.raw("poses");
    if (!poses.is_array() || poses.empty()) p.fail("poses", "must be a non-empty array");
    for (size_t i = 0; i < poses.size(); ++i)
      path.poses.push_back(readPose(poses[i], file, p.path(indexed("poses", i))));
  } else {
    const json& wps = p.raw("waypoints");
    if (!wps.is_array() || wps.size() < 2) p.fail("waypoints", "must list at least 2 [x, y] points");
    std::vector<Vec2> points;
    for (size_t i = 0; i < wps.size(); ++i) {
      const json& w = wps[i];
      if (!w.is_array() || w.size() != 2 || !w[0].is_number() || !w[1].is_number())
        p.fail(indexed("waypoints", i), "must be [x, y]");
      points.emplace_back(w[0].get<double>(), w[1].get<double>());
      if (!points.back().allFinite() || points.back().cwiseAbs().maxCoeff() > limits::kMaxWorldCoordinate)
        p.fail(indexed("waypoints", i), "must lie within ±" + shortNumber(limits::kMaxWorldCoordinate) + " m");
      if (i > 0 && points[i] == points[i - 1]) p.fail(indexed("waypoints", i), "repeats the previous point");
    }
    const int frames = p.integer("frames", 100, 1, 1000000);
    path.poses = sampleWaypointPath(points, frames);
  }
  p.finish();
  return path;
}

// `wanted`, or a variant of it that is not in `taken` and fits in 63 bytes; then marks it taken.
std::string uniqueName(const std::string& wanted, std::set<std::string>& taken) {
  const auto cut = [](std::string name, size_t bytes) {
    if (name.size() <= bytes) return name;
    name.resize(bytes);
    while (!name.empty() && (static_cast<unsigned char>(name.back()) & 0xC0) == 0x80) name.pop_back();  // UTF-8
    if (!name.empty() && static_cast<unsigned char>(name.back()) >= 0xC0) name.pop_back();
    return name;
  };
  std::string name = cut(wanted, 63);
  for (int k = 1; !taken.insert(name).second; ++k) {
    const std::string suffix = "." + std::to_string(k);
    name = cut(wanted, 63 - suffix.size()) + suffix;
  }
  return name;
}

TargetPattern readTargetPattern(JsonFields p) {
  const std::string kind = p.string("kind");
  TargetPattern pattern;
  if (kind == "checkerboard") {
    Checkerboard b;
    // At least 3 inner corners a side (Kalibr's and OpenCV's detectors need them).
    b.rows = static_cast<int>(p.integer("rows", 4, 1000));
    b.columns = static_cast<int>(p.integer("columns", 4, 1000));
    b.square = p.number("square", {1e-4, 10.0, false, "m"});
    // One odd and one even side: only then does the board look different turned half round, and
    // a detector can tell which corner is the first (OpenCV's advice).
    if ((b.rows + b.columns) % 2 == 0) p.fail("columns", "rows + columns must be odd (one side even, one odd: else the board has no first corner a detector can tell)");
    pattern = b;
  } else if (kind == "aprilgrid") {
    AprilGrid g;
    g.tagRows = static_cast<int>(p.integer("tag_rows", 1, 100));
    g.tagColumns = static_cast<int>(p.integer("tag_columns", 1, 100));
    g.tagSize = p.number("tag_size", {1e-3, 10.0, false, "m"});
    g.tagSpacing = p.number("tag_spacing", {0.0, 1.0, true});
    g.firstId = p.integer("first_id", 0, 0, aprilGridFamilySize() - 1);
    pattern = g;
  } else {
    p.fail("kind", "unknown pattern kind " + quote(kind) + " (checkerboard, aprilgrid)");
  }
  p.finish();
  return pattern;
}

// A calibration target: its board joins the objects (a textured quad) and its material the
// materials; the target itself keeps the exact pattern and pose.
void addCalibrationTarget(JsonFields& o, const std::string& name, Scene& scene, std::set<std::string>& materialNames) {
  CalibrationTarget target;
  target.name = name;
  target.pattern = readTargetPattern(o.object("pattern"));
  const double texel = targetTexel(target.pattern);
  const double defaultMargin = std::holds_alternative<Checkerboard>(target.pattern)
                                   ? std::get<Checkerboard>(target.pattern).square
                                   : std::get<AprilGrid>(target.pattern).tagSize / 5.0;  // two tag bits
  target.margin = o.number("margin", defaultMargin, {0.0, 10.0, false, "m"});
  if (std::llround(target.margin / texel) < 1)
    o.fail("margin", "must be at least one texel of the pattern (" + shortNumber(texel) + " m; the texture repeats)");
  const std::string problem = targetPatternProblem(target.pattern, target.margin);
  if (!problem.empty()) o.fail("pattern", problem);
  int64_t texels = targetBoardTexels(target.pattern, target.margin);
  for (const CalibrationTarget& other : scene.calibrationTargets) texels += targetBoardTexels(other.pattern, other.margin);
  if (texels > kMaxTargetTexelsInScene)
    o.fail("pattern", "the scene's boards need " + std::to_string(texels) + " texels in all (at most " +
                          std::to_string(kMaxTargetTexelsInScene) + ")");
  const Vec3 origin = o.vec3("origin"), xAxis = o.vec3("x_axis"), yAxis = o.vec3("y_axis");
  if (!(xAxis.norm() > 1e-9)) o.fail("x_axis", "must not be zero");
  if (!(yAxis.norm() > 1e-9)) o.fail("y_axis", "must not be zero");
  const Vec3 x = xAxis.normalized();
  if (std::abs(x.dot(yAxis.normalized())) > 1e-6) o.fail("y_axis", "must be perpendicular to x_axis");
  // Exactly orthonormal: y is the given one's part perpendicular to x.
  const Vec3 z = x.cross(yAxis).normalized();
  target.worldFromTarget.linear().col(0) = x;
  target.worldFromTarget.linear().col(1) = z.cross(x);
  target.worldFromTarget.linear().col(2) = z;
  target.worldFromTarget.translation() = origin;
  const double black = o.number("black", 0.03, {0.0, 1.0});
  const double white = o.number("white", 0.85, {0.0, 1.0});
  if (!(black < white)) o.fail("white", "must be brighter than black");
  SceneObject board;
  board.name = name;
  board.semanticClass = readClass(o);
  o.finish();

  const TargetBoard printed = targetBoard(target.pattern, target.margin, static_cast<float>(black), static_cast<float>(white));
  Material material;
  material.name = uniqueName(name + "/print", materialNames);
  material.texture = printed.texture;
  const Eigen::Matrix3d& rotation = target.worldFromTarget.linear();
  board.shape = Quad{target.worldFromTarget * printed.origin, rotation * printed.edgeU, rotation * printed.edgeV};
  board.material = static_cast<int>(scene.materials.size());
  scene.materials.push_back(std::move(material));
  target.object = static_cast<int>(scene.objects.size());
  scene.objects.push_back(std::move(board));
  scene.calibrationTargets.push_back(std::move(target));
}

}  // namespace

const std::string& semanticClassOf(const Scene& scene, const SceneObject& object) {
  if (!object.semanticClass.empty()) return object.semanticClass;
  return scene.materials.at(static_cast<size_t>(object.material)).semanticClass;
}

const CameraPath* Scene::findPath(const std::string& pathName) const {
  for (const auto& p : paths)
    if (p.name == pathName) return &p;
  return nullptr;
}

RigSpec rigFromJson(const nlohmann::json& rig, const std::string& file, const std::string& where) {
  return readRig(JsonFields(rig, file, where));
}

Scene loadScene(const std::string& file, const SceneLoadOptions& options) {
  std::string why;
  const auto text = readWholeFile(file, why, limits::kMaxJsonFileBytes);
  if (!text) throw InputError(showPath(file) + ": cannot open scene file (" + why + ")");
  return loadSceneFromText(*text, file, options);
}

Scene loadSceneFromText(const std::string& text, const std::string& file, const SceneLoadOptions& options) {
  const json root = parseJsonText(text, file);
  Context ctx{file, fs::absolute(file).parent_path(), options, {}};
  JsonFields top(root, file, "");
  Scene scene;
  scene.path = file;
  scene.sha256 = sha256OfBytes(text);
  const std::string format = top.string("format");
  if (format != kFormat) top.fail("format", "must be \"" + std::string(kFormat) + "\"");
  scene.name = top.string("name", fs::path(file).stem().string());
  top.string("description", "");
  scene.background = top.colour("background", scene.background, 1e6);
  scene.rig = top.has("rig") ? readRig(top.object("rig")) : RigSpec{};
  if (top.has("start_pose")) scene.startPose = readPose(top.raw("start_pose"), file, "start_pose");

  JsonFields materials = top.object("materials");
  const json& materialsJson = top.raw("materials");
  for (auto it = materialsJson.begin(); it != materialsJson.end(); ++it) {
    if (it.key() == "comment") continue;
    ctx.materialIndex[it.key()] = static_cast<int>(scene.materials.size());
    scene.materials.push_back(readMaterial(it.key(), materials.object(it.key()), ctx));
  }
  materials.finish();
  std::set<std::string> materialNames;
  for (const Material& m : scene.materials) materialNames.insert(m.name);

  static const json empty = json::array();
  const json& objects = requireArray(top, "objects", false, empty);
  // Objects and lights both become named nodes (glTF, Blender): one namespace.
  std::set<std::string> names;
  for (size_t i = 0; i < objects.size(); ++i) {
    JsonFields o(objects[i], file, indexed("objects", i));
    SceneObject obj;
    obj.name = o.string("name", "object_" + std::to_string(i));
    checkName(o, "name", obj.name);
    if (!names.insert(obj.name).second) o.fail("name", "duplicate name " + quote(obj.name) + " (objects and lights share one namespace)");
    if (o.has("type") && o.raw("type") == "gltf") {
      // An arena authored elsewhere: its meshes and materials join the scene, their names made
      // unique (glTF does not require that) and kept within Blender's 63 bytes.
      o.string("type");
      const std::string gltfFile = o.string("file");
      const std::string gltfClass = readClass(o);
      GltfArena arena;
      try {
        arena = importGltf(resolveInside(ctx, o, "file", gltfFile).string(),
                           {ctx.options.allowOutsideFolder ? fs::path() : ctx.folder});
      } catch (const InputError& e) {
        o.fail("file", e.what());
      }
      const int offset = static_cast<int>(scene.materials.size());
      for (Material& m : arena.materials) {
        m.name = uniqueName(obj.name + "/" + m.name, materialNames);
        scene.materials.push_back(std::move(m));
      }
      for (SceneObject& imported : arena.objects) {
        imported.name = uniqueName(obj.name + "/" + imported.name, names);
        imported.material += offset;
        imported.semanticClass = gltfClass;
        scene.objects.push_back(std::move(imported));
      }
      o.finish();
      continue;
    }
    if (o.has("type") && o.raw("type") == "calibration_target") {
      o.string("type");
      addCalibrationTarget(o, obj.name, scene, materialNames);
      continue;
    }
    const std::string materialName = o.string("material");
    auto m = ctx.materialIndex.find(materialName);
    if (m == ctx.materialIndex.end()) o.fail("material", "no material named " + quote(materialName));
    obj.material = m->second;
    obj.semanticClass = readClass(o);
    obj.shape = readShape(o.string("type"), o);
    o.finish();
    scene.objects.push_back(std::move(obj));
  }

  if (scene.materials.empty()) top.fail("materials", "must define at least one material");

  const json& lights = requireArray(top, "lights", true, empty);
  for (size_t i = 0; i < lights.size(); ++i) {
    JsonFields l(lights[i], file, indexed("lights", i));
    PointLight light{l.string("name", "light_" + std::to_string(i)), l.vec3("position"),
                     l.colour("intensity", Vec3f::Ones(), 1e6),
                     l.number("diameter", 0.0, JsonFields::Range(0.0, 100.0, false, "m"))};
    checkName(l, "name", light.name);
    if (!names.insert(light.name).second)
      l.fail("name", "duplicate name " + quote(light.name) + " (objects and lights share one namespace)");
    l.finish();
    scene.lights.push_back(std::move(light));
  }

  // Landmarks name what they mark (often an object of the same name): their own namespace.
  std::set<std::string> landmarkNames;
  const json& landmarks = requireArray(top, "landmarks", true, empty);
  for (size_t i = 0; i < landmarks.size(); ++i) {
    JsonFields l(landmarks[i], file, indexed("landmarks", i));
    Landmark lm{l.string("name"), l.vec3("position"), length(l, "diameter"), length(l, "height"),
                l.string("colour_class")};
    checkName(l, "name", lm.name);
    if (!landmarkNames.insert(lm.name).second) l.fail("name", "duplicate landmark name " + quote(lm.name));
    l.finish();
    scene.landmarks.push_back(std::move(lm));
  }

  const json& paths = requireArray(top, "paths", true, empty);
  for (size_t i = 0; i < paths.size(); ++i) {
    CameraPath p = readPath(JsonFields(paths[i], file, indexed("paths", i)), file);
    if (scene.findPath(p.name))
      throw InputError(showPath(file) + ": " + indexed("paths", i) + ".name: duplicate path " + quote(p.name));
    scene.paths.push_back(std::move(p));
  }
  top.finish();
  return scene;
}

}  // namespace omnicam
