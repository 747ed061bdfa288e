#pragma once
// Rasterises the scene into 90° cube faces from a viewpoint, for the cube-map modes' unlit
// faces: the way the thesis' Unreal engine produced its camera views, and far cheaper than one
// ray per texel. Texel centres are sampled exactly as the ray-cast faces do (a texel's colour is
// the albedo of the nearest surface through its centre); planar shapes are exact, curved ones
// are tessellated within 0.5 mm. Lit shading needs shadow rays and stays ray cast.
//
// Only the texels a lookup reads are rasterised (FaceTexels), so the cost per frame follows the
// omni image's sample count rather than the face resolution: a 512-texel face under a 360-pixel
// omni image is read at about a quarter of its texels.
#include <array>
#include <cstdint>
#include <vector>

#include "geometry.h"
#include "scene.h"

namespace omnicam {

// The texels to render, in (face, row, column) order: slot k of a colour buffer holds the k-th.
// Faces are padded × padded texels (faceSize plus a one-texel border each side).
struct FaceTexels {
  int faceSize = 0;
  std::vector<uint32_t> rowStart;  // 6·padded + 1 entries: row y of face f holds slots [rowStart[f·padded + y], next)
  std::vector<uint16_t> column;    // per slot: its x in [0, padded)
  std::vector<uint32_t> atlasIndex;  // per slot: f·padded² + y·padded + x

  int padded() const { return faceSize + 2; }
  size_t size() const { return column.size(); }
  // `used`: one flag per atlas texel (6·padded²). Throws std::length_error past 2^32 slots.
  static FaceTexels fromMask(int faceSize, const std::vector<char>& used);
  // Slot of an atlas texel that is in the set (binary search in its row).
  uint32_t slotOf(uint32_t atlasTexel) const;
};

// Colours of the texels in a FaceTexels set. Most texels show an untextured material or the
// background, so a slot usually holds only a 1-byte palette index: the omni lookup's scattered
// reads then touch a twelfth of the memory that full colours would (and stay in cache). Scenes
// with more than 254 materials keep every colour in `colour`.
using PaletteIndex = uint8_t;
struct FaceTexelColours {
  static constexpr PaletteIndex kOwnColour = 0xFF;  // the slot's colour is in `colour`
  std::vector<PaletteIndex> paletteIndex;  // per slot
  std::vector<Vec3f> colour;           // per slot; read only where paletteIndex is kOwnColour
  std::vector<Vec3f> palette;
  std::vector<float> inverseDepth;     // the rasteriser's scratch space (1/w per slot)

  Vec3f at(uint32_t slot) const {
    const PaletteIndex p = paletteIndex[slot];
    return p == kOwnColour ? colour[slot] : palette[p];
  }
};

class FaceRasterizer {
 public:
  explicit FaceRasterizer(const Scene& scene);

  // Colours every slot of `texels` on the faces in `faces` (others are left untouched), seen
  // from `origin` with the face bases (forward, right, up) already in world coordinates;
  // faceSize texels span [−1, 1]. Buffers in `out` are reused when they are large enough.
  // Deterministic: the result does not depend on the number of threads.
  void render(const Vec3& origin, const std::vector<int>& faces, const std::vector<std::array<Vec3, 3>>& bases,
              const FaceTexels& texels, FaceTexelColours& out) const;

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
