#pragma once
// The thesis' method as a mode of the fast renderer (thesis §3.1.3, docs/conventions.md §4):
//
//   cubemap      — render 90° cube faces from the effective viewpoint (five: four horizontal
//                  plus down, as the thesis; or six), then fill every omni sample from a
//                  precomputed lookup (exact direction → face texel, bilinear). Each face carries
//                  a one-texel border rendered in its own directions, so bilinear filtering never
//                  crosses a face edge and there are no seams. With five faces, directions whose
//                  major axis is "up" are black, as in the thesis.
//   thesis-mesh  — the thesis' mirror mesh (8·2^k sectors × 2·2^k rings = 16…1024 polygons,
//                  vertices on the exact mirror) seen by the physical camera; each sample's
//                  cube-face coordinates are interpolated *linearly* across the mesh triangle
//                  it hits, as Unreal's UV mapping did — reproducing thesis Fig. 3.4's distortions.
//
// Both lookups depend only on the rig, spp and these options: they are built once and cached.
// Only face texels that some lookup references are rendered (rasterised, or ray cast like
// exact mode), into buffers reused across frames.
#include <memory>
#include <mutex>

#include "face_rasterizer.h"
#include "fast_renderer.h"
#include "omni_mode.h"

namespace omnicam {

struct CubeLookupStats {
  long samples = 0;        // samples inside the rim
  long missedSamples = 0;  // with five faces: samples looking above every face (black)
  long texelsRendered = 0;
};

// InputError for options no cube map has (faces 5 or 6, face size 8 … 8192, polygons 16, 64,
// 256 or 1024), naming them in the library's words.
void checkCubeMapOptions(const CubeMapOptions& options);

class CubeMapRenderer {
 public:
  explicit CubeMapRenderer(const FastRenderer& renderer);
  // Throws InputError for bad options (faces, faceSize, polygons, spp).
  ImageRGBA render(const CameraPlacement& placement, const RenderSettings& settings, const CubeMapOptions& options) const;
  // The same into `film`'s colour (filmFor(settings)), whose storage is reused from frame to frame.
  void render(const CameraPlacement& placement, const RenderSettings& settings, const CubeMapOptions& options,
              Film& film) const;
  CubeLookupStats stats(const RenderSettings& settings, const CubeMapOptions& options) const;

  struct Lookup;

 private:
  std::shared_ptr<const Lookup> lookup(const RenderSettings& settings, const CubeMapOptions& options) const;

  // Per-frame face texels, reused: a render leases one set for its own exclusive use.
  class BufferLease {
   public:
    explicit BufferLease(const CubeMapRenderer& owner);
    ~BufferLease();
    BufferLease(const BufferLease&) = delete;
    BufferLease& operator=(const BufferLease&) = delete;
    FaceTexelColours& buffers() const { return *buffers_; }

   private:
    const CubeMapRenderer& owner_;
    std::unique_ptr<FaceTexelColours> buffers_;
  };

  const FastRenderer& renderer_;
  FaceRasterizer rasterizer_;
  mutable std::mutex mutex_;  // guards the cached lookup pointer and the spare buffers
  mutable std::shared_ptr<const Lookup> cached_;  // immutable once built
  mutable std::vector<std::unique_ptr<FaceTexelColours>> spareBuffers_;
};

// Polygon counts the thesis used and their sectors × rings.
bool thesisMeshLayout(int polygons, int& sectors, int& rings);

}  // namespace omnicam
