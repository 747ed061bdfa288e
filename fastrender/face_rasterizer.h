#pragma once
// Rasterises the scene into 90° cube faces from a viewpoint, for the cube-map modes' unlit
// faces: the way the thesis' Unreal engine produced its camera views, and far cheaper than one
// ray per texel. Texel centres are sampled exactly as the ray-cast faces do (a texel's colour is
// the albedo of the nearest surface through its centre); planar shapes are exact, curved ones
// are tessellated within 0.5 mm. Lit shading needs shadow rays and stays ray cast.
#include <array>
#include <vector>

#include "geometry.h"
#include "scene.h"

namespace omnicam {

class FaceRasterizer {
 public:
  explicit FaceRasterizer(const Scene& scene);

  // Fills `atlas` (faces of padded × padded texels, as laid out by the cube-map lookup) for the
  // faces in `faces`, seen from `origin` with the face bases (forward, right, up) already in
  // world coordinates; `faceSize` texels span [−1, 1] and one border texel surrounds them.
  void render(const Vec3& origin, const std::vector<int>& faces, const std::vector<std::array<Vec3, 3>>& bases,
              int faceSize, std::vector<Vec3f>& atlas) const;

 private:
  struct Vertex {
    Vec3 p;
    Eigen::Vector2d uv;
  };
  struct Triangle {
    Vertex v[3];
    int material;
  };
  const Scene& scene_;
  std::vector<Triangle> triangles_;
};

}  // namespace omnicam
