#include "scene_loader.h"

#include "data_files.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "camera_path.h"
#include "closest_name.h"
#include "errors.h"
#include "number_format.h"
#include "file_confinement.h"
#include "gltf_import.h"
#include "image.h"
#include "input_limits.h"
#include "json_fields.h"
#include "rig_fields.h"
#include "scene_limits.h"
#include "sha256.h"
#include "target_fields.h"

namespace omnicam {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// A file the scene read beyond its text: its name as the scene writes it (from the scene's folder,
// lexically: the same on every machine), the file read, and the SHA-256 of the very bytes decoded.
struct InputRead {
  std::string name, file, sha256;
};

struct Context {
  std::string file;
  fs::path folder;  // textures resolve relative to, and must stay inside, this folder
  SceneLoadOptions options;
  std::map<std::string, int> materialIndex;
  std::vector<std::string>* inputFiles = nullptr;  // the scene's, to which each file read is added
  std::vector<InputRead>* inputsRead = nullptr;    // the same files, named for a scene's inputs
};

// `name` as a path from the scene's folder: lexically normal, '/'-separated; an absolute one as it is.
std::string nameFromSceneFolder(const fs::path& name) { return name.lexically_normal().generic_string(); }

// One file the scene read: among the files its outputs must spare, and named for its inputs.
void noteFileRead(const Context& ctx, const fs::path& name, const std::string& file, const std::string& sha256) {
  if (ctx.inputFiles) ctx.inputFiles->push_back(file);
  if (ctx.inputsRead) ctx.inputsRead->push_back({nameFromSceneFolder(name), file, sha256});
}

std::string indexed(const std::string& array, size_t i) {
  return array + "[" + std::to_string(i) + "]";
}

// `key`'s array; a missing one is empty if `allowMissing`.
const json& requireArray(JsonFields& fields, const std::string& key, bool allowMissing) {
  static const json empty = json::array();
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

// The bytes of a file the scene reads (`name` as the scene writes it), read once: what is decoded
// is what its input's hash names, even if the file changes meanwhile. `doing` says what failed for
// a file that cannot be read ("read image", "load glTF": the decoders' own words).
std::string readNotedFile(const Context& ctx, const JsonFields& fields, const std::string& key, const fs::path& name,
                          const fs::path& file, const std::string& doing) {
  std::string why;
  std::optional<std::string> bytes = readWholeFile(file.string(), why);
  if (!bytes) fields.fail(key, showPath(file.string()) + ": cannot " + doing + " (" + why + ")");
  noteFileRead(ctx, name, file.string(), sha256OfBytes(*bytes));
  return std::move(*bytes);
}

// An image the scene reads (a texture, an environment), decoded from the bytes its input names;
// every value finite.
ImageRGBA readNotedImage(const Context& ctx, const JsonFields& fields, const std::string& key, const fs::path& name,
                         const fs::path& file) {
  const std::string bytes = readNotedFile(ctx, fields, key, name, file, "read image");
  try {
    return readFiniteImageFromMemory(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), showPath(file.string()));
  } catch (const InputError& error) {
    fields.fail(key, error.what());
  }
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


// An angle about an axis, taken modulo 360°: within ±kMaxYawDeg, as a robot's yaw.
const JsonFields::Range kYawRange{-limits::kMaxYawDeg, limits::kMaxYawDeg, false, "degrees"};

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
  const JsonFields::Range factor{0.0, scene_limits::kMaxShadingFactor};
  mat.ambient = static_cast<float>(m.number("ambient", mat.ambient, factor));
  mat.diffuse = static_cast<float>(m.number("diffuse", mat.diffuse, factor));
  mat.semanticClass = readClass(m);
  if (auto tex = m.optionalObject("texture")) {
    mat.texturePath = tex->string("file");
    const fs::path resolved = resolveInside(ctx, *tex, "file", mat.texturePath);
    const ImageRGBA image = readNotedImage(ctx, *tex, "file", mat.texturePath, resolved);
    try {
      mat.texture = Texture::fromPremultiplied(image.width, image.height, image.pixels.data(), showPath(resolved.string()));
    } catch (const InputError& e) {
      tex->fail("file", e.what());
    }
    if (tex->has("scale")) {
      const json& s = tex->raw("scale");
      auto repeats = [](const json& v) {
        return v.is_number() && v.get<double>() > 0.0 && v.get<double>() <= limits::kMaxTextureScale;
      };
      if (!s.is_array() || s.size() != 2 || !repeats(s[0]) || !repeats(s[1]))
        tex->fail("scale", "must be [su, sv] with both in (0, " + shortNumber(limits::kMaxTextureScale) + "]");
      mat.textureScale = {s[0].get<double>(), s[1].get<double>()};
    }
    tex->finish();
  }
  m.finish();
  return mat;
}

// Blender's own world EXRs (Debian's blender-data, CC0), named without their folder.
constexpr const char* kBlenderWorlds = "/usr/share/blender/datafiles/studiolights/world";

// The world EXR `name` names, or a failure listing those there are.
fs::path blenderWorld(const JsonFields& e, const std::string& name) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(kBlenderWorlds, ec))
    if (entry.path().extension() == ".exr") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  if (std::find(names.begin(), names.end(), name) != names.end()) return fs::path(kBlenderWorlds) / (name + ".exr");
  std::string known;
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  e.fail("blender_world", "no world " + quote(name) + " in " + kBlenderWorlds +
                              (names.empty() ? " (install blender-data with `make deps`)" : " (" + known + ")"));
}

// The environment's image is light: its stored RGB (an EXR's colour, associated with its alpha, as
// renderers show it), negative values counting as none; at most a light's 1e6 once scaled.
Environment readEnvironment(JsonFields e, const Context& ctx) {
  Environment environment;
  if (e.has("file") == e.has("blender_world")) e.fail("file", "give either file or blender_world");
  const std::string key = e.has("file") ? "file" : "blender_world";
  environment.file = e.string(key);
  environment.strength = static_cast<float>(e.number("strength", 1.0, {0.0, 1e6}));
  environment.rotationDeg = e.number("rotation_deg", 0.0, {-360.0, 360.0});
  e.finish();  // every field checked before the image is decoded
  const fs::path resolved = key == "file" ? resolveInside(ctx, e, key, environment.file) : blenderWorld(e, environment.file);
  // Blender's world is read like a file of the scene's (a scene's inputs name it by its full path,
  // the same wherever Debian's blender-data is installed). A NaN or ±∞ is refused, as in a texture.
  const ImageRGBA image = readNotedImage(ctx, e, key, key == "file" ? fs::path(environment.file) : resolved, resolved);
  std::vector<float> rgb(static_cast<size_t>(image.width) * image.height * 3);
  float brightest = 0.0f;
  for (size_t p = 0; p < rgb.size() / 3; ++p)
    for (int c = 0; c < 3; ++c) {
      // Lossy EXR compression leaves small negative values (Blender's forest.exr: -0.0016): no light.
      rgb[3 * p + c] = std::max(image.pixels[4 * p + c], 0.0f);
      brightest = std::max(brightest, rgb[3 * p + c]);
    }
  if (static_cast<double>(brightest) * environment.strength > 1e6)
    e.fail("strength", "the image's brightest value (" + shortNumber(brightest) + ") times strength must be at most 1e+06, a light's limit");
  environment.image = std::make_shared<Texture>(image.width, image.height, std::move(rgb));
  return environment;
}

// A primitive's length: at least a micrometre, at most the world's extent.
double length(JsonFields& o, const std::string& key) { return o.number(key, {limits::kMinLength, limits::kMaxLength, false, "m"}); }

Shape readShape(const std::string& type, JsonFields& o) {
  if (type == "box") {
    const Vec3 center = o.vec3("center");
    if (!o.has("size")) o.vec3("size");  // its "missing required field"
    // Lengths, not coordinates: up to the world's extent.
    const std::vector<double> size = o.numbers("size", {0.0, 0.0, 0.0}, {limits::kMinLength, limits::kMaxLength, false, "m"});
    return Box{center, Vec3(size[0], size[1], size[2]), o.number("yaw_deg", 0.0, kYawRange)};
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
    const json& vertices = requireArray(o, "vertices", false);
    for (size_t i = 0; i < vertices.size(); ++i)
      m.vertices.push_back(jsonVec3(vertices[i], o.file(), o.path(indexed("vertices", i))));
    const json& triangles = requireArray(o, "triangles", false);
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
    const json& uvs = requireArray(o, "uvs", true);
    for (size_t i = 0; i < uvs.size(); ++i) {
      const json& uv = uvs[i];
      if (!uv.is_array() || uv.size() != 2 || !uv[0].is_number() || !uv[1].is_number())
        o.fail(indexed("uvs", i), "must be [u, v]");
      const Eigen::Vector2d st(uv[0].get<double>(), uv[1].get<double>());
      if (!scene_limits::texCoordInRange(st))
        o.fail(indexed("uvs", i), "numbers must be finite and within ±1e6");
      m.uvs.push_back(st);
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
  // Two forms: explicit poses, or waypoints sampled by arc length (`frames`, default 100).
  if (p.has("poses") && (p.has("waypoints") || p.has("frames")))
    p.fail(p.has("waypoints") ? "waypoints" : "frames",
           "a path gives either \"poses\" or \"waypoints\" (with \"frames\"), not both");
  if (p.has("poses")) {
    const json& poses = p.raw("poses");
    if (!poses.is_array() || poses.empty()) p.fail("poses", "must be a non-empty array");
    for (size_t i = 0; i < poses.size(); ++i)
      path.poses.push_back(poseFromJson(poses[i], file, p.path(indexed("poses", i))));
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

// A calibration target: its board joins the objects (a textured quad) and its material the
// materials; the target itself keeps the exact pattern and pose.
void addCalibrationTarget(JsonFields& o, const std::string& name, Scene& scene, std::set<std::string>& materialNames) {
  CalibrationTarget target = readCalibrationTarget(o, name, scene.calibrationTargets);
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

// The names taken so far. Objects and lights become named nodes (glTF, Blender): one namespace;
// the materials' names are another.
// What the objects read so far hold: the names they took, and their mesh triangles (inline and
// glTF), bounded per scene, not per file: a small scene naming one large glTF many times would
// otherwise ask for memory without end.
struct SceneSoFar {
  std::set<std::string> nodes, materials;
  int64_t meshTriangles = 0;
};

// The named materials, in file order; ctx.materialIndex finds them by name. Optional: a scene of
// glTF arenas alone brings its own.
void readMaterials(JsonFields& top, Context& ctx, Scene& scene) {
  if (!top.has("materials")) return;
  JsonFields materials = top.object("materials");
  const json& materialsJson = top.raw("materials");
  for (auto it = materialsJson.begin(); it != materialsJson.end(); ++it) {
    if (it.key() == "comment") continue;
    ctx.materialIndex[it.key()] = static_cast<int>(scene.materials.size());
    scene.materials.push_back(readMaterial(it.key(), materials.object(it.key()), ctx));
  }
  materials.finish();
}

// An arena authored elsewhere: its meshes and materials join the scene, their names made
// unique (glTF does not require that) and kept within Blender's 63 bytes.
void addGltfArena(JsonFields& o, const std::string& name, const Context& ctx, Scene& scene, SceneSoFar& names) {
  o.string("type");
  const std::string gltfFile = o.string("file");
  const std::string gltfClass = readClass(o);
  GltfArena arena;
  const fs::path resolved = resolveInside(ctx, o, "file", gltfFile);  // names the field itself
  const std::string bytes = readNotedFile(ctx, o, "file", gltfFile, resolved, "load glTF");
  try {
    arena = importGltfFromMemory(bytes, resolved.string(),
                                 {ctx.options.allowOutsideFolder ? fs::path() : ctx.folder, names.meshTriangles});
  } catch (const InputError& e) {
    o.fail("file", e.what());
  }
  for (const GltfArena::FileRead& read : arena.filesRead) {
    // Named as the glTF's URI joins the glTF's own name (an absolute URI as it is).
    const fs::path uri(read.uri);
    noteFileRead(ctx, uri.is_absolute() ? uri : fs::path(gltfFile).parent_path() / uri, read.file, read.sha256);
  }
  const int offset = static_cast<int>(scene.materials.size());
  for (Material& m : arena.materials) {
    m.name = uniqueName(name + "/" + m.name, names.materials);
    scene.materials.push_back(std::move(m));
  }
  for (SceneObject& imported : arena.objects) {
    if (const Mesh* mesh = std::get_if<Mesh>(&imported.shape)) names.meshTriangles += static_cast<int64_t>(mesh->triangles.size());
    imported.name = uniqueName(name + "/" + imported.name, names.nodes);
    imported.material += offset;
    imported.semanticClass = gltfClass;
    scene.objects.push_back(std::move(imported));
  }
  o.finish();
}

// Objects and lights share one namespace. One left unnamed is called `<kind>_<index>`, which a
// named one may already have.
void takeNodeName(const JsonFields& fields, std::set<std::string>& taken, const std::string& name) {
  if (taken.insert(name).second) return;
  fields.fail("name", fields.has("name")
                          ? "duplicate name " + quote(name) + " (objects and lights share one namespace)"
                          : "not given, and its default " + quote(name) + " is another's (objects and lights share one namespace): give it a name");
}

void readObjects(JsonFields& top, const Context& ctx, Scene& scene, SceneSoFar& names) {
  const json& objects = requireArray(top, "objects", false);
  for (size_t i = 0; i < objects.size(); ++i) {
    JsonFields o(objects[i], ctx.file, indexed("objects", i));
    SceneObject obj;
    obj.name = o.string("name", "object_" + std::to_string(i));
    checkName(o, "name", obj.name);
    takeNodeName(o, names.nodes, obj.name);
    if (o.has("type") && o.raw("type") == "gltf") {
      addGltfArena(o, obj.name, ctx, scene, names);
      continue;
    }
    if (o.has("type") && o.raw("type") == "calibration_target") {
      o.string("type");
      addCalibrationTarget(o, obj.name, scene, names.materials);
      continue;
    }
    const std::string materialName = o.string("material");
    auto m = ctx.materialIndex.find(materialName);
    if (m == ctx.materialIndex.end()) {
      std::vector<std::string> materialNames;
      for (const auto& [name, index] : ctx.materialIndex) materialNames.push_back(name);
      o.fail("material", "no material named " + quote(materialName) + didYouMeanQuoted(materialName, materialNames));
    }
    obj.material = m->second;
    obj.semanticClass = readClass(o);
    obj.shape = readShape(o.string("type"), o);
    if (const Mesh* mesh = std::get_if<Mesh>(&obj.shape)) {
      names.meshTriangles += static_cast<int64_t>(mesh->triangles.size());
      if (names.meshTriangles > limits::kMaxTriangles)
        o.fail("triangles", "the scene's meshes would hold more than " + std::to_string(limits::kMaxTriangles) + " triangles");
    }
    o.finish();
    scene.objects.push_back(std::move(obj));
  }
}

void readLights(JsonFields& top, const std::string& file, Scene& scene, std::set<std::string>& nodeNames) {
  const json& lights = requireArray(top, "lights", true);
  for (size_t i = 0; i < lights.size(); ++i) {
    JsonFields l(lights[i], file, indexed("lights", i));
    PointLight light{l.string("name", "light_" + std::to_string(i)), l.vec3("position"),
                     l.colour("intensity", Vec3f::Ones(), 1e6),
                     l.number("diameter", 0.0, JsonFields::Range(0.0, 100.0, false, "m"))};
    checkName(l, "name", light.name);
    takeNodeName(l, nodeNames, light.name);
    l.finish();
    scene.lights.push_back(std::move(light));
  }
}

// Landmarks name what they mark (often an object of the same name): their own namespace.
void readLandmarks(JsonFields& top, const std::string& file, Scene& scene) {
  std::set<std::string> landmarkNames;
  const json& landmarks = requireArray(top, "landmarks", true);
  for (size_t i = 0; i < landmarks.size(); ++i) {
    JsonFields l(landmarks[i], file, indexed("landmarks", i));
    Landmark lm{l.string("name"), l.vec3("position"), length(l, "diameter"), length(l, "height"),
                l.string("colour_class")};
    checkName(l, "name", lm.name);
    if (!landmarkNames.insert(lm.name).second) l.fail("name", "duplicate landmark name " + quote(lm.name));
    l.finish();
    scene.landmarks.push_back(std::move(lm));
  }
}

void readPaths(JsonFields& top, const std::string& file, Scene& scene) {
  const json& paths = requireArray(top, "paths", true);
  for (size_t i = 0; i < paths.size(); ++i) {
    CameraPath p = readPath(JsonFields(paths[i], file, indexed("paths", i)), file);
    if (scene.findPath(p.name))
      throw InputError(showPath(file) + ": " + indexed("paths", i) + ".name: duplicate path " + quote(p.name));
    scene.paths.push_back(std::move(p));
  }
}

}  // namespace

// [x, y, yaw_deg]: x and y world coordinates, the yaw within ±kMaxYawDeg as --pose takes it.
RobotPose poseFromJson(const json& v, const std::string& file, const std::string& path) {
  if (!v.is_array() || v.size() != 3) throw InputError(showPath(file) + ": " + path + ": must be [x, y, yaw_deg]");
  const json place = {v[0], v[1], 0.0};
  const Vec3 p = jsonVec3(place, file, path);
  if (!v[2].is_number() || !(std::abs(v[2].get<double>()) <= limits::kMaxYawDeg))
    throw InputError(showPath(file) + ": " + path + "[2]: the yaw must be a number within ±" + shortNumber(limits::kMaxYawDeg) +
                     " degrees (got " + (v[2].is_number() ? roundTrip(v[2].get<double>()) : jsonTypeName(v[2])) + ")");
  return {p.x(), p.y(), v[2].get<double>()};
}

const std::string& semanticClassOf(const Scene& scene, const SceneObject& object) {
  if (!object.semanticClass.empty()) return object.semanticClass;
  return scene.materials.at(static_cast<size_t>(object.material)).semanticClass;
}

const CameraPath* Scene::findPath(const std::string& pathName) const {
  for (const auto& p : paths)
    if (p.name == pathName) return &p;
  return nullptr;
}

std::string Scene::noPathText(const std::string& pathName) const {
  std::vector<std::string> names;
  for (const CameraPath& p : paths) names.push_back(p.name);
  std::string text = "has no path " + quote(pathName);
  if (names.empty()) return text + " (it has no paths)";
  if (const std::string guess = didYouMeanQuoted(pathName, names); !guess.empty()) return text + guess;
  std::string list;
  for (const std::string& pathOfScene : names) list += (list.empty() ? "" : ", ") + quote(pathOfScene);
  return text + " (its paths: " + list + ")";
}

RigSpec rigFromJson(const nlohmann::json& rig, const std::string& file, const std::string& where) {
  // A rig given as a scene or a sidecar holds it ({"rig": {...}}): said, not "unknown field".
  if (rig.is_object() && rig.contains("rig"))
    throw InputError(fieldLocation(file, where.empty() ? "rig" : where + ".rig") +
                     ": a rig inside the rig: give the rig's own fields (height, mirror, camera, ...), not {\"rig\": ...}");
  return readRig(JsonFields(rig, file, where));
}

std::string bundledSceneHint(const std::string& name) { return bundledFileHint(name, "scenes"); }

namespace {

// Each file the scene read beyond its own text, once (by the file reached: two names of one file
// are one input, named as first written), hashed, in the order of their names: a later omnicam
// that reads them in another order describes the same scene alike.
std::vector<SceneInputFile> digestInputs(const std::vector<InputRead>& inputsRead) {
  std::vector<SceneInputFile> digests;
  std::set<std::string> files;
  for (const InputRead& read : inputsRead) {
    std::error_code ec;
    if (!files.insert(fs::weakly_canonical(fs::absolute(read.file), ec).string()).second) continue;
    digests.push_back({read.name, read.sha256});
  }
  std::sort(digests.begin(), digests.end(), [](const SceneInputFile& a, const SceneInputFile& b) { return a.path < b.path; });
  return digests;
}

}  // namespace

Scene loadScene(const std::string& file, const SceneLoadOptions& options) {
  std::string why;
  const auto text = readWholeFile(file, why, limits::kMaxJsonFileBytes);
  if (!text) throw InputError(showPath(file) + ": cannot open scene file (" + why + ")" + bundledSceneHint(file));
  return loadSceneFromText(*text, file, options);
}

Scene loadSceneFromText(const std::string& text, const std::string& file, const SceneLoadOptions& options) {
  const json root = parseJsonText(text, file);
  Scene scene;
  scene.inputFiles.push_back(file);
  std::vector<InputRead> inputsRead;
  Context ctx{file, fs::absolute(file).parent_path(), options, {}, &scene.inputFiles, &inputsRead};
  JsonFields top(root, file, "");
  scene.path = file;
  scene.sha256 = sha256OfBytes(text);
  const std::string format = top.string("format");
  if (format != kSceneFormat)
    top.fail("format", "must be \"" + std::string(kSceneFormat) + "\"" + formatMismatchHint(format, kSceneFormat) +
                           (format == kDatasetSpecFormat ? ", which names its scene in \"scene\"" : ""));
  scene.name = top.string("name", fs::path(file).stem().string());
  top.string("description", "");
  scene.background = top.colour("background", scene.background, 1e6);
  if (top.has("environment")) scene.environment = readEnvironment(top.object("environment"), ctx);
  scene.rig = top.has("rig") ? readRig(top.object("rig")) : RigSpec{};
  if (top.has("start_pose")) scene.startPose = poseFromJson(top.raw("start_pose"), file, "start_pose");
  readMaterials(top, ctx, scene);
  SceneSoFar names;
  for (const Material& m : scene.materials) names.materials.insert(m.name);
  readObjects(top, ctx, scene, names);
  readLights(top, file, scene, names.nodes);
  readLandmarks(top, file, scene);
  readPaths(top, file, scene);
  top.finish();
  scene.inputDigests = digestInputs(inputsRead);
  return scene;
}

}  // namespace omnicam
