#pragma once
// omnicam's own renderer, exact mode: every sample's ray comes from the rig's camera (camera.h):
// for the ideal rig straight from the effective viewpoint F' through the closed-form pixel → ray
// map (no mirror tracing), for a physical rig traced through the exact mirror from its own
// mirror point. It is intersected with the scene and shaded per docs/conventions.md §2. Pixels are box-filtered means of an n×n regular grid;
// rows are rendered in parallel with TBB and the result does not depend on the thread count.
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "aov_frame.h"
#include "camera.h"
#include "film.h"
#include "image.h"
#include "path_tracer.h"
#include "ray_scene.h"
#include "render_settings.h"
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
  // camera's, and the frame with every AOV and its files): checked before a table is built, and
  // the size of a dataset's frame in flight.
  static int64_t frameBytes(int width, int height, int spp, bool central);

  const Scene& scene() const { return scene_; }
  const RayScene& rays() const { return rays_; }

  // Radiance along one ray from `origin` (exposed for tests); path shading traces sample `key` of
  // one pixel's sequence with `bounces` diffuse bounces.
  Vec3f radiance(const Vec3& origin, const Vec3& direction, Shading shading, uint64_t key = 0,
                 int bounces = kDefaultBounces) const;

 private:
  struct PathFrame;
  struct DenoiseSums;
  // The rays of every imaged sample, per pixel, in the viewpoint frame: they depend only on the
  // camera and spp, so they are computed once and reused for every pose.
  struct SampleTable {
    static constexpr uint32_t kNoSample = 0xffffffffu;
    std::shared_ptr<const Camera> camera;
    int samplesPerAxis = 0;
    std::vector<Eigen::Vector3f> directions;  // imaged samples, pixel by pixel
    // Non-central cameras: each sample's ray leaves its mirror point, stored as the point of its
    // line nearest F' (F' = 0) and the distance on to the mirror point, where tracing starts.
    // Rays are thus given as precisely as the central model's (all from F'), and the ideal rig
    // traced gives the closed form's image.
    std::vector<Eigen::Vector3f> origins;
    std::vector<float> starts;
    std::vector<uint32_t> firstSample;        // per pixel, index into directions (+1 sentinel)
    std::vector<uint16_t> gridIndex;          // per sample: b·n + a of its pixel's n×n grid
    // Per pixel: the centre's ray (direction NaN where not imaged) and, at odd n, the index of
    // the sample that is the centre (kNoSample otherwise).
    std::vector<Eigen::Vector3f> centreDirections;
    std::vector<Eigen::Vector3f> centreOrigins;  // non-central cameras only
    std::vector<float> centreStarts;
    std::vector<uint32_t> centreSample;
  };
  // Where this frame's rays go: F' in the world and the world's rotation of viewpoint vectors.
  struct Placement {
    Vec3 origin;
    Eigen::Matrix3d rotation;
    Eigen::Matrix3f rotationF;  // float, like the rays Embree traces
  };
  // Where a frame's rays go when its samples see the robot at different times (docs/motion.md):
  // one placement per readout line and instant, and per line the one its AOVs are taken at.
  struct MovingPlacements {
    Shutter shutter;
    int width = 0, height = 0, n = 1;
    PixelInstants instants;
    std::vector<Placement> samples;  // [line · instants.count + instant]
    std::vector<Placement> centres;  // [line]
    const Placement& centre(int i, int j) const { return centres[lineOf(shutter, i, j, width, height)]; }
  };
  // A row's lookup of each sample's placement in one pass: samples[lineBase[column] + instantOfGrid[grid index]].
  struct RowPlacements {
    std::vector<int> lineBase;       // per column
    std::vector<int> instantOfGrid;  // per grid index b·n + a
    void prepare(const MovingPlacements& at, int j, int pass);
  };
  static MovingPlacements movingPlacements(const RenderSettings& settings, const CameraPlacement& camera, int samplesPerAxis);
  void renderPass(const CameraPlacement& camera, const RenderSettings& settings, Film& film) const;
  // The film's AOV planes sized for a frame; InputError for a scene whose instance ids overflow.
  void beginAovs(Film& film) const;
  std::shared_ptr<const SampleTable> sampleTable(const RenderSettings& settings, int samplesPerAxis) const;
  static Placement placement(const RenderSettings& settings, const CameraPlacement& camera, double seconds = 0.0);
  // Loads `count` rays of one table (first.., or the listed entries) into a packet.
  static void loadSamples(HitPacket& hits, const Placement& at, const SampleTable& table, uint32_t first, int count);
  // Reused memory of a thread's moving rows.
  struct MovingRowScratch {
    RowPlacements row;
    std::vector<uint16_t> columns;  // per sample of the row
  };
  // Row j of a moving frame: every pixel's sum of its samples' colours (over every pass) into
  // sums[0, width).
  void traceMovingRow(const MovingPlacements& at, const SampleTable& table, int j, Shading shading, const PathFrame* path,
                      MovingRowScratch& scratch, HitPacket& hits, Vec3f* sums, DenoiseSums* denoise) const;
  // Centre rays of listed pixels, each placed by at(pixel).
  template <typename PlacementOfPixel>
  static void loadCentres(HitPacket& hits, const PlacementOfPixel& at, const SampleTable& table, const size_t* pixels,
                          int count);
  // Traces the centre rays of `count` ≤ kRayPacketSize imaged pixels as one packet and records
  // the AOVs of those that hit; returns the mask of hits (bit k: pixels[k]).
  template <typename PlacementOfPixel>
  uint32_t recordCentreAovs(const PlacementOfPixel& at, const SampleTable& table, const size_t* pixels, int count,
                            HitPacket& hits, Film& film) const;

  // Path shading's frame: its tracer and the key its samples' keys derive from.
  struct PathFrame {
    PathTracer tracer;
    uint64_t key = 0;
  };
  std::optional<PathFrame> pathFrame(const RenderSettings& settings, const CameraPlacement& camera) const;
  // Per pixel, the sums a denoised path frame needs beside its colour: the direct light's, and the
  // guides' of each sample's first surface (albedo, normal facing the camera, depth); nothing
  // where a sample sees no surface.
  struct DenoiseSums {
    std::vector<Vec3f> direct, albedo, normal;
    std::vector<float> depth;
    void resize(size_t pixels);
    void add(size_t pixel, const PathSample& sample, const HitPacket& hits, int k);
  };
  // The film's colour with its indirect light filtered (denoise/indirect_filter.h).
  static void denoise(Film& film, const DenoiseSums& sums, float weight, const std::vector<uint32_t>& imaged);
  // Colours of a packet of rays: the background where a ray missed, else its hit shaded per
  // docs/conventions.md §3, with the shadow rays traced as packets too. Path shading (`path`
  // given) traces ray k's path keyed by samples[k].
  void shadePacket(const HitPacket& hits, Shading shading, Vec3f* colours, const PathFrame* path = nullptr,
                   const PathKey* samples = nullptr, PathSample* pathSamples = nullptr) const;
  const Scene& scene_;
  RayScene rays_;
  mutable std::mutex tableMutex_;  // guards only the cached pointer; tables are immutable
  mutable std::shared_ptr<const SampleTable> table_;
};

}  // namespace omnicam
