#include "fast_renderer.h"

#include <algorithm>
#include <cstring>

namespace omnicam {

namespace {
// Denoised frames trace the indirect light of a share of their samples, as the filter smooths it
// over its window anyway: a quarter, and at least two samples per pixel (half of 4 spp, all of 1).
// Measured in docs/path-tracing.md ("Coverage"): at 4 spp half gives +1.0 dB for 10–36 % more time.
constexpr double kDenoisedIndirectShare = 0.25;
constexpr int kDenoisedScatteringSamples = 2;
double denoisedIndirectShare(int spp) { return std::min(1.0, std::max(kDenoisedIndirectShare, double{kDenoisedScatteringSamples} / spp)); }
}  // namespace

std::optional<FastRenderer::PathFrame> FastRenderer::pathFrame(const RenderSettings& settings,
                                                               const CameraPlacement& camera) const {
  if (settings.shading != Shading::Path) return std::nullopt;
  PathTracingOptions options;
  options.diffuseBounces = settings.bounces;
  if (settings.denoise) options.indirectShare = denoisedIndirectShare(settings.spp);
  // Frames of other poses get other noise; the same pose, seed and settings the same frame. The
  // cameras of one robot mounted apart draw apart too (a stereo pair's noise would otherwise be
  // the same in both); an unmounted camera's key is as it always was. (Cameras on one mount that
  // differ only in their rig, stacked, still share it.)
  const RobotPose& pose = camera.robot();
  const BodyVelocity& velocity = camera.velocity();
  uint64_t key = settings.seed;
  const auto mix = [&key](double v) {
    uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    key = mixKey(key, bits);
  };
  for (double v : {pose.x, pose.y, pose.yawDeg, velocity.vx, velocity.vy, velocity.yawRateDegPerS}) mix(v);
  if (const RobotMount& mount = camera.mount(); mount != RobotMount{})
    for (double v : {mount.x, mount.y, mount.yawDeg}) mix(v);
  return PathFrame{PathTracer(scene_, rays_, options, environmentLight()), key};
}

void FastRenderer::shadePacket(const HitPacket& hits, Shading shading, Vec3f* colours, const PathFrame* path,
                               const PathKey* samples, PathSample* pathSamples) const {
  const int count = hits.count();
  if (shading == Shading::Path) {
    for (int k = 0; k < count; ++k) {
      const Vec3 direction = hits.direction(k).normalized();
      const std::optional<SurfaceHit> first = hits.hit(k) ? std::optional<SurfaceHit>(hits.surface(k)) : std::nullopt;
      PathSample sample = path->tracer.cameraRay(hits.start(k), direction, first ? &*first : nullptr, samples[k]);
      colours[k] = sample.radiance;
      if (!pathSamples) continue;
      if (first) {  // the denoiser's guides, from the hit in hand (working it out again costs a re-intersection)
        const Vec3 d = hits.direction(k);
        sample.firstNormal = (first->normal.dot(d) > 0.0 ? Vec3(-first->normal) : first->normal).cast<float>();
        sample.firstDepth = static_cast<float>(first->t * d.norm());
      }
      pathSamples[k] = sample;
    }
    return;
  }
  const Material* materials[kRayPacketSize];
  for (int k = 0; k < count; ++k) {
    if (!hits.hit(k)) {
      colours[k] = scene_.background;
      continue;
    }
    const Material& material = scene_.materials[scene_.objects[hits.object(k)].material];
    materials[k] = &material;
    colours[k] = material.color;
    if (material.texture) {
      const Eigen::Vector2d uv = hits.uv(k);
      colours[k] = colours[k].cwiseProduct(
          material.texture->sample(uv.x() * material.textureScale.x(), uv.y() * material.textureScale.y()));
    }
  }
  if (shading == Shading::Unlit || hits.mask() == 0) return;
  SurfaceHit surfaces[kRayPacketSize];
  Vec3 faced[kRayPacketSize];  // two-sided surfaces: the normal faces the viewer
  Vec3f light[kRayPacketSize];
  for (int k = 0; k < count; ++k) {
    light[k] = Vec3f::Zero();
    if (!hits.hit(k)) continue;
    surfaces[k] = hits.surface(k);
    faced[k] = surfaces[k].normal.dot(hits.direction(k)) > 0.0 ? Vec3(-surfaces[k].normal) : surfaces[k].normal;
    light[k] = Vec3f::Constant(materials[k]->ambient);
  }
  // One shadow packet per lamp: the hit points are neighbours, so their shadow rays are too.
  Vec3 origins[kRayPacketSize], toLamp[kRayPacketSize];
  double tNear[kRayPacketSize], tFar[kRayPacketSize], cosine[kRayPacketSize];
  for (const PointLight& lamp : scene_.lights) {
    uint32_t facing = 0;
    for (int k = 0; k < count; ++k) {
      if (!hits.hit(k)) continue;
      const Vec3 offset = lamp.position - surfaces[k].point;
      const double distance = offset.norm();
      toLamp[k] = offset / distance;
      cosine[k] = faced[k].dot(toLamp[k]);
      if (cosine[k] <= 0.0) continue;
      const double off = rays_.surfaceOffset(surfaces[k].point);
      origins[k] = surfaces[k].point + off * faced[k];
      tNear[k] = 0.0;
      tFar[k] = distance - off;
      facing |= 1u << k;
    }
    const uint32_t lit = facing & ~rays_.occludedPacket(origins, toLamp, tNear, tFar, facing);
    for (int k = 0; k < count; ++k)
      if ((lit >> k) & 1u) light[k] += static_cast<float>(materials[k]->diffuse * cosine[k]) * lamp.intensity;
  }
  for (int k = 0; k < count; ++k)
    if (hits.hit(k)) colours[k] = colours[k].cwiseProduct(light[k]);
}

Vec3f FastRenderer::radiance(const Vec3& origin, const Vec3& direction, Shading shading, uint64_t key, int bounces) const {
  HitPacket hits;
  hits.begin(origin, 1);
  hits.setDirection(0, direction.cast<float>());
  rays_.intersectPacket(hits);
  Vec3f colour;
  PathTracingOptions options;
  options.diffuseBounces = bounces;
  const PathFrame path{PathTracer(scene_, rays_, options, shading == Shading::Path ? environmentLight() : nullptr), 0};
  const PathKey sample{0, static_cast<uint32_t>(key)};
  shadePacket(hits, shading, &colour, &path, &sample);
  return colour;
}

}  // namespace omnicam
