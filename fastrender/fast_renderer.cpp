#include "fast_renderer.h"

#include <embree3/rtcore_config.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "errors.h"
#include "indirect_filter.h"
#include "make_camera.h"
#include "memory_budget.h"

namespace omnicam {

namespace {
// Denoised frames trace the indirect light of this share of their samples: the filter smooths it
// over its window anyway (measured in docs/path-tracing.md).
constexpr double kDenoisedIndirectShare = 0.25;
// Shadow rays start this far off the surface (metres) to avoid self-intersection.
constexpr double kShadowEpsilon = 1e-5;
}  // namespace

std::string fastRendererVersion() {
  return std::string("omnicam ") + OMNICAM_VERSION + " (Embree " + RTC_VERSION_STRING + ")";
}

FastRenderer::FastRenderer(const Scene& scene) : scene_(scene), rays_(scene) {}

std::optional<FastRenderer::PathFrame> FastRenderer::pathFrame(const RenderSettings& settings,
                                                               const CameraPlacement& camera) const {
  if (settings.shading != Shading::Path) return std::nullopt;
  PathTracingOptions options;
  options.diffuseBounces = settings.bounces;
  if (settings.denoise) options.indirectShare = kDenoisedIndirectShare;
  // Frames of other poses get other noise; the same pose, seed and settings the same frame.
  const RobotPose& pose = camera.robot();
  const BodyVelocity& velocity = camera.velocity();
  uint64_t key = settings.seed;
  for (double v : {pose.x, pose.y, pose.yawDeg, velocity.vx, velocity.vy, velocity.yawRateDegPerS}) {
    uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    key = mixKey(key, bits);
  }
  return PathFrame{PathTracer(scene_, rays_, options), key};
}

void FastRenderer::DenoiseSums::resize(size_t pixels) {
  direct.assign(pixels, Vec3f::Zero());
  albedo.assign(pixels, Vec3f::Zero());
  normal.assign(pixels, Vec3f::Zero());
  depth.assign(pixels, 0.0f);
}

void FastRenderer::DenoiseSums::add(size_t pixel, const PathSample& sample, const HitPacket& hits, int k) {
  direct[pixel] += sample.direct;
  if (!hits.hit(k)) return;
  const SurfaceHit hit = hits.surface(k);
  albedo[pixel] += sample.firstAlbedo;
  const Vec3 d = hits.direction(k);
  normal[pixel] += (hit.normal.dot(d) > 0.0 ? Vec3(-hit.normal) : hit.normal).cast<float>();
  depth[pixel] += static_cast<float>(hit.t * d.norm());
}

void FastRenderer::denoise(Film& film, const DenoiseSums& sums, float weight, const std::vector<uint32_t>& imaged) {
  IndirectFilterInputs in;
  const size_t pixels = sums.depth.size();
  in.full = film.image();
  in.direct = film.image();
  in.albedo.resize(3 * pixels);
  in.normal.resize(3 * pixels);
  in.depth.resize(pixels);
  for (size_t p = 0; p < pixels; ++p) {
    // The guides are means over the samples the camera images (the colour's, over the whole grid).
    const float perSample = imaged[p] > 0 ? 1.0f / static_cast<float>(imaged[p]) : 0.0f;
    for (int c = 0; c < 3; ++c) {
      in.direct.pixels[4 * p + c] = sums.direct[p][c] * weight;
      in.albedo[3 * p + c] = sums.albedo[p][c] * perSample;
      in.normal[3 * p + c] = sums.normal[p][c] * perSample;
    }
    in.depth[p] = sums.depth[p] * perSample;
  }
  // At the few samples per pixel datasets use, the traced light of pixels along creases is the
  // noisiest left: they are filtered too (measured +0.3 dB at 16 spp, docs/path-tracing.md).
  IndirectFilterParameters parameters;
  parameters.filterStraddling = true;
  film.setResolvedColour(filterIndirectLight(in, parameters));
}

void FastRenderer::shadePacket(const HitPacket& hits, Shading shading, Vec3f* colours, const PathFrame* path,
                               const PathKey* samples, PathSample* pathSamples) const {
  const int count = hits.count();
  if (shading == Shading::Path) {
    for (int k = 0; k < count; ++k) {
      const Vec3 direction = hits.direction(k).normalized();
      const std::optional<SurfaceHit> first = hits.hit(k) ? std::optional<SurfaceHit>(hits.surface(k)) : std::nullopt;
      const PathSample sample =
          path->tracer.cameraRay(hits.start(k), direction, first ? &*first : nullptr, samples[k]);
      colours[k] = sample.radiance;
      if (pathSamples) pathSamples[k] = sample;
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
      origins[k] = surfaces[k].point + kShadowEpsilon * faced[k];
      tNear[k] = 0.0;
      tFar[k] = distance - kShadowEpsilon;
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
  const PathFrame path{PathTracer(scene_, rays_, options), 0};
  const PathKey sample{0, static_cast<uint32_t>(key)};
  shadePacket(hits, shading, &colour, &path, &sample);
  return colour;
}

std::shared_ptr<const FastRenderer::SampleTable> FastRenderer::sampleTable(const RenderSettings& settings,
                                                                          int n) const {
  const std::shared_ptr<const Camera> camera = makeCamera(settings.rig, settings.traced);
  {
    std::lock_guard<std::mutex> lock(tableMutex_);
    if (table_ && table_->samplesPerAxis == n && *table_->camera == *camera) return table_;
  }
  // Built outside the lock: frames of other rigs (a vibrating robot's) build theirs meanwhile.
  auto table = std::make_shared<SampleTable>();
  table->camera = camera;
  table->samplesPerAxis = n;
  const bool central = camera->central();
  const size_t pixels = static_cast<size_t>(camera->width()) * camera->height();
  requireMemory(frameBytes(camera->width(), camera->height(), n * n, central),
                "a " + std::to_string(camera->width()) + "x" + std::to_string(camera->height()) + " frame at " +
                    std::to_string(n * n) + " spp (its sample table, the frame and its files)");
  table->firstSample.reserve(pixels + 1);
  table->centreDirections.reserve(pixels);
  table->centreSample.reserve(pixels);
  const auto record = [&](const CameraRay& ray, std::vector<Eigen::Vector3f>& directions,
                          std::vector<Eigen::Vector3f>& origins, std::vector<float>& starts) {
    directions.push_back(ray.direction.cast<float>());
    if (central) return;
    const double start = std::max(0.0, ray.origin.dot(ray.direction));
    origins.push_back((ray.origin - start * ray.direction).cast<float>());
    starts.push_back(static_cast<float>(start));
  };
  for (int j = 0; j < camera->height(); ++j)
    for (int i = 0; i < camera->width(); ++i) {
      table->firstSample.push_back(static_cast<uint32_t>(table->directions.size()));
      uint32_t centre = SampleTable::kNoSample;
      for (int b = 0; b < n; ++b)
        for (int a = 0; a < n; ++a) {
          const auto ray = camera->generateRay({Film::sample(i, j, a, b, n)});
          if (!ray) continue;
          if (2 * a + 1 == n && 2 * b + 1 == n) centre = static_cast<uint32_t>(table->directions.size());
          record(*ray, table->directions, table->origins, table->starts);
          table->gridIndex.push_back(static_cast<uint16_t>(b * n + a));
        }
      const auto middle = camera->generateRay({pixelCentre(i, j)});
      if (middle) {
        record(*middle, table->centreDirections, table->centreOrigins, table->centreStarts);
      } else {
        table->centreDirections.push_back(Eigen::Vector3f::Constant(NAN));
        if (!central) {
          table->centreOrigins.push_back(Eigen::Vector3f::Zero());
          table->centreStarts.push_back(0.0f);
        }
      }
      table->centreSample.push_back(centre);
    }
  table->firstSample.push_back(static_cast<uint32_t>(table->directions.size()));
  std::lock_guard<std::mutex> lock(tableMutex_);
  table_ = table;
  return table;
}

int64_t FastRenderer::frameBytes(int width, int height, int spp, bool central) {
  // At most every sample imaged: its direction and grid index (14 B), a non-central ray's origin
  // and start too (30 B), in vectors that may hold twice that while they grow; per pixel, the
  // centre's ray and indices (20 B, non-central 36 B), and the frame with every AOV and its
  // encoding (84 B).
  return int64_t{width} * height * (int64_t{spp} * (central ? 14 : 30) * 2 + (central ? 20 : 36) + 84);
}

FastRenderer::Placement FastRenderer::placement(const RenderSettings& settings, const CameraPlacement& camera,
                                                double seconds) {
  const Rigid worldFromView = camera.worldFromViewpoint(settings.rig, seconds);
  return {worldFromView.translation(), worldFromView.linear(), worldFromView.linear().cast<float>()};
}

void FastRenderer::loadSamples(HitPacket& hits, const Placement& at, const SampleTable& table, uint32_t first,
                               int count) {
  hits.begin(at.origin, count);
  for (int k = 0; k < count; ++k) hits.setDirection(k, at.rotationF * table.directions[first + k]);
  if (table.origins.empty()) return;
  for (int k = 0; k < count; ++k)
    hits.setOrigin(k, at.origin + at.rotation * table.origins[first + k].cast<double>(), table.starts[first + k]);
}

FastRenderer::MovingPlacements FastRenderer::movingPlacements(const RenderSettings& settings, const CameraPlacement& camera,
                                                              int samplesPerAxis) {
  MovingPlacements out;
  out.shutter = settings.rig.shutter;
  out.width = settings.rig.imageWidth(), out.height = settings.rig.imageHeight();
  out.n = samplesPerAxis;
  out.instants = pixelInstants(out.shutter, samplesPerAxis);
  const int lines = lineCount(out.shutter, out.width, out.height);
  out.samples.resize(static_cast<size_t>(lines) * out.instants.count);
  out.centres.resize(lines);
  const auto at = [&](double seconds) { return placement(settings, camera, seconds); };
  // A rolling shutter has thousands of placements (lines × instants): worked out on every core,
  // each written to its own slot.
  tbb::parallel_for(0, lines, [&](int line) {
    const double start = lineStart(out.shutter, line);
    for (int m = 0; m < out.instants.count; ++m)
      out.samples[static_cast<size_t>(line) * out.instants.count + m] = at(start + instantTime(out.shutter, m, out.instants.count));
    out.centres[line] = at(start + 0.5 * out.shutter.exposureS);
  });
  return out;
}

void FastRenderer::RowPlacements::prepare(const MovingPlacements& at, int j, int pass) {
  lineBase.resize(at.width);
  for (int i = 0; i < at.width; ++i) lineBase[i] = lineOf(at.shutter, i, j, at.width, at.height) * at.instants.count;
  instantOfGrid.resize(static_cast<size_t>(at.n) * at.n);
  for (int g = 0; g < at.n * at.n; ++g) instantOfGrid[g] = instantOf(at.shutter, g % at.n, g / at.n, at.n, pass);
}

void FastRenderer::traceMovingRow(const MovingPlacements& at, const SampleTable& table, int j, Shading shading,
                                  const PathFrame* path, MovingRowScratch& scratch, HitPacket& hits, Vec3f* sums,
                                  DenoiseSums* denoise) const {
  const size_t rowStart = static_cast<size_t>(j) * at.width;
  const uint32_t rowFirst = table.firstSample[rowStart], rowEnd = table.firstSample[rowStart + at.width];
  const uint32_t samples = rowEnd - rowFirst;
  std::fill(sums, sums + at.width, Vec3f::Zero());
  scratch.columns.resize(samples);
  for (int i = 0; i < at.width; ++i)
    std::fill(scratch.columns.begin() + (table.firstSample[rowStart + i] - rowFirst),
              scratch.columns.begin() + (table.firstSample[rowStart + i + 1] - rowFirst), static_cast<uint16_t>(i));
  const bool central = table.origins.empty();
  Vec3f colours[kRayPacketSize];
  PathSample pathSamples[kRayPacketSize];
  PathKey keys[kRayPacketSize];
  const uint32_t gridSize = static_cast<uint32_t>(at.n * at.n);
  // With fixed instants the row is traced once per instant, and the sums add up.
  for (int pass = 0; pass < at.instants.passes; ++pass) {
    scratch.row.prepare(at, j, pass);
    // In table order: a packet holds neighbouring samples of a pixel or two, each at its own
    // instant (measured faster than packets of one instant across eight pixels).
    uint16_t current = 0;
    Vec3f sum = Vec3f::Zero();
    for (uint32_t first = 0; first < samples; first += kRayPacketSize) {
      const int count = static_cast<int>(std::min<uint32_t>(kRayPacketSize, samples - first));
      hits.beginEach(count);
      for (int k = 0; k < count; ++k) {
        const uint32_t r = first + static_cast<uint32_t>(k), s = rowFirst + r;
        const Placement& p = at.samples[scratch.row.lineBase[scratch.columns[r]] + scratch.row.instantOfGrid[table.gridIndex[s]]];
        hits.setDirection(k, p.rotationF * table.directions[s]);
        if (central) hits.setOrigin(k, p.origin, 0.0f);
        else hits.setOrigin(k, p.origin + p.rotation * table.origins[s].cast<double>(), table.starts[s]);
      }
      rays_.intersectPacket(hits);
      if (path)
        for (int k = 0; k < count; ++k) {
          const uint32_t s = rowFirst + first + static_cast<uint32_t>(k);
          // Each pass continues the pixel's sequence: its instants are more samples of one pixel.
          keys[k] = {mixKey(path->key, static_cast<uint64_t>(j) * at.width + scratch.columns[first + k]),
                     pass * gridSize + table.gridIndex[s]};
        }
      shadePacket(hits, shading, colours, path, keys, denoise ? pathSamples : nullptr);
      // A pixel's samples are consecutive: summed in a register, stored when the pixel changes.
      for (int k = 0; k < count; ++k) {
        const uint16_t column = scratch.columns[first + k];
        if (denoise) denoise->add(static_cast<size_t>(j) * at.width + column, pathSamples[k], hits, k);
        if (column != current) {
          sums[current] += sum;
          sum = Vec3f::Zero();
          current = column;
        }
        sum += colours[k];
      }
    }
    sums[current] += sum;
  }
}

template <typename PlacementOfPixel>
void FastRenderer::loadCentres(HitPacket& hits, const PlacementOfPixel& at, const SampleTable& table, const size_t* pixels,
                               int count) {
  hits.begin(Vec3::Zero(), count);
  const bool central = table.centreOrigins.empty();
  for (int k = 0; k < count; ++k) {
    const Placement& p = at(pixels[k]);
    hits.setDirection(k, p.rotationF * table.centreDirections[pixels[k]]);
    if (central) hits.setOrigin(k, p.origin, 0.0f);
    else hits.setOrigin(k, p.origin + p.rotation * table.centreOrigins[pixels[k]].cast<double>(), table.centreStarts[pixels[k]]);
  }
}

void FastRenderer::render(const CameraPlacement& placement, const RenderSettings& settings, Film& film) const {
  checkRenderSettings(settings);
  checkPlacement(placement);
  film.requireFits(settings, "FastRenderer::render");
  renderPass(placement, settings, film);
}

ImageRGBA FastRenderer::render(const CameraPlacement& placement, const RenderSettings& settings) const {
  Film film = filmFor(settings);
  render(placement, settings, film);
  return film.takeImage();
}

ImageRGBA FastRenderer::render(const CameraPlacement& placement, const RenderSettings& settings, AovFrame& aovs) const {
  Film film = filmFor(settings, /*wantsAovs=*/true);
  film.reuseAovPlanes(std::move(aovs));
  render(placement, settings, film);
  aovs = film.takeAovs();
  return film.takeImage();
}

void FastRenderer::beginAovs(Film& film) const {
  if (scene_.objects.size() > kMaxInstances)
    throw InputError(showPath(scene_.path) + ": " + std::to_string(scene_.objects.size()) +
                     " objects; instance ids are 16-bit (at most " + std::to_string(kMaxInstances) + ")");
  film.beginAovs();
}

namespace {

void recordAov(Film& film, size_t pixel, const SurfaceHit& hit, const Vec3& direction) {
  const Vec3 n = hit.normal.dot(direction) > 0.0 ? Vec3(-hit.normal) : hit.normal;  // two-sided
  film.recordAov(pixel, static_cast<float>(hit.t), static_cast<uint16_t>(hit.object + 1), n);
}

}  // namespace

template <typename PlacementOfPixel>
uint32_t FastRenderer::recordCentreAovs(const PlacementOfPixel& at, const SampleTable& table, const size_t* pixels,
                                        int count, HitPacket& hits, Film& film) const {
  loadCentres(hits, at, table, pixels, count);
  rays_.intersectPacket(hits);
  for (int k = 0; k < count; ++k)
    if (hits.hit(k)) recordAov(film, pixels[k], hits.surface(k), hits.direction(k));
  return hits.mask();
}

void FastRenderer::renderAovsOnly(const CameraPlacement& camera, const RenderSettings& settings, Film& film) const {
  RenderSettings centreOnly = settings;
  centreOnly.spp = 1;
  checkRenderSettings(centreOnly);
  checkPlacement(camera);
  const std::shared_ptr<const SampleTable> table = sampleTable(centreOnly, 1);  // checks the frame fits in memory
  if (film.width() != settings.rig.imageWidth() || film.height() != settings.rig.imageHeight() || !film.wantsAovs())
    throw std::invalid_argument("FastRenderer::renderAovsOnly: the film does not match the settings or wants no AOVs");
  beginAovs(film);
  const int width = film.width(), height = film.height();
  const Placement still = placement(settings, camera);
  const bool moves = moving(camera, settings.rig);
  const MovingPlacements motion = moves ? movingPlacements(settings, camera, 1) : MovingPlacements{};
  const auto at = [&](size_t p) -> const Placement& {
    return moves ? motion.centre(static_cast<int>(p % width), static_cast<int>(p / width)) : still;
  };
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    // The same packets as a render pass traces for its centre rays, so both give the same AOVs.
    HitPacket hits;
    size_t pending[kRayPacketSize];
    int count = 0;
    const auto trace = [&] {
      const uint32_t hit = recordCentreAovs(at, *table, pending, count, hits, film);
      for (int k = 0; k < count; ++k)
        if (!((hit >> k) & 1u)) film.recordNoHit(pending[k]);
      count = 0;
    };
    for (int j = rows.begin(); j != rows.end(); ++j) {
      for (int i = 0; i < width; ++i) {
        const size_t p = static_cast<size_t>(j) * width + i;
        const Eigen::Vector3f& centre = table->centreDirections[p];
        if (std::isnan(centre.x())) {
          film.recordNoHit(p);
          continue;
        }
        pending[count++] = p;
        if (count == kRayPacketSize) trace();
      }
      if (count > 0) trace();  // packets stay within a row, as in a render pass
    }
  });
}

void FastRenderer::renderPass(const CameraPlacement& camera, const RenderSettings& settings, Film& film) const {
  const bool aovs = film.wantsAovs();
  const auto n = samplesPerAxis(settings.spp);
  const std::shared_ptr<const SampleTable> table = sampleTable(settings, *n);  // checks the frame fits in memory
  film.begin();
  if (aovs) beginAovs(film);
  const int width = settings.rig.imageWidth(), height = settings.rig.imageHeight();
  const Placement at = placement(settings, camera);
  // A moving frame places each ray by its line and instant (the still one's path is unchanged,
  // so a still robot's frame is the static frame bit for bit, whatever the shutter).
  const bool moves = moving(camera, settings.rig);
  const MovingPlacements motion = moves ? movingPlacements(settings, camera, *n) : MovingPlacements{};
  const int passes = moves ? motion.instants.passes : 1;
  const auto centreAt = [&](size_t p) -> const Placement& {
    return moves ? motion.centre(static_cast<int>(p % width), static_cast<int>(p / width)) : at;
  };
  const float weight = film.weight(passes);
  const std::optional<PathFrame> path = pathFrame(settings, camera);
  DenoiseSums denoiseSums;
  DenoiseSums* denoising = path && settings.denoise ? &denoiseSums : nullptr;
  if (denoising) denoiseSums.resize(static_cast<size_t>(width) * height);
  constexpr int kPacket = kRayPacketSize;
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    std::vector<Vec3f> sums(width);
    std::vector<uint8_t> centreRecorded(width);
    MovingRowScratch scratch;
    HitPacket hits;
    Vec3f colours[kPacket];
    PathSample pathSamples[kPacket];
    for (int j = rows.begin(); j != rows.end(); ++j) {
      const size_t rowStart = static_cast<size_t>(j) * width;
      std::fill(centreRecorded.begin(), centreRecorded.end(), uint8_t{0});
      // A still frame's row: its samples are contiguous in the table; packets run across pixel
      // borders. Each pixel's sum is built in a register from zero in sample order (as one ray at
      // a time would) and stored once its last sample is in.
      if (moves) {
        traceMovingRow(motion, *table, j, settings.shading, path ? &*path : nullptr, scratch, hits, sums.data(), denoising);
      } else {
        const uint32_t rowEnd = table->firstSample[rowStart + width];
        size_t pixel = rowStart;
        uint32_t pixelEnd = table->firstSample[pixel + 1];
        Vec3f sum = Vec3f::Zero();
        const auto storePixel = [&] {
          sums[pixel - rowStart] = sum;
          sum = Vec3f::Zero();
          if (++pixel < rowStart + width) pixelEnd = table->firstSample[pixel + 1];
        };
        for (uint32_t first = table->firstSample[rowStart]; first < rowEnd; first += kPacket) {
          const int count = static_cast<int>(std::min<uint32_t>(kPacket, rowEnd - first));
          loadSamples(hits, at, *table, first, count);
          rays_.intersectPacket(hits);
          PathKey keys[kPacket];
          if (path) {
            size_t keyPixel = pixel;
            uint32_t keyEnd = pixelEnd;
            for (int k = 0; k < count; ++k) {
              const uint32_t s = first + static_cast<uint32_t>(k);
              while (keyEnd <= s) keyEnd = table->firstSample[++keyPixel + 1];
              keys[k] = {mixKey(path->key, keyPixel), table->gridIndex[s]};
            }
          }
          shadePacket(hits, settings.shading, colours, path ? &*path : nullptr, keys, denoising ? pathSamples : nullptr);
          for (int k = 0; k < count; ++k) {
            const uint32_t s = first + static_cast<uint32_t>(k);
            while (pixelEnd <= s) storePixel();
            sum += colours[k];
            if (denoising) denoising->add(pixel, pathSamples[k], hits, k);
            if (aovs && s == table->centreSample[pixel] && hits.hit(k)) {
              recordAov(film, pixel, hits.surface(k), hits.direction(k));
              centreRecorded[pixel - rowStart] = 1;
            }
          }
        }
        while (pixel < rowStart + width) storePixel();  // the last pixel, and any beyond the rim
      }
      if (aovs) {
        // At even n no sample is the centre, and a moving frame's AOVs are taken at the pixel's
        // own time: one more ray per pixel, again in packets.
        size_t pending[kPacket];
        int count = 0;
        const auto traceCentres = [&] {
          const uint32_t hit = recordCentreAovs(centreAt, *table, pending, count, hits, film);
          for (int k = 0; k < count; ++k)
            if ((hit >> k) & 1u) centreRecorded[pending[k] - rowStart] = 1;
          count = 0;
        };
        for (int i = 0; i < width; ++i) {
          const Eigen::Vector3f& centre = table->centreDirections[rowStart + i];
          if ((!moves && table->centreSample[rowStart + i] != SampleTable::kNoSample) || std::isnan(centre.x())) continue;
          pending[count++] = rowStart + i;
          if (count == kPacket) traceCentres();
        }
        if (count > 0) traceCentres();
        for (int i = 0; i < width; ++i)
          if (!centreRecorded[i]) film.recordNoHit(rowStart + i);
      }
      for (int i = 0; i < width; ++i) {
        const size_t p = rowStart + i;
        film.addSamples(i, j, sums[i].data());
        film.setImagedGridPoints(i, j, static_cast<int>(table->firstSample[p + 1] - table->firstSample[p]));
      }
    }
  });
  film.resolve(passes);
  if (denoising) {
    std::vector<uint32_t> imaged(static_cast<size_t>(width) * height);
    for (size_t p = 0; p < imaged.size(); ++p) imaged[p] = (table->firstSample[p + 1] - table->firstSample[p]) * passes;
    denoise(film, denoiseSums, weight, imaged);
  }
}

}  // namespace omnicam
