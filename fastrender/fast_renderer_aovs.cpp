#include "fast_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <stdexcept>

#include "errors.h"

namespace omnicam {

namespace {

void recordAov(Film& film, size_t pixel, const SurfaceHit& hit, const Vec3& direction) {
  const Vec3 n = hit.normal.dot(direction) > 0.0 ? Vec3(-hit.normal) : hit.normal;  // two-sided
  film.recordAov(pixel, static_cast<float>(hit.t), static_cast<uint16_t>(hit.object + 1), n);
}

}  // namespace

void FastRenderer::beginAovs(Film& film) const {
  if (scene_.objects.size() > kMaxInstances)
    throw InputError(showPath(scene_.path) + ": " + std::to_string(scene_.objects.size()) +
                     " objects; instance ids are 16-bit (at most " + std::to_string(kMaxInstances) + ")");
  film.beginAovs();
}

void FastRenderer::recordSampleAov(Film& film, size_t pixel, const HitPacket& hits, int k) {
  recordAov(film, pixel, hits.surface(k), hits.direction(k));
}

uint32_t FastRenderer::recordCentreAovs(const CentrePlacements& at, const SampleTable& table, const size_t* pixels, int count,
                                        HitPacket& hits, Film& film) const {
  loadCentres(hits, at, table, pixels, count);
  rays_.intersectPacket(hits);
  for (int k = 0; k < count; ++k)
    if (hits.hit(k)) recordAov(film, pixels[k], hits.surface(k), hits.direction(k));
  return hits.mask();
}

void FastRenderer::finishRowAovs(const FrameJob& job, int j, int width, HitPacket& hits, std::vector<uint8_t>& centreRecorded,
                                 Film& film) const {
  const size_t rowStart = static_cast<size_t>(j) * width;
  const CentrePlacements at{job.still, job.moving};
  size_t pending[kRayPacketSize];
  int count = 0;
  const auto traceCentres = [&] {
    const uint32_t hit = recordCentreAovs(at, job.table, pending, count, hits, film);
    for (int k = 0; k < count; ++k)
      if ((hit >> k) & 1u) centreRecorded[pending[k] - rowStart] = 1;
    count = 0;
  };
  for (int i = 0; i < width; ++i) {
    const size_t p = rowStart + i;
    if (std::isnan(job.table.centreDirections[p].x())) continue;
    if (job.centresFromSamples && job.table.centreSample[p] != SampleTable::kNoSample) continue;
    pending[count++] = p;
    if (count == kRayPacketSize) traceCentres();
  }
  if (count > 0) traceCentres();  // packets stay within a row
  for (int i = 0; i < width; ++i)
    if (!centreRecorded[i]) film.recordNoHit(rowStart + i);
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
  const RayPlacement still = rayPlacement(settings, camera);
  const bool moves = moving(camera, settings.rig);
  const MovingPlacements motion = moves ? movingPlacements(settings, camera, 1) : MovingPlacements{};
  // Every centre traced, in the packets a render pass traces its centre rays in, so both give the
  // same AOVs.
  const FrameJob job{.table = *table, .still = still, .moving = moves ? &motion : nullptr, .shading = settings.shading, .aovs = true};
  tbb::parallel_for(tbb::blocked_range<int>(0, film.height()), [&](const tbb::blocked_range<int>& rows) {
    HitPacket hits;
    std::vector<uint8_t> centreRecorded(film.width());
    for (int j = rows.begin(); j != rows.end(); ++j) {
      std::fill(centreRecorded.begin(), centreRecorded.end(), uint8_t{0});
      finishRowAovs(job, j, film.width(), hits, centreRecorded, film);
    }
  });
}

}  // namespace omnicam
