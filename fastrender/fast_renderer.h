#pragma once
// omnicam's own renderer, exact mode: every sample's ray comes from the rig's camera (camera.h):
// for the ideal rig straight from the effective viewpoint F' through the closed-form pixel → ray
// map (no mirror tracing), for a physical rig traced through the exact mirror from its own
// mirror point. It is intersected with the scene and shaded per docs/conventions.md §2. Pixels are box-filtered means of an n×n regular grid;
// rows are rendered in parallel with TBB and the result does not depend on the thread count.
#include <algorithm>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "aov_frame.h"
#include "camera.h"
#include "denoise_guides.h"
#include "film.h"
#include "image.h"
#include "path_tracer.h"
#include "ray_placements.h"
#include "ray_scene.h"
#include "render_settings.h"
#include "sample_table.h"
#include "scene.h"

namespace omnicam {

// "omnicam <version> (Embree <version>)", for sidecars (the mode is recorded on its own).
std::string fastRendererVersion();

class FastRenderer {
 public:
  using SceneType = Scene;
  // Keeps a reference to `scene`, which must outlive the renderer.
  explicit FastRenderer(const Scene& scene);

  // Exposes `film` (filmFor(settings, …)) to the camera at `placement`: its colour and, in the
  // same pass when it wants them, its AOVs (aov_frame.h): at odd n the centre sample's hit is
  // reused, at even n one more ray goes through the pixel centre. InputError for settings out of
  // range, and for AOVs of a scene with more than kMaxInstances objects.
  void render(const CameraPlacement& placement, const RenderSettings& settings, Film& film) const;
  // The colour alone; the colour and the AOVs.
  ImageRGBA render(const CameraPlacement& placement, const RenderSettings& settings) const;
  ImageRGBA render(const CameraPlacement& placement, const RenderSettings& settings, AovFrame& aovs) const;
  // Only the AOVs, into a film that wants them (settings.spp does not matter; its colour is left
  // alone).
  void renderAovsOnly(const CameraPlacement& placement, const RenderSettings& settings, Film& film) const;

  // The memory one width × height frame at `spp` takes (its sample table, a central or a traced
  // camera's, the frame with every AOV and its files, and a denoised path frame's filter):
  // checked before a table is built, and the size of a dataset's frame in flight.
  static int64_t frameBytes(int width, int height, int spp, bool central, bool denoised);

  const Scene& scene() const { return scene_; }
  const RayScene& rays() const { return rays_; }

  // Radiance along one ray from `origin` (exposed for tests); path shading traces sample `key` of
  // one pixel's sequence with `bounces` diffuse bounces.
  Vec3f radiance(const Vec3& origin, const Vec3& direction, Shading shading, uint64_t key = 0,
                 int bounces = kDefaultBounces) const;

 private:
  // Path shading's frame: its tracer and the key its samples' keys derive from.
  struct PathFrame {
    PathTracer tracer;
    uint64_t key = 0;
  };
  // Reused memory of a thread's rows.
  struct RowScratch {
    RowPlacements row;
    std::vector<uint16_t> columns;  // per sample of a moving row
    std::vector<StoredRay> rays;    // a refined pixel's finer grid's rays (adaptive sampling, coverage)
    std::vector<uint16_t> grid;     // their index in that grid
    std::vector<uint8_t> centreRecorded;  // per column: its AOVs are written
  };
  // What every row of one frame shares.
  struct FrameJob {
    const SampleTable& table;
    const RayPlacement& still;
    const MovingPlacements* moving = nullptr;  // null for a still frame
    Shading shading = Shading::Unlit;
    const PathFrame* path = nullptr;           // path shading only
    DenoiseSums* denoise = nullptr;            // a denoised path frame only
    bool aovs = false;
    bool centresFromSamples = false;  // at odd n a still frame's centre sample gives its AOVs
  };

  std::shared_ptr<const SampleTable> sampleTable(const RenderSettings& settings, int samplesPerAxis) const;
  void renderPass(const CameraPlacement& camera, const RenderSettings& settings, Film& film) const;
  // Row j of a still frame: every pixel's sum of its samples' colours into sums[0, width), and the
  // AOVs of pixels whose centre is a sample.
  // A pixel's samples' luminances summed, and their squares (in double: in float a bright pixel's
  // rounding would pass for noise).
  struct LuminanceMoments {
    double sum = 0.0, squares = 0.0;
  };
  // With `moments`, also each pixel's luminance moments into moments[0, width).
  void traceStillRow(const FrameJob& job, int j, int width, HitPacket& hits, Vec3f* sums, RowScratch& scratch, Film& film,
                     LuminanceMoments* moments = nullptr) const;

  // Adaptive sampling (fast_renderer_adaptive.cpp). Each pixel's grid from its first grid's noise:
  // level k is the grid of 4^k·spp samples (0: the first; pixels the rim cuts stay there).
  std::vector<uint8_t> adaptiveLevels(const RenderSettings& settings, const SampleTable& table,
                                      const std::vector<LuminanceMoments>& moments) const;
  // Row j's pixels of level > 0 traced anew on their grid (the first grid's samples dropped),
  // exactly as a fixed frame of that grid traces them; their colours' sums into sums[i]. A pixel
  // whose grid the rim cuts goes back a level (its alpha is the first grid's), to 0 at most.
  void traceFinerRow(const FrameJob& job, int j, int width, uint8_t* levels, HitPacket& hits, Vec3f* sums,
                     RowScratch& scratch) const;
  // The pixels whose error is above the target traced again on finer grids; then every pixel's
  // sum into the film, scaled to the first grid's count of samples.
  void refineAdaptively(const FrameJob& job, const RenderSettings& settings, std::vector<Vec3f>& sums,
                        const std::vector<LuminanceMoments>& moments, Film& film) const;
  // A pixel's grid of rays (addGridRays) traced from the still frame's placement in packets;
  // after each packet, packet(first, count) with its hits in `hits`.
  template <typename PacketFunction>
  void traceGridRays(const FrameJob& job, const std::vector<StoredRay>& rays, HitPacket& hits,
                     const PacketFunction& packet) const {
    for (size_t first = 0; first < rays.size(); first += kRayPacketSize) {
      const int count = static_cast<int>(std::min<size_t>(kRayPacketSize, rays.size() - first));
      loadStoredRays(hits, job.still, &rays[first], job.table.camera->central(), count);
      rays_.intersectPacket(hits);
      packet(first, count);
    }
  }
  // Coverage refinement of denoised still frames (fast_renderer_coverage.cpp): the pixels whose
  // samples (or a neighbour's) disagree on the albedo or the light shining along them traced again
  // on a finer grid to their first surfaces; its kept light and albedo into `sums`.
  void refineCoverage(const FrameJob& job, int width, int height, DenoiseSums& sums) const;
  // Row j of a moving frame: every pixel's sum of its samples' colours (over every pass) into
  // sums[0, width).
  void traceMovingRow(const MovingPlacements& at, const SampleTable& table, int j, Shading shading, const PathFrame* path,
                      RowScratch& scratch, HitPacket& hits, Vec3f* sums, DenoiseSums* denoise) const;

  // AOVs (fast_renderer_aovs.cpp). The film's AOV planes sized for a frame; InputError for a
  // scene whose instance ids overflow.
  void beginAovs(Film& film) const;
  static void recordSampleAov(Film& film, size_t pixel, const HitPacket& hits, int k);
  // Traces the centre rays of `count` ≤ kRayPacketSize imaged pixels as one packet and records
  // the AOVs of those that hit; returns the mask of hits (bit k: pixels[k]).
  uint32_t recordCentreAovs(const CentrePlacements& at, const SampleTable& table, const size_t* pixels, int count,
                            HitPacket& hits, Film& film) const;
  // Row j's AOVs that no sample recorded: at even n no sample is the centre, and a moving frame's
  // AOVs are taken at the pixel's own time (one more ray per pixel, again in packets); pixels
  // whose centre sees nothing get none.
  void finishRowAovs(const FrameJob& job, int j, int width, HitPacket& hits, std::vector<uint8_t>& centreRecorded, Film& film) const;

  // Shading (fast_renderer_shading.cpp).
  std::optional<PathFrame> pathFrame(const RenderSettings& settings, const CameraPlacement& camera) const;
  // Colours of a packet of rays: the background where a ray missed, else its hit shaded per
  // docs/conventions.md §3, with the shadow rays traced as packets too. Path shading (`path`
  // given) traces ray k's path keyed by samples[k].
  void shadePacket(const HitPacket& hits, Shading shading, Vec3f* colours, const PathFrame* path = nullptr,
                   const PathKey* samples = nullptr, PathSample* pathSamples = nullptr) const;

  const Scene& scene_;
  RayScene rays_;
  // The environment's sampling tables: built once, by the first path-shaded frame (they cost a
  // frame's worth), shared by every frame after.
  std::shared_ptr<const EnvironmentLight> environmentLight() const;
  mutable std::once_flag environmentOnce_;
  mutable std::shared_ptr<const EnvironmentLight> environmentLight_;
  mutable std::mutex tableMutex_;  // guards only the cached pointer; tables are immutable
  mutable std::shared_ptr<const SampleTable> table_;
};

}  // namespace omnicam
