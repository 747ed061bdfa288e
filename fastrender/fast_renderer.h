#pragma once
// omnicam's own renderer, exact mode: every sample's ray comes straight from the effective
// viewpoint F' through the closed-form pixel → ray map (no mirror tracing), is intersected with
// the scene, and shaded per docs/conventions.md §2. Pixels are box-filtered means of an n×n regular grid;
// rows are rendered in parallel with TBB and the result does not depend on the thread count.
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "aov_frame.h"
#include "image.h"
#include "ray_scene.h"
#include "render_settings.h"
#include "scene.h"

namespace omnicam {

// "omnicam <version> (Embree <version>)", for sidecars (the mode is recorded on its own).
std::string fastRendererVersion();

class FastRenderer {
 public:
  // Keeps a reference to `scene`, which must outlive the renderer.
  explicit FastRenderer(const Scene& scene);

  // Throws InputError if settings.spp is not a perfect square.
  ImageRGBA render(const RobotPose& pose, const RenderSettings& settings) const;
  // The same image and, in the same pass, its AOVs (aov_frame.h): at odd n the centre sample's
  // hit is reused, at even n one more ray goes through the pixel centre. InputError also for a
  // scene with more than kMaxInstances objects.
  ImageRGBA render(const RobotPose& pose, const RenderSettings& settings, AovFrame& aovs) const;
  // Only the AOVs (settings.spp does not matter).
  void renderAovsOnly(const RobotPose& pose, const RenderSettings& settings, AovFrame& aovs) const;

  const Scene& scene() const { return scene_; }
  const RayScene& rays() const { return rays_; }

  // Radiance along one ray from `origin` (exposed for tests).
  Vec3f radiance(const Vec3& origin, const Vec3& direction, Shading shading) const;

 private:
  // Camera-frame directions of every sample inside the rim, per pixel: they depend only on the
  // rig's image model and spp, so they are computed once and reused for every pose.
  struct SampleTable {
    static constexpr uint32_t kNoSample = 0xffffffffu;
    RigSpec rig;
    int samplesPerAxis = 0;
    std::vector<Eigen::Vector3f> directions;  // inside-rim samples, pixel by pixel
    std::vector<uint32_t> firstSample;        // per pixel, index into directions (+1 sentinel)
    // Per pixel: the centre's direction (NaN beyond the rim) and, at odd n, the index of the
    // sample that is the centre (kNoSample otherwise).
    std::vector<Eigen::Vector3f> centreDirections;
    std::vector<uint32_t> centreSample;
  };
  ImageRGBA renderPass(const RobotPose& pose, const RenderSettings& settings, AovFrame* aovs) const;
  void prepareAovs(const RenderSettings& settings, AovFrame& aovs) const;
  std::shared_ptr<const SampleTable> sampleTable(const RigSpec& rig, int samplesPerAxis) const;
  // Traces the centre rays of `count` ≤ kRayPacketSize inside-rim pixels as one packet and
  // records the AOVs of those that hit; returns the mask of hits (bit k: pixels[k]).
  uint32_t recordCentreAovs(const Vec3& origin, const Eigen::Matrix3f& rotation, const SampleTable& table,
                            const size_t* pixels, int count, HitPacket& hits, AovFrame& aovs) const;

  // Colours of a packet of rays: the background where a ray missed, else its hit shaded per
  // docs/conventions.md §2, with the shadow rays traced as packets too.
  void shadePacket(const HitPacket& hits, Shading shading, Vec3f* colours) const;
  const Scene& scene_;
  RayScene rays_;
  mutable std::mutex tableMutex_;  // guards only the cached pointer; tables are immutable
  mutable std::shared_ptr<const SampleTable> table_;
};

}  // namespace omnicam
