#include "fast_renderer.h"

#include <embree3/rtcore_config.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "errors.h"
#include "make_camera.h"
#include "memory_budget.h"

namespace omnicam {

std::string fastRendererVersion() {
  return std::string("omnicam ") + OMNICAM_VERSION + " (Embree " + RTC_VERSION_STRING + ")";
}

FastRenderer::FastRenderer(const Scene& scene) : scene_(scene), rays_(scene) {}

std::shared_ptr<const EnvironmentLight> FastRenderer::environmentLight() const {
  std::call_once(environmentOnce_, [this] { environmentLight_ = environmentLightOf(scene_); });
  return environmentLight_;
}

std::shared_ptr<const SampleTable> FastRenderer::sampleTable(const RenderSettings& settings, int n) const {
  const std::shared_ptr<const Camera> camera = makeCamera(settings.rig, settings.traced);
  {
    std::lock_guard<std::mutex> lock(tableMutex_);
    if (table_ && table_->samplesPerAxis == n && *table_->camera == *camera) return table_;
  }
  // Built outside the lock: frames of other rigs (a vibrating robot's) build theirs meanwhile.
  const bool denoised = settings.denoise && settings.shading == Shading::Path;
  requireMemory(frameBytes(camera->width(), camera->height(), n * n, camera->central(), denoised),
                "a " + std::to_string(camera->width()) + "x" + std::to_string(camera->height()) + " frame at " +
                    std::to_string(n * n) + " spp (its sample table, the frame and its files)");
  std::shared_ptr<const SampleTable> table = buildSampleTable(camera, n);
  std::lock_guard<std::mutex> lock(tableMutex_);
  table_ = table;
  return table;
}

int64_t FastRenderer::frameBytes(int width, int height, int spp, bool central, bool denoised) {
  // At most every sample imaged: its direction and grid index (14 B), a non-central ray's origin
  // and start too (30 B), in vectors that may hold twice that while they grow; per pixel, the
  // centre's ray and indices (20 B, non-central 36 B), and the frame with every AOV and its
  // encoding (84 B). A denoised path frame adds its sums and the filter's planes: DenoiseSums
  // 129 B, the filter's inputs 108, guides 26, two parts' levels 72, outputs 44, not all live at
  // once (about 320 B at the peak, budgeted as 355).
  const int64_t filter = denoised ? 355 : 0;
  return int64_t{width} * height * (int64_t{spp} * (central ? 14 : 30) * 2 + (central ? 20 : 36) + 84 + filter);
}

void FastRenderer::traceMovingRow(const MovingPlacements& at, const SampleTable& table, int j, Shading shading,
                                  const PathFrame* path, RowScratch& scratch, HitPacket& hits, Vec3f* sums,
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
        const RayPlacement& p = at.samples[scratch.row.lineBase[scratch.columns[r]] + scratch.row.instantOfGrid[table.gridIndex[s]]];
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
        if (denoise) denoise->add(static_cast<size_t>(j) * at.width + column, pathSamples[k]);
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

void FastRenderer::traceStillRow(const FrameJob& job, int j, int width, HitPacket& hits, Vec3f* sums, RowScratch& scratch,
                                 Film& film, LuminanceMoments* moments) const {
  const SampleTable& table = job.table;
  const size_t rowStart = static_cast<size_t>(j) * width;
  // The row's samples are contiguous in the table; packets run across pixel borders. Each
  // pixel's sum is built in a register from zero in sample order (as one ray at a time would) and
  // stored once its last sample is in.
  const uint32_t rowEnd = table.firstSample[rowStart + width];
  size_t pixel = rowStart;
  uint32_t pixelEnd = table.firstSample[pixel + 1];
  Vec3f sum = Vec3f::Zero();
  LuminanceMoments moment;
  const auto storePixel = [&] {
    sums[pixel - rowStart] = sum;
    sum = Vec3f::Zero();
    if (moments) moments[pixel - rowStart] = moment;
    moment = {};
    if (++pixel < rowStart + width) pixelEnd = table.firstSample[pixel + 1];
  };
  Vec3f colours[kRayPacketSize];
  PathSample pathSamples[kRayPacketSize];
  for (uint32_t first = table.firstSample[rowStart]; first < rowEnd; first += kRayPacketSize) {
    const int count = static_cast<int>(std::min<uint32_t>(kRayPacketSize, rowEnd - first));
    loadSamples(hits, job.still, table, first, count);
    rays_.intersectPacket(hits);
    PathKey keys[kRayPacketSize];
    if (job.path) {
      size_t keyPixel = pixel;
      uint32_t keyEnd = pixelEnd;
      for (int k = 0; k < count; ++k) {
        const uint32_t s = first + static_cast<uint32_t>(k);
        while (keyEnd <= s) keyEnd = table.firstSample[++keyPixel + 1];
        keys[k] = {mixKey(job.path->key, keyPixel), table.gridIndex[s]};
      }
    }
    shadePacket(hits, job.shading, colours, job.path, keys, job.denoise ? pathSamples : nullptr);
    for (int k = 0; k < count; ++k) {
      const uint32_t s = first + static_cast<uint32_t>(k);
      while (pixelEnd <= s) storePixel();
      sum += colours[k];
      if (moments) {
        const double l = luminance(colours[k].data());
        moment.sum += l;
        moment.squares += l * l;
      }
      if (job.denoise) job.denoise->add(pixel, pathSamples[k]);
      if (job.aovs && s == table.centreSample[pixel] && hits.hit(k)) {
        recordSampleAov(film, pixel, hits, k);
        scratch.centreRecorded[pixel - rowStart] = 1;
      }
    }
  }
  while (pixel < rowStart + width) storePixel();  // the last pixel, and any beyond the rim
}

void FastRenderer::renderPass(const CameraPlacement& camera, const RenderSettings& settings, Film& film) const {
  const bool aovs = film.wantsAovs();
  const auto n = samplesPerAxis(settings.spp);
  const std::shared_ptr<const SampleTable> table = sampleTable(settings, *n);  // checks the frame fits in memory
  film.begin();
  if (aovs) beginAovs(film);
  const int width = settings.rig.imageWidth(), height = settings.rig.imageHeight();
  const RayPlacement still = rayPlacement(settings, camera);
  // A moving frame places each ray by its line and instant (the still one's path is unchanged,
  // so a still robot's frame is the static frame bit for bit, whatever the shutter).
  const bool moves = moving(camera, settings.rig);
  const MovingPlacements motion = moves ? movingPlacements(settings, camera, *n) : MovingPlacements{};
  const int passes = moves ? motion.instants.passes : 1;
  const std::optional<PathFrame> path = pathFrame(settings, camera);
  const bool adaptive = settings.adaptiveSpp > 0;
  if (adaptive && moves) throw InputError("adaptive sampling: not with a moving frame (its shutter is open while the robot moves)");
  const size_t pixels = static_cast<size_t>(width) * height;
  std::vector<Vec3f> frameSums(adaptive ? pixels : 0);  // adaptive: the first grid's sums, then the finest
  std::vector<LuminanceMoments> frameMoments(adaptive ? pixels : 0);
  DenoiseSums denoiseSums;
  DenoiseSums* denoising = path && settings.denoise ? &denoiseSums : nullptr;
  if (denoising) denoiseSums.resize(static_cast<size_t>(width) * height);
  const FrameJob job{.table = *table,
                     .still = still,
                     .moving = moves ? &motion : nullptr,
                     .shading = settings.shading,
                     .path = path ? &*path : nullptr,
                     .denoise = denoising,
                     .aovs = aovs,
                     .centresFromSamples = !moves};
  const auto rowStart = [width](int j) { return static_cast<size_t>(j) * width; };
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    std::vector<Vec3f> sums(width);
    RowScratch scratch;
    scratch.centreRecorded.resize(width);
    HitPacket hits;
    for (int j = rows.begin(); j != rows.end(); ++j) {
      std::fill(scratch.centreRecorded.begin(), scratch.centreRecorded.end(), uint8_t{0});
      if (moves) traceMovingRow(motion, *table, j, settings.shading, job.path, scratch, hits, sums.data(), denoising);
      else traceStillRow(job, j, width, hits, sums.data(), scratch, film, adaptive ? &frameMoments[rowStart(j)] : nullptr);
      if (aovs) finishRowAovs(job, j, width, hits, scratch.centreRecorded, film);
      for (int i = 0; i < width; ++i) {
        if (adaptive) frameSums[rowStart(j) + i] = sums[i];
        else film.addSamples(i, j, sums[i].data());
        film.setImagedGridPoints(i, j, table->imagedSamples(static_cast<size_t>(j) * width + i));
      }
    }
  });
  if (adaptive) refineAdaptively(job, settings, frameSums, frameMoments, film);
  film.resolve(passes);
  if (denoising && !moves) refineCoverage(job, width, height, denoiseSums);
  if (denoising) {
    std::vector<uint32_t> imaged(static_cast<size_t>(width) * height);
    for (size_t p = 0; p < imaged.size(); ++p) imaged[p] = static_cast<uint32_t>(table->imagedSamples(p)) * passes;
    denoiseFilm(film, denoiseSums, film.weight(passes), imaged);
  }
}

}  // namespace omnicam
