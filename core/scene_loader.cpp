#include "scene_loader.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "camera_path.h"
#include "errors.h"
#include "gltf_import.h"
#include "json_fields.h"
#include "sha256.h"

namespace omnicam {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

constexpr const char* kFormat = "omnicam-scene/1";

struct Context {
  std::string file;
  fs::path folder;  // textures resolve relative to, and must stay inside, this folder
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

// A file named in the scene: relative to the scene's folder, which it must not leave (spec §9).
fs::path resolveInside(const Context& ctx, const JsonFields& fields, const std::string& key, const std::string& name) {
  const fs::path resolved = fs::weakly_canonical(ctx.folder / name);
  const auto rel = resolved.lexically_relative(fs::weakly_canonical(ctx.folder));
  if (rel.empty() || *rel.begin() == "..")
    fields.fail(key, "must stay inside the scene's folder (got \"" + name + "\")");
  if (!fs::is_regular_file(resolved)) fields.fail(key, "file not found: " + resolved.string());
  return resolved;
}

RigSpec readRig(JsonFields rig) {
  RigSpec spec;
  spec.height = rig.positive("height", spec.height);
  if (auto mirror = rig.optionalObject("mirror")) {
    spec.k = mirror->number("k", spec.k);
    if (!(spec.k > 2.0)) mirror->fail("k", "must be > 2 (got " + std::to_string(spec.k) + ")");
    spec.c = mirror->positive("c", spec.c);
    spec.rimElevationDeg = mirror->number("rim_elevation_deg", spec.rimElevationDeg);
    if (!(spec.rimElevationDeg > -60.0 && spec.rimElevationDeg < 80.0))
      mirror->fail("rim_elevation_deg", "must be in (-60, 80) degrees");
    mirror->finish();
  }
  if (auto image = rig.optionalObject("image")) {
    spec.imageSize = image->integer("size", spec.imageSize, 8, 16384);
    spec.framingElevationDeg = image->number("framing_elevation_deg", spec.rimElevationDeg);
    if (!(spec.framingElevationDeg > -60.0 && spec.framingElevationDeg <= spec.rimElevationDeg))
      image->fail("framing_elevation_deg", "must be in (-60, rim_elevation_deg] degrees");
    image->finish();
  } else {
    spec.framingElevationDeg = spec.rimElevationDeg;
  }
  rig.finish();
  try {
    (void)spec.camera();  // the mirror must be able to image the rim and framing
  } catch (const InputError& e) {
    throw InputError(rig.file() + ": rig." + e.what());
  }
  return spec;
}

RobotPose readPose(const json& v, const std::string& file, const std::string& path) {
  const Vec3 p = jsonVec3(v, file, path);
  return {p.x(), p.y(), p.z()};
}

Material readMaterial(const std::string& name, JsonFields m, const Context& ctx) {
  Material mat;
  mat.name = name;
  mat.color = m.colour("color", mat.color, 1.0);
  mat.ambient = static_cast<float>(m.nonNegative("ambient", mat.ambient));
  mat.diffuse = static_cast<float>(m.nonNegative("diffuse", mat.diffuse));
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

Shape readShape(const std::string& type, JsonFields& o) {
  if (type == "box") {
    Box b{o.vec3("center"), o.vec3("size"), o.number("yaw_deg", 0.0)};
    for (int i = 0; i < 3; ++i)
      if (!(b.size[i] > 0.0)) o.fail("size", "all sizes must be > 0");
    return b;
  }
  if (type == "cylinder") {
    Cylinder c{o.vec3("base"), o.vec3("top"), o.positive("radius"), o.boolean("caps", true)};
    if ((c.top - c.base).norm() <= 0.0) o.fail("top", "must differ from base");
    return c;
  }
  if (type == "sphere") return Sphere{o.vec3("center"), o.positive("radius")};
  if (type == "quad") {
    Quad q{o.vec3("origin"), o.vec3("edge_u"), o.vec3("edge_v")};
    if (q.edgeU.cross(q.edgeV).norm() <= 0.0) o.fail("edge_v", "edges must not be parallel or zero");
    return q;
  }
  if (type == "disc") {
    Disc d{o.vec3("center"), o.vec3("normal", Vec3::UnitZ()), o.positive("radius"),
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
        if (!t[k].is_number_integer() || t[k].get<long long>() < 0 ||
            t[k].get<long long>() >= static_cast<long long>(m.vertices.size()))
          o.fail(where, "vertex indices must be integers in [0, " +
                            std::to_string(m.vertices.size()) + ")");
        tri[k] = t[k].get<int>();
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
  o.fail("type", "unknown object type \"" + type + "\" (box, cylinder, sphere, quad, disc, mesh)");
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
      if (i > 0 && points[i] == points[i - 1]) p.fail(indexed("waypoints", i), "repeats the previous point");
    }
    const int frames = p.integer("frames", 100, 1, 1000000);
    path.poses = sampleWaypointPath(points, frames);
  }
  p.finish();
  return path;
}

}  // namespace

const CameraPath* Scene::findPath(const std::string& pathName) const {
  for (const auto& p : paths)
    if (p.name == pathName) return &p;
  return nullptr;
}

Scene loadScene(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file + ": cannot open scene file");
  json root;
  try {
    root = json::parse(in);
  } catch (const json::parse_error& e) {
    throw InputError(file + ": not valid JSON (" + std::string(e.what()) + ")");
  }
  Context ctx{file, fs::absolute(file).parent_path(), {}};
  JsonFields top(root, file, "");
  Scene scene;
  scene.path = file;
  scene.sha256 = sha256OfFile(file);
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

  static const json empty = json::array();
  const json& objects = requireArray(top, "objects", false, empty);
  std::set<std::string> names;
  for (size_t i = 0; i < objects.size(); ++i) {
    JsonFields o(objects[i], file, indexed("objects", i));
    SceneObject obj;
    obj.name = o.string("name", indexed("object", i));
    if (o.has("type") && o.raw("type") == "gltf") {
      // An arena authored elsewhere: its meshes and materials join the scene.
      o.string("type");
      const std::string gltfFile = o.string("file");
      GltfArena arena;
      try {
        arena = importGltf(resolveInside(ctx, o, "file", gltfFile).string());
      } catch (const InputError& e) {
        o.fail("file", e.what());
      }
      const int offset = static_cast<int>(scene.materials.size());
      for (Material& m : arena.materials) {
        m.name = obj.name + "/" + m.name;
        scene.materials.push_back(std::move(m));
      }
      for (SceneObject& imported : arena.objects) {
        imported.name = obj.name + "/" + imported.name;
        imported.material += offset;
        scene.objects.push_back(std::move(imported));
      }
      o.finish();
      continue;
    }
    const std::string materialName = o.string("material");
    auto m = ctx.materialIndex.find(materialName);
    if (m == ctx.materialIndex.end()) o.fail("material", "no material named \"" + materialName + "\"");
    obj.material = m->second;
    obj.shape = readShape(o.string("type"), o);
    o.finish();
    scene.objects.push_back(std::move(obj));
  }

  if (scene.materials.empty()) top.fail("materials", "must define at least one material");

  const json& lights = requireArray(top, "lights", true, empty);
  for (size_t i = 0; i < lights.size(); ++i) {
    JsonFields l(lights[i], file, indexed("lights", i));
    scene.lights.push_back({l.string("name", indexed("light", i)), l.vec3("position"),
                            l.colour("intensity", Vec3f::Ones(), 1e6)});
    l.finish();
  }

  const json& landmarks = requireArray(top, "landmarks", true, empty);
  for (size_t i = 0; i < landmarks.size(); ++i) {
    JsonFields l(landmarks[i], file, indexed("landmarks", i));
    Landmark lm{l.string("name"), l.vec3("position"), l.positive("diameter"), l.positive("height"),
                l.string("colour_class")};
    if (!names.insert("landmark:" + lm.name).second) l.fail("name", "duplicate landmark name");
    l.finish();
    scene.landmarks.push_back(std::move(lm));
  }

  const json& paths = requireArray(top, "paths", true, empty);
  for (size_t i = 0; i < paths.size(); ++i) {
    CameraPath p = readPath(JsonFields(paths[i], file, indexed("paths", i)), file);
    if (scene.findPath(p.name))
      throw InputError(file + ": " + indexed("paths", i) + ".name: duplicate path \"" + p.name + "\"");
    scene.paths.push_back(std::move(p));
  }
  top.finish();
  return scene;
}

}  // namespace omnicam
