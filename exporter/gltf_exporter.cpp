#include "gltf_exporter.h"

#include <algorithm>
#include <iterator>

#include <tiny_gltf.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <nlohmann/json.hpp>

#include "atomic_file.h"
#include "engine_capabilities.h"
#include "errors.h"
#include "image.h"
#include "lens_camera.h"
#include "make_camera.h"
#include "mirror_mesh.h"
#include "physical_camera.h"
#include "placement.h"
#include "sidecar.h"
#include "texture_image.h"
#include "triangulate.h"

namespace omnicam {

namespace {

namespace fs = std::filesystem;
using Vec3f = Eigen::Vector3f;

// omnicam (X, Y, Z) → glTF (X, Z, −Y).
Vec3 toGltf(const Vec3& p) { return {p.x(), p.z(), -p.y()}; }
Eigen::Matrix3d gltfFromOmnicam() {
  Eigen::Matrix3d g;
  g << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  return g;
}

tinygltf::Value toValue(const nlohmann::json& j) {
  if (j.is_object()) {
    tinygltf::Value::Object o;
    for (auto it = j.begin(); it != j.end(); ++it) o[it.key()] = toValue(it.value());
    return tinygltf::Value(o);
  }
  if (j.is_array()) {
    tinygltf::Value::Array a;
    for (const auto& v : j) a.push_back(toValue(v));
    return tinygltf::Value(a);
  }
  if (j.is_boolean()) return tinygltf::Value(j.get<bool>());
  if (j.is_number_integer()) return tinygltf::Value(j.get<int>());
  if (j.is_number()) return tinygltf::Value(j.get<double>());
  if (j.is_string()) return tinygltf::Value(j.get<std::string>());
  return {};
}

class GltfBuilder {
 public:
  GltfBuilder() {
    model_.asset.version = "2.0";
    model_.asset.generator = "omnicam";
    model_.buffers.emplace_back();
    model_.scenes.emplace_back();
    model_.defaultScene = 0;
  }

  int bufferView(const void* data, size_t bytes, int target) {
    auto& buffer = model_.buffers[0].data;
    while (buffer.size() % 4) buffer.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.size();
    view.byteLength = bytes;
    view.target = target;
    const auto* bytesIn = static_cast<const unsigned char*>(data);
    buffer.insert(buffer.end(), bytesIn, bytesIn + bytes);
    model_.bufferViews.push_back(view);
    return static_cast<int>(model_.bufferViews.size()) - 1;
  }

  int vec3Accessor(const std::vector<float>& xyz, bool withBounds) {
    tinygltf::Accessor a;
    a.bufferView = bufferView(xyz.data(), xyz.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.type = TINYGLTF_TYPE_VEC3;
    a.count = xyz.size() / 3;
    if (withBounds) {
      a.minValues = {INFINITY, INFINITY, INFINITY};
      a.maxValues = {-INFINITY, -INFINITY, -INFINITY};
      for (size_t k = 0; k < xyz.size(); ++k) {
        a.minValues[k % 3] = std::min(a.minValues[k % 3], static_cast<double>(xyz[k]));
        a.maxValues[k % 3] = std::max(a.maxValues[k % 3], static_cast<double>(xyz[k]));
      }
    }
    model_.accessors.push_back(a);
    return static_cast<int>(model_.accessors.size()) - 1;
  }

  int vec2Accessor(const std::vector<float>& uv) {
    tinygltf::Accessor a;
    a.bufferView = bufferView(uv.data(), uv.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.type = TINYGLTF_TYPE_VEC2;
    a.count = uv.size() / 2;
    model_.accessors.push_back(a);
    return static_cast<int>(model_.accessors.size()) - 1;
  }

  int indexAccessor(const std::vector<uint32_t>& indices) {
    tinygltf::Accessor a;
    a.bufferView = bufferView(indices.data(), indices.size() * sizeof(uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    a.type = TINYGLTF_TYPE_SCALAR;
    a.count = indices.size();
    model_.accessors.push_back(a);
    return static_cast<int>(model_.accessors.size()) - 1;
  }

  // A mesh from triangles in omnicam coordinates (converted here); normals optional.
  // `uvScale` null: no texture coordinates (the material has no texture).
  int mesh(const std::string& name, const TriangleMesh& m, const std::vector<Vec3>* normals, int material,
           const Eigen::Vector2d* uvScale) {
    std::vector<float> xyz, nrm, uv;
    for (const Vec3& v : m.vertices) {
      const Vec3 g = toGltf(v);
      xyz.insert(xyz.end(), {static_cast<float>(g.x()), static_cast<float>(g.y()), static_cast<float>(g.z())});
    }
    if (normals)
      for (const Vec3& n : *normals) {
        const Vec3 g = toGltf(n);
        nrm.insert(nrm.end(), {static_cast<float>(g.x()), static_cast<float>(g.y()), static_cast<float>(g.z())});
      }
    // glTF's UV origin is the image's top-left; omnicam's (like POV-Ray's) the bottom-left.
    if (uvScale)
      for (const auto& t : m.uvs)
        uv.insert(uv.end(), {static_cast<float>(t.x() * uvScale->x()), static_cast<float>(1.0 - t.y() * uvScale->y())});
    std::vector<uint32_t> indices;
    for (const auto& t : m.triangles)
      indices.insert(indices.end(), {static_cast<uint32_t>(t[0]), static_cast<uint32_t>(t[1]), static_cast<uint32_t>(t[2])});
    tinygltf::Primitive p;
    p.attributes["POSITION"] = vec3Accessor(xyz, true);
    if (normals) p.attributes["NORMAL"] = vec3Accessor(nrm, false);
    if (uvScale) p.attributes["TEXCOORD_0"] = vec2Accessor(uv);
    p.indices = indexAccessor(indices);
    p.material = material;
    p.mode = TINYGLTF_MODE_TRIANGLES;
    tinygltf::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(p);
    model_.meshes.push_back(mesh);
    return static_cast<int>(model_.meshes.size()) - 1;
  }

  int texture(const std::string& name, const std::vector<unsigned char>& png) {
    tinygltf::Image image;
    image.name = name;
    image.mimeType = "image/png";
    image.bufferView = bufferView(png.data(), png.size(), 0);
    model_.images.push_back(image);
    if (model_.samplers.empty()) {
      tinygltf::Sampler s;  // bilinear, no mipmaps, repeat: what the other engines do
      s.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
      s.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
      s.wrapS = s.wrapT = TINYGLTF_TEXTURE_WRAP_REPEAT;
      model_.samplers.push_back(s);
    }
    tinygltf::Texture t;
    t.sampler = 0;
    t.source = static_cast<int>(model_.images.size()) - 1;
    model_.textures.push_back(t);
    return static_cast<int>(model_.textures.size()) - 1;
  }

  int material(const std::string& name, const Vec3f& colour, int texture, double metallic, double roughness,
               const nlohmann::json& extras) {
    tinygltf::Material m;
    m.name = name;
    m.pbrMetallicRoughness.baseColorFactor = {colour.x(), colour.y(), colour.z(), 1.0};
    m.pbrMetallicRoughness.baseColorTexture.index = texture;
    m.pbrMetallicRoughness.metallicFactor = metallic;
    m.pbrMetallicRoughness.roughnessFactor = roughness;
    m.doubleSided = true;
    m.extras = toValue(extras);
    model_.materials.push_back(m);
    return static_cast<int>(model_.materials.size()) - 1;
  }

  // Emitted radiance as glTF has it: a factor in [0, 1] times KHR_materials_emissive_strength.
  void setEmission(int material, const Vec3f& emission) {
    const float strength = emission.maxCoeff();
    if (!(strength > 0.0f)) return;
    tinygltf::Material& m = model_.materials[material];
    const Vec3f factor = emission / strength;
    m.emissiveFactor = {factor.x(), factor.y(), factor.z()};
    if (strength != 1.0f) {
      tinygltf::Value::Object ext;
      ext["emissiveStrength"] = tinygltf::Value(static_cast<double>(strength));
      m.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(ext);
      auto& used = model_.extensionsUsed;
      if (std::find(used.begin(), used.end(), "KHR_materials_emissive_strength") == used.end())
        used.push_back("KHR_materials_emissive_strength");
    }
  }

  // A node with a rigid transform given in omnicam coordinates. `cameraAxes`: the node's own
  // axes are glTF camera axes (view −Z, up +Y), which no axis conversion applies to, so only
  // the parent side is converted.
  int node(const std::string& name, const Rigid& parentFromNode, int mesh, const nlohmann::json& extras,
           bool cameraAxes = false) {
    tinygltf::Node n;
    n.name = name;
    n.mesh = mesh;
    const Eigen::Matrix3d g = gltfFromOmnicam();
    const Vec3 t = g * parentFromNode.translation();
    const Eigen::Quaterniond q(cameraAxes ? Eigen::Matrix3d(g * parentFromNode.linear())
                                          : Eigen::Matrix3d(g * parentFromNode.linear() * g.transpose()));
    if (t.norm() > 0.0) n.translation = {t.x(), t.y(), t.z()};
    if (std::abs(q.w()) < 1.0 - 1e-15) n.rotation = {q.x(), q.y(), q.z(), q.w()};
    if (!extras.is_null()) n.extras = toValue(extras);
    model_.nodes.push_back(n);
    return static_cast<int>(model_.nodes.size()) - 1;
  }

  void addChild(int parent, int child) { model_.nodes[parent].children.push_back(child); }
  void addRoot(int node) { model_.scenes[0].nodes.push_back(node); }
  tinygltf::Model& model() { return model_; }

 private:
  tinygltf::Model model_;
};

// Encoded in memory: no temporary file another user could predict or read.
std::vector<unsigned char> pngBytes(const Texture& t) { return encodeImage("texture.png", opaqueImage(t)); }

// An annulus in the viewpoint frame at the rim height: what the camera sees beyond the rim.
TriangleMesh rimMask(double rimHeight, double innerRadius) {
  return tessellate(Disc{{0.0, 0.0, rimHeight}, {0.0, 0.0, -1.0}, innerRadius + 1.0, innerRadius}, 1e-7 + innerRadius * 1e-4);
}

}  // namespace

namespace {

// The rig's root node at the viewpoint, with the rig, pose and intrinsics in its extras.
int addRigNode(GltfBuilder& b, const GltfExportOptions& options, const char* frame) {
  const int rig = b.node(kGltfRigNode, options.placement.worldFromViewpoint(options.rig), -1,
                         {{"omnicam",
                           {{"role", "rig"},
                            {"rig", rigToJson(options.rig)},
                            {"pose", footPoseToJson(options.placement.footAt(0.0))},
                            {"intrinsics", makeCamera(options.rig)->describe()},
                            {"frame", frame}}}});
  b.addRoot(rig);
  return rig;
}

// The rig's camera: a glTF perspective camera whose axes are `viewpointFromCamera`'s (x image
// right, y image down, z optical axis) with y and z flipped, as glTF cameras look along −Z with
// +Y up; what glTF cannot say travels in `extras`.
void addCameraNode(GltfBuilder& b, int rig, double yfov, double aspectRatio, const Rigid& viewpointFromCamera,
                   const nlohmann::json& extras) {
  tinygltf::Camera cam;
  cam.name = kGltfCameraNode;
  cam.type = "perspective";
  cam.perspective.aspectRatio = aspectRatio;
  cam.perspective.yfov = yfov;
  cam.perspective.znear = 1e-4;
  cam.perspective.zfar = 1e4;  // tinygltf would write 0, which the validator rejects
  b.model().cameras.push_back(cam);
  Rigid viewpointFromGltfCamera = viewpointFromCamera;
  viewpointFromGltfCamera.linear() = viewpointFromCamera.linear() * Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  const int camNode = b.node(kGltfCameraNode, viewpointFromGltfCamera, -1, {{"omnicam", extras}}, true);
  b.model().nodes[camNode].camera = static_cast<int>(b.model().cameras.size()) - 1;
  b.addChild(rig, camNode);
}

// A lens camera's rig: the rig node at the viewpoint and its camera, no mirror. glTF cameras look
// along −Z with +Y up: the lens' axes (x right, y down, z forward) with y and z flipped. glTF has
// only the pinhole: a lens travels in the node's extras ("lens", the sidecar's intrinsics), which
// Blender's job turns into its panoramic camera.
void addLensRig(GltfBuilder& b, const GltfExportOptions& options, const LensCameraSpec& lens) {
  const int rig = addRigNode(b, options, "viewpoint: origin at the lens' centre of projection, robot axes (x forward, y left, z up)");
  const auto* pinhole = std::get_if<PinholeRadTan>(&lens.model);
  const double yfov = pinhole ? 2.0 * std::atan(0.5 * lens.height / pinhole->fy) : kPi / 2;  // a stand-in for the others
  Rigid viewpointFromLensFrame = Rigid::Identity();
  viewpointFromLensFrame.linear() = viewpointFromLens(lens);
  addCameraNode(b, rig, yfov, static_cast<double>(lens.width) / lens.height, viewpointFromLensFrame,
                {{"role", "camera"}, {"lens", lensIntrinsicsJson(lens)}});
}

// The scene's materials, and its objects tessellated under one "arena" node.
void addArena(GltfBuilder& b, const Scene& scene, double chordTolerance) {
  std::vector<int> materials;
  for (size_t index = 0; index < scene.materials.size(); ++index) {
    const Material& m = scene.materials[index];
    const int texture = m.texture ? b.texture(m.name, pngBytes(*m.texture)) : -1;
    // The material's index in the scene: Blender's job names its linear texture by it.
    materials.push_back(b.material(m.name, m.color, texture, 0.0, 1.0,
                                   {{"omnicam", {{"ambient", m.ambient}, {"diffuse", m.diffuse}, {"material_index", index}}}}));
    b.setEmission(materials.back(), m.emission);
  }
  const int arena = b.node("arena", Rigid::Identity(), -1, {{"omnicam", {{"scene", scene.name}}}});
  b.addRoot(arena);
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    const TriangleMesh mesh = tessellate(o.shape, chordTolerance);
    const Material& material = scene.materials[o.material];
    const int meshIndex = b.mesh(o.name, mesh, nullptr, materials[o.material], material.texture ? &material.textureScale : nullptr);
    b.addChild(arena, b.node(o.name, Rigid::Identity(), meshIndex, nullptr));
  }
}

// Point lights (KHR_lights_punctual), each a root node.
void addLights(GltfBuilder& b, const Scene& scene) {
  for (const PointLight& l : scene.lights) {
    tinygltf::Light light;
    light.name = l.name;
    light.type = "point";
    const float peak = std::max(1e-6f, l.intensity.maxCoeff());
    light.color = {l.intensity.x() / peak, l.intensity.y() / peak, l.intensity.z() / peak};
    light.intensity = peak;  // omnicam lights have no fall-off: consumers scale as they see fit
    b.model().lights.push_back(light);
    Rigid at = Rigid::Identity();
    at.translate(l.position);
    // Consumers (the Blender driver) find lights by this index, never by name.
    const int node = b.node(l.name, at, -1,
                            {{"omnicam", {{"role", "light"}, {"light_index", b.model().lights.size() - 1},
                                          {"light", "point, no distance fall-off"}}}});
    tinygltf::Value::Object ext;
    ext["light"] = tinygltf::Value(static_cast<int>(b.model().lights.size()) - 1);
    b.model().nodes[node].extensions["KHR_lights_punctual"] = tinygltf::Value(ext);
    b.addRoot(node);
  }
  if (!scene.lights.empty()) b.model().extensionsUsed.push_back("KHR_lights_punctual");
}

// Landmarks as empty root nodes whose extras say what they mark.
void addLandmarks(GltfBuilder& b, const Scene& scene) {
  for (size_t i = 0; i < scene.landmarks.size(); ++i) {
    const Landmark& lm = scene.landmarks[i];
    Rigid at = Rigid::Identity();
    at.translate(lm.position);
    // Landmarks often share the name of the object they mark; their nodes get their own names.
    b.addRoot(b.node("landmark_" + std::to_string(i), at, -1,
                     {{"omnicam", {{"role", "landmark"}, {"name", lm.name}, {"colour_class", lm.colourClass},
                                   {"diameter", lm.diameter}, {"height", lm.height}}}}));
  }
}

// The mirror and its rim are the ideal rig's whatever the camera; the camera is the physical
// pinhole as mounted (physical_camera.h), modelled once for every exporter.
void addMirrorRig(GltfBuilder& b, const GltfExportOptions& options, const MirrorRig& mirror) {
  const Pinhole pinhole = pinholeOf(mirror);
  const MirrorMesh mirrorMesh = buildMirrorMesh(mirror, options.mirrorDeviation);  // checkGltfMirror: a certified shape
  const int rig = addRigNode(b, options, "viewpoint: origin at the mirror's design point (the hyperboloid's F', the sphere's centre), robot axes (x forward, y left, z up)");
  const int mirrorMaterial = b.material(kGltfMirrorNode, Vec3f::Ones(), -1, 1.0, 0.0, {{"omnicam", "perfect mirror"}});
  b.addChild(rig, b.node(kGltfMirrorNode, Rigid::Identity(),
                         b.mesh(kGltfMirrorNode, mirrorMesh.mesh, &mirrorMesh.normals, mirrorMaterial, nullptr),
                         {{"omnicam",
                           {{"role", "mirror"},
                            {"certified_max_deviation_m", mirrorMesh.requestedBound},
                            {"rings", mirrorMesh.rings},
                            {"sectors", mirrorMesh.sectors}}}}));
  const Vec3 rimPoint = mirrorMesh.mesh.vertices.back();
  const int maskMaterial = b.material(kGltfRimMaskNode, Vec3f::Zero(), -1, 0.0, 1.0,
                                      {{"omnicam", "black, seen only by the camera"}});
  b.addChild(rig, b.node(kGltfRimMaskNode, Rigid::Identity(),
                         b.mesh(kGltfRimMaskNode, rimMask(rimPoint.z(), std::hypot(rimPoint.x(), rimPoint.y())),
                                nullptr, maskMaterial, nullptr),
                         {{"omnicam", {{"role", "rim_mask"}}}}));
  // The pinhole looking up. glTF has no principal point: it travels in the node's extras
  // (Blender's job shifts the lens by it). Square images.
  Rigid viewpointFromPinhole = Rigid::Identity();
  viewpointFromPinhole.translate(pinhole.position);
  viewpointFromPinhole.linear() = pinhole.viewpointFromPinhole;
  addCameraNode(b, rig, 2.0 * std::atan(0.5 * mirror.imageSize / pinhole.focalPx), 1.0, viewpointFromPinhole,
                {{"role", "camera"},
                 {"focal_length_px", pinhole.focalPx},
                 {"principal_point_px", {pinhole.principalPoint.x(), pinhole.principalPoint.y()}}});
}

}  // namespace

namespace {

void checkGltfMirror(const MirrorRig& rig) {
  if (std::find(std::begin(kCertifiedMeshShapes), std::end(kCertifiedMeshShapes), rig.shapeKind()) == std::end(kCertifiedMeshShapes)) {
    std::string certified;
    for (MirrorShape shape : kCertifiedMeshShapes) certified += (certified.empty() ? "the " : " and the ") + std::string(mirrorShapeName(shape));
    throw InputError("rig.mirror.shape: the glTF export (and Blender) has certified meshes of " + certified + " only, not of a " +
                     mirrorShapeName(rig.shape) + "; render it with the fast renderer or POV-Ray");
  }
  if (!rig.mount.distortion.none())
    throw InputError("rig.camera.distortion: glTF cameras (and Blender's) have no lens distortion; render it with "
                     "the fast renderer");
}

}  // namespace

void checkGltfCamera(const RigSpec& rig) {
  std::visit(Overloaded{[](const MirrorRig& mirror) { checkGltfMirror(mirror); },
                        [&](const LensCameraSpec&) { checkEngineRenders(EngineKind::Blender, rig, CameraPlacement{}); }},  // the lenses Cycles has
             rig.kind);
}

std::string gltfBytes(const Scene& scene, const GltfExportOptions& options) {
  GltfBuilder b;
  addArena(b, scene, options.chordTolerance);
  addLights(b, scene);
  addLandmarks(b, scene);
  if (options.includeRig) {
    checkGltfCamera(options.rig);
    std::visit(Overloaded{[&](const MirrorRig& mirror) { addMirrorRig(b, options, mirror); },
                          [&](const LensCameraSpec& lens) { addLensRig(b, options, lens); }},
               options.rig.kind);
  }
  std::ostringstream glb;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&b.model(), glb, false, true)) throw OutputError("cannot encode the scene as glTF");
  return glb.str();
}

void exportGltf(const Scene& scene, const GltfExportOptions& options, const std::string& path) {
  writeBytesAtomically(path, gltfBytes(scene, options));
}

}  // namespace omnicam
