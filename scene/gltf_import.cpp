#include "gltf_import.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <functional>
#include <optional>
#include <set>

#include "errors.h"
#include "sha256.h"
#include "file_confinement.h"
#include "image.h"
#include "input_limits.h"
#include "json_text.h"
#include "scene_limits.h"

namespace omnicam {

namespace fs = std::filesystem;

namespace {

Vec3 fromGltf(const Vec3& g) { return {g.x(), -g.z(), g.y()}; }

// What the loader's callbacks saw: the first problem, reported as our own one-line error.
struct LoadContext {
  std::string file;
  fs::path base;       // folder relative URIs resolve against
  fs::path confineTo;  // empty: anywhere
  std::string problem;
  int images = 0;
  std::vector<GltfArena::FileRead> filesRead;
};

// tinygltf looks for a URI under the glTF's folder and then under the working directory; it joins
// even an absolute URI to the folder. What the URI names, or nothing (the working directory is
// never searched: a scene means the same wherever omnicam runs).
struct UriTarget {
  std::string uri;  // as written in the glTF, for messages
  fs::path file;
};
std::optional<UriTarget> targetOf(const std::string& path, const LoadContext& ctx) {
  std::string prefix = ctx.base.string();
  if (prefix.empty() || prefix.back() != '/') prefix += '/';
  if (path.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
  std::string uri = path.substr(prefix.size());
  const fs::path file = !uri.empty() && uri.front() == '/' ? fs::path(uri) : fs::path(path);
  return UriTarget{std::move(uri), file};
}

bool outsideConfinement(const UriTarget& target, const LoadContext& ctx) {
  return !ctx.confineTo.empty() && !isInsideFolder(ctx.confineTo, target.file);
}

// A file outside the confining folder is taken to exist, so that reading it gives the one refusal
// whether or not it does: the loader's errors do not tell what lies outside the scene's folder.
bool fileExists(const std::string& path, void* user) {
  const auto* ctx = static_cast<const LoadContext*>(user);
  const auto target = targetOf(path, *ctx);
  if (!target) return false;
  if (outsideConfinement(*target, *ctx)) return true;
  std::error_code ec;
  return fs::is_regular_file(target->file, ec);
}

// tinygltf's default expands "~" and shell words; a file name is only a file name here.
std::string expandFilePath(const std::string& path, void*) { return path; }

bool readWholeFileConfined(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto* ctx = static_cast<LoadContext*>(user);
  std::string why;
  const auto target = targetOf(path, *ctx);
  if (!target) {
    why = "file not found: " + showPath(path);
  } else if (outsideConfinement(*target, *ctx)) {
    why = quote(target->uri) + " " + std::string(kOutsideFolderWords);
  } else if (const auto bytes = readWholeFile(target->file.string(), why)) {
    out->assign(bytes->begin(), bytes->end());
    ctx->filesRead.push_back({target->file.string(), target->uri, sha256OfBytes(*bytes)});  // the bytes decoded
    return true;
  }
  if (ctx->problem.empty()) ctx->problem = why;
  if (err) *err += why + "\n";
  return false;
}

bool refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not allowed while importing\n";
  return false;
}

// Images are decoded by omnicam's own reader (size limits before pixels, colour spaces), into
// linear float RGBA stored in the tinygltf image's bytes (bits = 32).
bool loadImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
               const unsigned char* bytes, int size, void* user) {
  auto* ctx = static_cast<LoadContext*>(user);
  try {
    if (++ctx->images > 4096) throw InputError("more than 4096 images");
    const ImageRGBA decoded = readFiniteImageFromMemory(bytes, static_cast<size_t>(std::max(size, 0)),
                                                  "images[" + std::to_string(index) + "]");
    image->width = decoded.width;
    image->height = decoded.height;
    image->component = 4;
    image->bits = 32;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_FLOAT;
    image->image.resize(decoded.pixels.size() * sizeof(float));
    std::memcpy(image->image.data(), decoded.pixels.data(), image->image.size());
    return true;
  } catch (const InputError& e) {
    if (ctx->problem.empty()) ctx->problem = e.what();
    if (err) *err += std::string(e.what()) + "\n";
    return false;
  }
}

Eigen::Matrix4d nodeMatrix(const tinygltf::Node& n, const std::string& where) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  const auto finite = [&](const std::vector<double>& v, size_t size, const char* field) {
    if (!v.empty() && v.size() != size) throw InputError(where + "." + field + ": must have " + std::to_string(size) + " numbers");
    for (double x : v)
      if (!std::isfinite(x) || std::abs(x) > 1e6) throw InputError(where + "." + field + ": numbers must be finite and within ±1e6");
  };
  finite(n.matrix, 16, "matrix");
  finite(n.translation, 3, "translation");
  finite(n.rotation, 4, "rotation");
  finite(n.scale, 3, "scale");
  if (n.matrix.size() == 16) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = n.matrix[c * 4 + r];  // column-major
    return m;
  }
  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  if (n.translation.size() == 3) t.translate(Vec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4) {
    const Eigen::Quaterniond q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    if (!(q.norm() > 1e-6)) throw InputError(where + ".rotation: must be a unit quaternion");
    t.rotate(q.normalized());
  }
  if (n.scale.size() == 3) t.scale(Vec3(n.scale[0], n.scale[1], n.scale[2]));
  return t.matrix();
}

enum class AccessorUse { Position, TexCoord, Index };

// One validated accessor: every element it reads lies inside its buffer view and buffer.
class AccessorReader {
 public:
  AccessorReader(const tinygltf::Model& model, int index, AccessorUse use, const std::string& where) {
    const std::string at = where + ": accessors[" + std::to_string(index) + "]";
    if (index < 0 || index >= static_cast<int>(model.accessors.size())) throw InputError(where + ": no accessor " + std::to_string(index));
    const tinygltf::Accessor& a = model.accessors[index];
    if (a.sparse.isSparse) throw InputError(at + ": sparse accessors are not supported");
    if (a.bufferView < 0 || a.bufferView >= static_cast<int>(model.bufferViews.size()))
      throw InputError(at + ".bufferView: missing or out of range");
    componentType_ = a.componentType;
    normalized_ = a.normalized;
    const bool isFloat = componentType_ == TINYGLTF_COMPONENT_TYPE_FLOAT;
    const bool isSmallUnsigned = componentType_ == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                 componentType_ == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    switch (use) {
      case AccessorUse::Position:
        if (a.type != TINYGLTF_TYPE_VEC3 || !isFloat || a.normalized)
          throw InputError(at + ": POSITION must be VEC3 of float, not normalized");
        break;
      case AccessorUse::TexCoord:
        if (a.type != TINYGLTF_TYPE_VEC2 || !(isFloat ? !a.normalized : isSmallUnsigned && a.normalized))
          throw InputError(at + ": TEXCOORD_0 must be VEC2 of float, or normalized unsigned byte/short");
        break;
      case AccessorUse::Index:
        if (a.type != TINYGLTF_TYPE_SCALAR || a.normalized ||
            !(isSmallUnsigned || componentType_ == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
          throw InputError(at + ": indices must be SCALAR unsigned byte/short/int, not normalized");
        break;
    }
    components_ = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
    componentSize_ = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(componentType_));
    const size_t elementSize = static_cast<size_t>(components_) * componentSize_;
    const tinygltf::BufferView& view = model.bufferViews[a.bufferView];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size()))
      throw InputError(at + ": its bufferView names no buffer");
    const auto& data = model.buffers[view.buffer].data;
    if (view.byteLength > data.size() || view.byteOffset > data.size() - view.byteLength)
      throw InputError(at + ": its bufferView runs past its buffer");
    stride_ = view.byteStride ? view.byteStride : elementSize;
    if (view.byteStride && (view.byteStride < elementSize || view.byteStride > 252 || view.byteStride % componentSize_))
      throw InputError(at + ": bufferView.byteStride " + std::to_string(view.byteStride) + " does not fit the element");
    if (a.count < 1 || a.count > static_cast<size_t>(3 * limits::kMaxTriangles))
      throw InputError(at + ".count: must be in [1, " + std::to_string(3 * limits::kMaxTriangles) + "]");
    // Last element's end ≤ view length, without overflow: offset + (count−1)·stride + size.
    if (a.byteOffset > view.byteLength || elementSize > view.byteLength - a.byteOffset ||
        (a.count - 1) > (view.byteLength - a.byteOffset - elementSize) / stride_)
      throw InputError(at + ": count " + std::to_string(a.count) + " runs past its bufferView");
    count_ = a.count;
    base_ = data.data() + view.byteOffset + a.byteOffset;
  }
  size_t count() const { return count_; }
  int components() const { return components_; }
  double get(size_t k, int c) const {
    const unsigned char* p = base_ + k * stride_ + static_cast<size_t>(c) * componentSize_;
    switch (componentType_) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load<uint32_t>(p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load<uint16_t>(p) / (normalized_ ? 65535.0 : 1.0);
      default: return load<uint8_t>(p) / (normalized_ ? 255.0 : 1.0);
    }
  }

 private:
  template <typename T>
  static double load(const unsigned char* p) {
    T v;
    std::memcpy(&v, p, sizeof v);  // glTF allows any alignment within a view
    return static_cast<double>(v);
  }
  const unsigned char* base_ = nullptr;
  int componentType_ = 0, components_ = 1, componentSize_ = 4;
  bool normalized_ = false;
  size_t stride_ = 0, count_ = 0;
};

std::shared_ptr<const Texture> textureOf(const tinygltf::Model& model, int textureIndex, const std::string& where) {
  if (textureIndex < 0) return nullptr;
  if (textureIndex >= static_cast<int>(model.textures.size())) throw InputError(where + ": no texture " + std::to_string(textureIndex));
  const int source = model.textures[textureIndex].source;
  if (source < 0 || source >= static_cast<int>(model.images.size()))
    throw InputError(where + ": texture " + std::to_string(textureIndex) + " has no image");
  const tinygltf::Image& image = model.images[source];
  const size_t pixels = static_cast<size_t>(std::max(image.width, 0)) * static_cast<size_t>(std::max(image.height, 0));
  if (image.bits != 32 || image.component != 4 || pixels == 0 || image.image.size() != pixels * 4 * sizeof(float)) {
    // tinygltf only warns about an image file it could not find (or found empty); a file it
    // found but could not decode was refused by loadImage already.
    const bool fromFile = image.bufferView < 0 && !image.uri.empty() && image.uri.rfind("data:", 0) != 0;
    throw InputError(where + ": image " + std::to_string(source) +
                     (fromFile ? " " + quote(image.uri) + ": file not found or empty" : " holds no decodable pixels"));
  }
  std::vector<float> rgba(pixels * 4);
  std::memcpy(rgba.data(), image.image.data(), image.image.size());
  return Texture::fromPremultiplied(image.width, image.height, rgba.data(), where + ": image " + std::to_string(source));
}

bool isOmnicamRig(const tinygltf::Node& node) {
  if (!node.extras.IsObject() || !node.extras.Has("omnicam")) return false;
  const tinygltf::Value& o = node.extras.Get("omnicam");
  return o.IsObject() && o.Has("role") && o.Get("role").IsString() && o.Get("role").Get<std::string>() == "rig";
}

float extraFactor(const tinygltf::Value& o, const char* key, float fallback, const std::string& where) {
  if (!o.Has(key)) return fallback;
  const tinygltf::Value& v = o.Get(key);
  const double d = v.IsNumber() || v.IsInt() ? v.GetNumberAsDouble() : -1.0;
  if (!(d >= 0.0 && d <= scene_limits::kMaxShadingFactor))
    throw InputError(where + ".extras.omnicam." + key + ": must be a number in [0, 1000]");
  return static_cast<float>(d);
}

// Emitted radiance: emissiveFactor times KHR_materials_emissive_strength, as omnicam exports it,
// within the scene format's emission range. An emissive texture omnicam cannot represent: such a
// material emits nothing here (its factor scales the texture, not a uniform glow).
Vec3f emissionOf(const tinygltf::Material& m, const std::string& where) {
  if (m.emissiveTexture.index >= 0) return Vec3f::Zero();
  double strength = 1.0;
  if (const auto ext = m.extensions.find("KHR_materials_emissive_strength"); ext != m.extensions.end()) {
    const tinygltf::Value& v = ext->second;
    const tinygltf::Value& s = v.IsObject() && v.Has("emissiveStrength") ? v.Get("emissiveStrength") : tinygltf::Value();
    strength = s.IsNumber() || s.IsInt() ? s.GetNumberAsDouble() : -1.0;
    if (!(strength >= 0.0 && strength <= 1e6))
      throw InputError(where + ".extensions.KHR_materials_emissive_strength.emissiveStrength: must be a number in [0, 1000000]");
  }
  const auto& e = m.emissiveFactor;
  Vec3f emission = Vec3f::Zero();
  if (e.size() != 3) throw InputError(where + ".emissiveFactor: must have 3 numbers");
  for (size_t c = 0; c < 3; ++c) {  // clamped into glTF's [0, 1], as the base colour is
    const double factor = std::isfinite(e[c]) ? std::clamp(e[c], 0.0, 1.0) : 0.0;
    emission[static_cast<int>(c)] = static_cast<float>(std::min(factor * strength, 1e6));
  }
  return emission;
}

Material convertMaterial(const tinygltf::Model& model, size_t i, const std::string& file) {
  const auto& m = model.materials[i];
  const std::string where = file + ": materials[" + std::to_string(i) + "]";
  Material mat;
  mat.name = m.name.empty() ? "material_" + std::to_string(i) : m.name;
  const auto& f = m.pbrMetallicRoughness.baseColorFactor;
  if (f.size() != 4) throw InputError(where + ".baseColorFactor: must have 4 numbers");
  for (int c = 0; c < 3; ++c)
    mat.color[c] = static_cast<float>(std::isfinite(f[c]) ? std::clamp(f[c], 0.0, 1.0) : 0.0);
  if (m.pbrMetallicRoughness.baseColorTexture.index >= 0 && m.pbrMetallicRoughness.baseColorTexture.texCoord != 0)
    throw InputError(where + ".pbrMetallicRoughness.baseColorTexture.texCoord: only 0 (TEXCOORD_0) is read");
  mat.texture = textureOf(model, m.pbrMetallicRoughness.baseColorTexture.index, where);
  mat.emission = emissionOf(m, where);
  // omnicam's own exports carry the lit-shading factors in extras.
  if (m.extras.IsObject() && m.extras.Has("omnicam") && m.extras.Get("omnicam").IsObject()) {
    const auto& o = m.extras.Get("omnicam");
    mat.ambient = extraFactor(o, "ambient", mat.ambient, where);
    mat.diffuse = extraFactor(o, "diffuse", mat.diffuse, where);
  }
  return mat;
}

// A primitive's TEXCOORD_0, if it has one, one per vertex; v flipped (glTF's origin is top left).
void appendTexCoords(const tinygltf::Model& model, const tinygltf::Primitive& prim, size_t vertexCount,
                     const std::string& where, Mesh& out) {
  auto uv = prim.attributes.find("TEXCOORD_0");
  if (uv == prim.attributes.end()) return;
  const AccessorReader t(model, uv->second, AccessorUse::TexCoord, where);
  if (t.count() != vertexCount)
    throw InputError(where + ": TEXCOORD_0 has " + std::to_string(t.count()) + " entries for " +
                     std::to_string(vertexCount) + " vertices");
  for (size_t k = 0; k < t.count(); ++k) {
    const Eigen::Vector2d st(t.get(k, 0), 1.0 - t.get(k, 1));
    if (!scene_limits::texCoordInRange(st))
      throw InputError(where + ": TEXCOORD_0 must be finite and within ±1e6");
    out.uvs.push_back(st);
  }
}

// The primitive's triangles: its indices in threes, or without indices its vertices in threes.
void appendTriangles(const tinygltf::Model& model, const tinygltf::Primitive& prim, const std::string& where,
                     Mesh& out) {
  const auto vertexCount = static_cast<double>(out.vertices.size());
  if (prim.indices >= 0) {
    const AccessorReader idx(model, prim.indices, AccessorUse::Index, where);
    if (idx.count() % 3) throw InputError(where + ": index count " + std::to_string(idx.count()) + " is not a multiple of 3");
    for (size_t k = 0; k < idx.count(); k += 3) {
      Eigen::Vector3i tri;
      for (int c = 0; c < 3; ++c) {
        const double i = idx.get(k + c, 0);
        if (!(i < vertexCount)) throw InputError(where + ": index " + std::to_string(k + c) + " out of range");
        tri[c] = static_cast<int>(i);
      }
      out.triangles.push_back(tri);
    }
  } else {
    if (out.vertices.size() % 3) throw InputError(where + ": vertex count is not a multiple of 3 (no indices)");
    for (size_t k = 0; k + 2 < out.vertices.size(); k += 3)
      out.triangles.emplace_back(static_cast<int>(k), static_cast<int>(k + 1), static_cast<int>(k + 2));
  }
}

// A triangle primitive as a mesh in omnicam's world frame (`world`: the node's glTF transform).
Mesh primitiveMesh(const tinygltf::Model& model, const tinygltf::Primitive& prim, const Eigen::Matrix4d& world,
                   const std::string& where) {
  if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1)
    throw InputError(where + ".mode: only TRIANGLES (mode 4) is read (got mode " + std::to_string(prim.mode) +
                     "; strips, fans, lines and points are not; re-export with triangulated meshes)");
  auto position = prim.attributes.find("POSITION");
  if (position == prim.attributes.end()) throw InputError(where + ": no POSITION");
  Mesh out;
  const AccessorReader pos(model, position->second, AccessorUse::Position, where);
  for (size_t k = 0; k < pos.count(); ++k) {
    const Eigen::Vector4d g = world * Eigen::Vector4d(pos.get(k, 0), pos.get(k, 1), pos.get(k, 2), 1.0);
    const Vec3 v = fromGltf(g.head<3>());
    if (!v.allFinite() || v.cwiseAbs().maxCoeff() > limits::kMaxWorldCoordinate)
      throw InputError(where + ": vertex " + std::to_string(k) + " lies beyond ±" +
                       std::to_string(static_cast<int>(limits::kMaxWorldCoordinate)) + " m");
    out.vertices.push_back(v);
  }
  appendTexCoords(model, prim, pos.count(), where, out);
  appendTriangles(model, prim, where, out);
  return out;
}

// The walk down the default scene's node trees, each mesh primitive becoming an arena object.
class NodeWalk {
 public:
  NodeWalk(const tinygltf::Model& model, const std::string& file, GltfArena& arena, int64_t trianglesBefore)
      : model_(model), file_(file), arena_(arena), trianglesBefore_(trianglesBefore), triangles_(trianglesBefore) {}

  void visit(int nodeIndex, const Eigen::Matrix4d& parent, int depth) {
    const std::string nodeWhere = file_ + ": nodes[" + std::to_string(nodeIndex) + "]";
    if (nodeIndex < 0 || nodeIndex >= static_cast<int>(model_.nodes.size())) throw InputError(nodeWhere + ": out of range");
    if (!visited_.insert(nodeIndex).second) throw InputError(nodeWhere + ": reached twice (node graphs must be trees)");
    if (depth > 256) throw InputError(nodeWhere + ": nested deeper than 256 levels");
    const tinygltf::Node& node = model_.nodes[nodeIndex];
    if (isOmnicamRig(node)) return;  // an exported camera rig, not arena geometry
    const Eigen::Matrix4d world = parent * nodeMatrix(node, nodeWhere);
    if (node.mesh >= static_cast<int>(model_.meshes.size())) throw InputError(nodeWhere + ".mesh: out of range");
    if (node.mesh >= 0)
      for (size_t pi = 0; pi < model_.meshes[node.mesh].primitives.size(); ++pi) addPrimitive(node, pi, world);
    for (int child : node.children) visit(child, world, depth + 1);
  }

 private:
  void addPrimitive(const tinygltf::Node& node, size_t pi, const Eigen::Matrix4d& world) {
    const tinygltf::Mesh& mesh = model_.meshes[node.mesh];
    const tinygltf::Primitive& prim = mesh.primitives[pi];
    const std::string where = file_ + ": meshes[" + std::to_string(node.mesh) + "].primitives[" + std::to_string(pi) + "]";
    Mesh out = primitiveMesh(model_, prim, world, where);
    triangles_ += static_cast<int64_t>(out.triangles.size());
    if (triangles_ > limits::kMaxTriangles)
      throw InputError(file_ + ": more than " + std::to_string(limits::kMaxTriangles) + " triangles" +
                       (trianglesBefore_ > 0 ? " with the " + std::to_string(trianglesBefore_) + " the scene holds before it" : ""));
    int material = prim.material;
    if (material >= static_cast<int>(model_.materials.size())) throw InputError(where + ".material: out of range");
    if (material < 0) {
      if (defaultMaterial_ < 0) {
        defaultMaterial_ = static_cast<int>(arena_.materials.size());
        arena_.materials.push_back(Material{"default", {1.0f, 1.0f, 1.0f}, nullptr, "", {1, 1}, 0.2f, 0.8f, ""});
      }
      material = defaultMaterial_;
    }
    if (arena_.materials[static_cast<size_t>(material)].texture && out.uvs.empty())
      throw InputError(where + ": its material's baseColorTexture needs TEXCOORD_0, which the primitive lacks");
    const std::string name = !node.name.empty() ? node.name : !mesh.name.empty() ? mesh.name : "mesh_" + std::to_string(node.mesh);
    arena_.objects.push_back({name, material, std::move(out), ""});
  }

  const tinygltf::Model& model_;
  const std::string& file_;
  GltfArena& arena_;
  int defaultMaterial_ = -1;
  const int64_t trianglesBefore_;
  int64_t triangles_;
  std::set<int> visited_;  // glTF node graphs are trees: a node reached twice is invalid
};

GltfArena convert(const tinygltf::Model& model, const std::string& path, int64_t trianglesBefore) {
  const std::string file = showPath(path);  // prefixes every message
  // A required extension changes what the file means; omnicam reads only the one below.
  for (const std::string& extension : model.extensionsRequired)
    if (extension != "KHR_materials_emissive_strength")
      throw InputError(file + ": extensionsRequired: " + quote(extension) +
                       " is not supported (omnicam reads KHR_materials_emissive_strength only)");
  GltfArena arena;
  for (size_t i = 0; i < model.materials.size(); ++i) arena.materials.push_back(convertMaterial(model, i, file));
  if (model.scenes.empty()) throw InputError(file + ": no scene in the glTF file");
  const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (sceneIndex >= static_cast<int>(model.scenes.size())) throw InputError(file + ": scene: out of range");
  NodeWalk walk(model, file, arena, trianglesBefore);
  for (int root : model.scenes[sceneIndex].nodes) walk.visit(root, Eigen::Matrix4d::Identity(), 0);
  return arena;
}

// The JSON of a glTF file: all of a .gltf, the JSON chunk of a well-formed .glb (tinygltf
// reports what is wrong with any other).
std::optional<std::string> gltfJson(const std::string& bytes, bool binary) {
  if (!binary) return bytes;
  if (bytes.size() < 20) return std::nullopt;
  uint32_t length = 0, type = 0;  // little-endian, like the host
  std::memcpy(&length, bytes.data() + 12, 4);
  std::memcpy(&type, bytes.data() + 16, 4);
  if (type != 0x4E4F534Au || length > bytes.size() - 20) return std::nullopt;
  return bytes.substr(20, length);
}

GltfArena load(const std::string& path, const std::string* bytes, const GltfImportOptions& options) {
  LoadContext ctx;
  ctx.file = path;
  ctx.base = fs::absolute(path).parent_path();
  ctx.confineTo = options.confineTo;
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({fileExists, expandFilePath, readWholeFileConfined, refuseWrite, &ctx});
  loader.SetImageLoader(loadImage, &ctx);
  tinygltf::Model model;
  std::string error, warning;
  std::string owned;
  if (!bytes) {
    std::string why;
    const auto read = readWholeFile(path, why);
    if (!read) throw InputError(showPath(path) + ": cannot load glTF (" + why + ")");
    owned = *read;
    bytes = &owned;
  }
  const bool binary = bytes->size() >= 4 && bytes->compare(0, 4, "glTF") == 0;
  // A .glb is binary glTF: one without its header is not a glTF at all, not JSON gone wrong.
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (!binary && extension == ".glb")
    throw InputError(showPath(path) + ": cannot load glTF (a .glb file starts with \"glTF\"; this one does not)");
  // Like every JSON input: bounded depth (tinygltf reads extras recursively), no duplicate keys.
  if (const auto json = gltfJson(*bytes, binary)) checkJsonText(*json, path);
  const auto* data = reinterpret_cast<const unsigned char*>(bytes->data());
  const std::string baseDir = ctx.base.string();
  bool ok = false;
  try {
    ok = binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, data, static_cast<unsigned>(bytes->size()), baseDir)
                : loader.LoadASCIIFromString(&model, &error, &warning, bytes->data(), static_cast<unsigned>(bytes->size()), baseDir);
  } catch (const std::exception& e) {  // tinygltf's JSON parser throws on some malformed input
    throw InputError(showPath(path) + ": cannot load glTF (" + e.what() + ")");
  }
  if (!ctx.problem.empty()) throw InputError(showPath(path) + ": " + ctx.problem);
  if (!ok) {
    std::string line = error.substr(0, error.find('\n'));
    throw InputError(showPath(path) + ": cannot load glTF (" + (line.empty() ? "invalid file" : line) + ")");
  }
  GltfArena arena = convert(model, path, options.trianglesBefore);
  arena.filesRead = std::move(ctx.filesRead);
  return arena;
}

}  // namespace

GltfArena importGltf(const std::string& path, const GltfImportOptions& options) { return load(path, nullptr, options); }

GltfArena importGltfFromMemory(const std::string& bytes, const std::string& path, const GltfImportOptions& options) {
  return load(path, &bytes, options);
}

}  // namespace omnicam
