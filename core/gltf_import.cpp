#include "gltf_import.h"

#include <tiny_gltf.h>

#include <functional>

#include "errors.h"
#include "image.h"

namespace omnicam {

namespace {

Vec3 fromGltf(const Vec3& g) { return {g.x(), -g.z(), g.y()}; }

Eigen::Matrix4d nodeMatrix(const tinygltf::Node& n) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  if (n.matrix.size() == 16) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = n.matrix[c * 4 + r];  // column-major
    return m;
  }
  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  if (n.translation.size() == 3) t.translate(Vec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4) t.rotate(Eigen::Quaterniond(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
  if (n.scale.size() == 3) t.scale(Vec3(n.scale[0], n.scale[1], n.scale[2]));
  return t.matrix();
}

// Reads accessor element k, component c, as double (float or normalized integers not needed).
class AccessorReader {
 public:
  AccessorReader(const tinygltf::Model& model, int index, const std::string& file) : file_(file) {
    if (index < 0 || index >= static_cast<int>(model.accessors.size())) throw InputError(file + ": bad accessor");
    accessor_ = &model.accessors[index];
    const auto& view = model.bufferViews.at(accessor_->bufferView);
    const auto& buffer = model.buffers.at(view.buffer);
    base_ = buffer.data.data() + view.byteOffset + accessor_->byteOffset;
    const int components = tinygltf::GetNumComponentsInType(accessor_->type);
    componentSize_ = tinygltf::GetComponentSizeInBytes(accessor_->componentType);
    stride_ = view.byteStride ? view.byteStride : components * componentSize_;
    const size_t end = view.byteOffset + accessor_->byteOffset + (accessor_->count ? (accessor_->count - 1) * stride_ : 0) +
                       components * componentSize_;
    if (end > buffer.data.size()) throw InputError(file + ": accessor runs past its buffer");
  }
  size_t count() const { return accessor_->count; }
  double get(size_t k, int c) const {
    const unsigned char* p = base_ + k * stride_ + c * componentSize_;
    switch (accessor_->componentType) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: return *reinterpret_cast<const float*>(p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return *reinterpret_cast<const uint32_t*>(p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return *reinterpret_cast<const uint16_t*>(p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
      default: throw InputError(file_ + ": unsupported accessor component type");
    }
  }

 private:
  std::string file_;
  const tinygltf::Accessor* accessor_;
  const unsigned char* base_;
  int componentSize_ = 4;
  size_t stride_ = 0;
};

std::shared_ptr<const Texture> textureOf(const tinygltf::Model& model, int textureIndex, const std::string& file) {
  if (textureIndex < 0) return nullptr;
  const auto& image = model.images.at(model.textures.at(textureIndex).source);
  if (image.image.empty() || image.bits != 8)
    throw InputError(file + ": texture \"" + image.name + "\" is not an 8-bit image omnicam can read");
  std::vector<float> rgb(static_cast<size_t>(image.width) * image.height * 3);
  for (size_t p = 0; p < rgb.size() / 3; ++p)
    for (int c = 0; c < 3; ++c) {
      const int channel = image.component >= 3 ? c : 0;
      rgb[p * 3 + c] = srgbToLinear(image.image[p * image.component + channel] / 255.0f);  // glTF: sRGB
    }
  return std::make_shared<Texture>(image.width, image.height, std::move(rgb));
}

}  // namespace

GltfArena importGltf(const std::string& path) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  const bool binary = path.size() >= 4 && path.compare(path.size() - 4, 4, ".glb") == 0;
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &error, &warning, path)
                         : loader.LoadASCIIFromFile(&model, &error, &warning, path);
  if (!ok) throw InputError(path + ": cannot load glTF (" + error + ")");
  GltfArena arena;
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const auto& m = model.materials[i];
    Material mat;
    mat.name = m.name.empty() ? "material_" + std::to_string(i) : m.name;
    const auto& f = m.pbrMetallicRoughness.baseColorFactor;
    mat.color = Vec3f(static_cast<float>(std::clamp(f[0], 0.0, 1.0)), static_cast<float>(std::clamp(f[1], 0.0, 1.0)),
                      static_cast<float>(std::clamp(f[2], 0.0, 1.0)));
    mat.texture = textureOf(model, m.pbrMetallicRoughness.baseColorTexture.index, path);
    // omnicam's own exports carry the lit-shading factors in extras.
    if (m.extras.Has("omnicam")) {
      const auto& o = m.extras.Get("omnicam");
      if (o.Has("ambient")) mat.ambient = static_cast<float>(o.Get("ambient").GetNumberAsDouble());
      if (o.Has("diffuse")) mat.diffuse = static_cast<float>(o.Get("diffuse").GetNumberAsDouble());
    }
    arena.materials.push_back(mat);
  }
  int defaultMaterial = -1;
  const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (model.scenes.empty()) throw InputError(path + ": no scene in the glTF file");
  std::function<void(int, const Eigen::Matrix4d&)> visit = [&](int nodeIndex, const Eigen::Matrix4d& parent) {
    const tinygltf::Node& node = model.nodes.at(nodeIndex);
    if (node.name.rfind("omnicam_", 0) == 0) return;  // an exported rig, not arena geometry
    const Eigen::Matrix4d world = parent * nodeMatrix(node);
    if (node.mesh >= 0) {
      const tinygltf::Mesh& mesh = model.meshes.at(node.mesh);
      for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
        const tinygltf::Primitive& prim = mesh.primitives[pi];
        const std::string where = path + ": meshes[" + std::to_string(node.mesh) + "].primitives[" + std::to_string(pi) + "]";
        if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1)
          throw InputError(where + ": only triangle primitives are supported");
        auto position = prim.attributes.find("POSITION");
        if (position == prim.attributes.end()) throw InputError(where + ": no POSITION");
        Mesh out;
        const AccessorReader pos(model, position->second, path);
        for (size_t k = 0; k < pos.count(); ++k) {
          const Eigen::Vector4d g = world * Eigen::Vector4d(pos.get(k, 0), pos.get(k, 1), pos.get(k, 2), 1.0);
          out.vertices.push_back(fromGltf(g.head<3>()));
        }
        if (auto uv = prim.attributes.find("TEXCOORD_0"); uv != prim.attributes.end()) {
          const AccessorReader t(model, uv->second, path);
          for (size_t k = 0; k < t.count(); ++k) out.uvs.emplace_back(t.get(k, 0), 1.0 - t.get(k, 1));
        }
        if (prim.indices >= 0) {
          const AccessorReader idx(model, prim.indices, path);
          for (size_t k = 0; k + 2 < idx.count(); k += 3)
            out.triangles.emplace_back(static_cast<int>(idx.get(k, 0)), static_cast<int>(idx.get(k + 1, 0)),
                                       static_cast<int>(idx.get(k + 2, 0)));
        } else {
          for (size_t k = 0; k + 2 < out.vertices.size(); k += 3)
            out.triangles.emplace_back(static_cast<int>(k), static_cast<int>(k + 1), static_cast<int>(k + 2));
        }
        for (const auto& t : out.triangles)
          if (t.maxCoeff() >= static_cast<int>(out.vertices.size()) || t.minCoeff() < 0)
            throw InputError(where + ": index out of range");
        int material = prim.material;
        if (material < 0) {
          if (defaultMaterial < 0) {
            defaultMaterial = static_cast<int>(arena.materials.size());
            arena.materials.push_back(Material{"default", {1.0f, 1.0f, 1.0f}, nullptr, "", {1, 1}, 0.2f, 0.8f});
          }
          material = defaultMaterial;
        }
        arena.objects.push_back({node.name.empty() ? mesh.name : node.name, material, std::move(out)});
      }
    }
    for (int child : node.children) visit(child, world);
  };
  for (int root : model.scenes[sceneIndex].nodes) visit(root, Eigen::Matrix4d::Identity());
  return arena;
}

}  // namespace omnicam
