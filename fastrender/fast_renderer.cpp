#include "fast_renderer.h"

#include <embree3/rtcore_config.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "errors.h"

namespace omnicam {

namespace {
// Shadow rays start this far off the surface (metres) to avoid self-intersection.
constexpr double kShadowEpsilon = 1e-5;
}  // namespace

std::string fastRendererVersion() {
  return std::string("omnicam ") + OMNICAM_VERSION + " exact (Embree " + RTC_VERSION_STRING + ")";
}

FastRenderer::FastRenderer(const Scene& scene) : scene_(scene), rays_(scene) {}

Vec3f FastRenderer::shade(const SurfaceHit& hit, const Vec3& direction, Shading shading) const {
  const Material& material = scene_.materials[scene_.objects[hit.object].material];
  Vec3f albedo = material.color;
  if (material.texture)
    albedo = albedo.cwiseProduct(material.texture->sample(hit.uv.x() * material.textureScale.x(),
                                                          hit.uv.y() * material.textureScale.y()));
  if (shading == Shading::Unlit) return albedo;
  // Two-sided surfaces: the normal faces the viewer.
  const Vec3 n = hit.normal.dot(direction) > 0.0 ? Vec3(-hit.normal) : hit.normal;
  Vec3f light = Vec3f::Constant(material.ambient);
  for (const PointLight& lamp : scene_.lights) {
    const Vec3 toLight = lamp.position - hit.point;
    const double distance = toLight.norm();
    const Vec3 l = toLight / distance;
    const double cosine = n.dot(l);
    if (cosine <= 0.0) continue;
    if (rays_.occluded(hit.point + kShadowEpsilon * n, l, 0.0, distance - kShadowEpsilon)) continue;
    light += static_cast<float>(material.diffuse * cosine) * lamp.intensity;
  }
  return albedo.cwiseProduct(light);
}

Vec3f FastRenderer::radiance(const Vec3& origin, const Vec3& direction, Shading shading) const {
  SurfaceHit hit;
  if (!rays_.intersect(origin, direction, 0.0, hit)) return scene_.background;
  return shade(hit, direction, shading);
}

ImageRGBA FastRenderer::render(const RobotPose& pose, const RenderSettings& settings) const {
  const auto n = samplesPerAxis(settings.spp);
  if (!n) throw InputError("--spp: must be a perfect square n*n (got " + std::to_string(settings.spp) + ")");
  const OmniCamera camera = settings.rig.camera();
  const Rigid worldFromCam = worldFromCamera(settings.rig, pose);
  const Vec3 origin = worldFromCam.translation();
  const Eigen::Matrix3d rotation = worldFromCam.linear();
  ImageRGBA image(camera.width(), camera.height());
  const int samplesAxis = *n;
  const float weight = 1.0f / static_cast<float>(samplesAxis * samplesAxis);
  tbb::parallel_for(tbb::blocked_range<int>(0, camera.height()), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j != rows.end(); ++j) {
      for (int i = 0; i < camera.width(); ++i) {
        Vec3f sum = Vec3f::Zero();
        int inside = 0;
        for (int b = 0; b < samplesAxis; ++b) {
          for (int a = 0; a < samplesAxis; ++a) {
            const Vec2 raster(i + (a + 0.5) / samplesAxis, j + (b + 0.5) / samplesAxis);
            if (!camera.insideRim(raster)) continue;
            ++inside;
            sum += radiance(origin, rotation * camera.cameraFromRaster(raster), settings.shading);
          }
        }
        float* px = image.at(i, j);
        for (int c = 0; c < 3; ++c) px[c] = sum[c] * weight;
        px[3] = static_cast<float>(inside) * weight;
      }
    }
  });
  return image;
}

}  // namespace omnicam
