#pragma once
// omnicam's own renderer, exact mode: every sample's ray comes straight from the effective
// viewpoint F' through the closed-form pixel → ray map (no mirror tracing), is intersected with
// the scene, and shaded per spec §3. Pixels are box-filtered means of an n×n regular grid;
// rows are rendered in parallel with TBB and the result does not depend on the thread count.
#include <memory>
#include <string>

#include "image.h"
#include "ray_scene.h"
#include "render_settings.h"
#include "scene.h"

namespace omnicam {

// "omnicam <version> exact (Embree <version>)", for sidecars.
std::string fastRendererVersion();

class FastRenderer {
 public:
  // Keeps a reference to `scene`, which must outlive the renderer.
  explicit FastRenderer(const Scene& scene);

  // Throws InputError if settings.spp is not a perfect square.
  ImageRGBA render(const RobotPose& pose, const RenderSettings& settings) const;

  // Radiance along one ray from `origin` (exposed for tests).
  Vec3f radiance(const Vec3& origin, const Vec3& direction, Shading shading) const;

 private:
  Vec3f shade(const SurfaceHit& hit, const Vec3& direction, Shading shading) const;
  const Scene& scene_;
  RayScene rays_;
};

}  // namespace omnicam
