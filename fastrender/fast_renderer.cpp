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
  return std::string("omnicam ") + OMNICAM_VERSION + " (Embree " + RTC_VERSION_STRING + ")";
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

std::shared_ptr<const FastRenderer::SampleTable> FastRenderer::sampleTable(const RigSpec& rig, int n) const {
  std::lock_guard<std::mutex> lock(tableMutex_);
  const auto same = [&](const RigSpec& r) {
    return r.k == rig.k && r.c == rig.c && r.rimElevationDeg == rig.rimElevationDeg && r.imageSize == rig.imageSize &&
           r.framingElevationDeg == rig.framingElevationDeg;
  };
  if (table_ && table_->samplesPerAxis == n && same(table_->rig)) return table_;
  auto table = std::make_shared<SampleTable>();
  table->rig = rig;
  table->samplesPerAxis = n;
  const OmniCamera camera = rig.camera();
  const size_t pixels = static_cast<size_t>(camera.width()) * camera.height();
  table->firstSample.reserve(pixels + 1);
  table->centreDirections.reserve(pixels);
  table->centreSample.reserve(pixels);
  for (int j = 0; j < camera.height(); ++j)
    for (int i = 0; i < camera.width(); ++i) {
      table->firstSample.push_back(static_cast<uint32_t>(table->directions.size()));
      uint32_t centre = SampleTable::kNoSample;
      for (int b = 0; b < n; ++b)
        for (int a = 0; a < n; ++a) {
          const Vec2 raster(i + (a + 0.5) / n, j + (b + 0.5) / n);
          if (!camera.insideRim(raster)) continue;
          if (2 * a + 1 == n && 2 * b + 1 == n) centre = static_cast<uint32_t>(table->directions.size());
          table->directions.push_back(camera.cameraFromRaster(raster).cast<float>());
        }
      const Vec2 middle(i + 0.5, j + 0.5);
      table->centreDirections.push_back(camera.insideRim(middle) ? Eigen::Vector3f(camera.cameraFromRaster(middle).cast<float>())
                                                                  : Eigen::Vector3f::Constant(NAN));
      table->centreSample.push_back(centre);
    }
  table->firstSample.push_back(static_cast<uint32_t>(table->directions.size()));
  table_ = table;
  return table_;
}

ImageRGBA FastRenderer::render(const RobotPose& pose, const RenderSettings& settings) const {
  return renderPass(pose, settings, nullptr);
}

ImageRGBA FastRenderer::render(const RobotPose& pose, const RenderSettings& settings, AovFrame& aovs) const {
  prepareAovs(settings, aovs);
  return renderPass(pose, settings, &aovs);
}

void FastRenderer::prepareAovs(const RenderSettings& settings, AovFrame& aovs) const {
  if (scene_.objects.size() > kMaxInstances)
    throw InputError(scene_.path + ": " + std::to_string(scene_.objects.size()) +
                     " objects; instance ids are 16-bit (at most " + std::to_string(kMaxInstances) + ")");
  aovs.width = aovs.height = settings.rig.imageSize;
  const size_t pixels = static_cast<size_t>(aovs.width) * aovs.height;
  // Sized only: every pixel is written by the pass (zeros where nothing is hit), so a reused
  // frame costs no clearing.
  aovs.depth.resize(pixels);
  aovs.instance.resize(pixels);
  aovs.normal.resize(3 * pixels);
}

namespace {

void recordNoHit(AovFrame& aovs, size_t pixel) {
  aovs.depth[pixel] = 0.0f;
  aovs.instance[pixel] = 0;
  for (int c = 0; c < 3; ++c) aovs.normal[3 * pixel + c] = 0.0f;
}

void recordAov(AovFrame& aovs, size_t pixel, const SurfaceHit& hit, const Vec3& direction) {
  aovs.depth[pixel] = static_cast<float>(hit.t);
  aovs.instance[pixel] = static_cast<uint16_t>(hit.object + 1);
  const Vec3 n = hit.normal.dot(direction) > 0.0 ? Vec3(-hit.normal) : hit.normal;  // two-sided
  for (int c = 0; c < 3; ++c) aovs.normal[3 * pixel + c] = static_cast<float>(n[c]);
}

}  // namespace

void FastRenderer::renderAovsOnly(const RobotPose& pose, const RenderSettings& settings, AovFrame& aovs) const {
  RenderSettings centreOnly = settings;
  centreOnly.spp = 1;
  checkRenderSettings(centreOnly);
  checkPose(pose, "--pose");
  prepareAovs(settings, aovs);
  const std::shared_ptr<const SampleTable> table = sampleTable(settings.rig, 1);
  const Rigid worldFromCam = worldFromCamera(settings.rig, pose);
  const Vec3 origin = worldFromCam.translation();
  const Eigen::Matrix3d rotation = worldFromCam.linear();
  tbb::parallel_for(tbb::blocked_range<int>(0, aovs.height), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j != rows.end(); ++j)
      for (int i = 0; i < aovs.width; ++i) {
        const size_t p = static_cast<size_t>(j) * aovs.width + i;
        const Eigen::Vector3f& centre = table->centreDirections[p];
        const Vec3 direction = rotation * centre.cast<double>();
        SurfaceHit hit;
        if (!std::isnan(centre.x()) && rays_.intersect(origin, direction, 0.0, hit)) recordAov(aovs, p, hit, direction);
        else recordNoHit(aovs, p);
      }
  });
}

ImageRGBA FastRenderer::renderPass(const RobotPose& pose, const RenderSettings& settings, AovFrame* aovs) const {
  checkRenderSettings(settings);
  checkPose(pose, "--pose");
  const auto n = samplesPerAxis(settings.spp);
  const std::shared_ptr<const SampleTable> table = sampleTable(settings.rig, *n);
  const int width = settings.rig.imageSize, height = settings.rig.imageSize;
  const Rigid worldFromCam = worldFromCamera(settings.rig, pose);
  const Vec3 origin = worldFromCam.translation();
  const Eigen::Matrix3d rotation = worldFromCam.linear();
  ImageRGBA image(width, height);
  const float weight = 1.0f / static_cast<float>(*n * *n);
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j != rows.end(); ++j) {
      for (int i = 0; i < width; ++i) {
        const size_t pixel = static_cast<size_t>(j) * width + i;
        const uint32_t first = table->firstSample[pixel], last = table->firstSample[pixel + 1];
        Vec3f sum = Vec3f::Zero();
        bool centreRecorded = false;
        for (uint32_t s = first; s < last; ++s) {
          const Vec3 direction = rotation * table->directions[s].cast<double>();
          SurfaceHit hit;
          if (!rays_.intersect(origin, direction, 0.0, hit)) {
            sum += scene_.background;
            continue;
          }
          sum += shade(hit, direction, settings.shading);
          if (aovs && s == table->centreSample[pixel]) {
            recordAov(*aovs, pixel, hit, direction);
            centreRecorded = true;
          }
        }
        if (aovs && table->centreSample[pixel] == SampleTable::kNoSample) {
          const Eigen::Vector3f& centre = table->centreDirections[pixel];
          SurfaceHit hit;
          const Vec3 direction = rotation * centre.cast<double>();
          if (!std::isnan(centre.x()) && rays_.intersect(origin, direction, 0.0, hit)) {
            recordAov(*aovs, pixel, hit, direction);
            centreRecorded = true;
          }
        }
        if (aovs && !centreRecorded) recordNoHit(*aovs, pixel);
        float* px = image.at(i, j);
        for (int c = 0; c < 3; ++c) px[c] = sum[c] * weight;
        px[3] = static_cast<float>(last - first) * weight;
      }
    }
  });
  return image;
}

}  // namespace omnicam
