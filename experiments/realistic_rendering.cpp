#include "realistic_rendering.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "errors.h"
#include "render_request.h"
#include "render_settings.h"

namespace omnicam {

namespace {

// Cycles' samples per session: independent sessions are averaged above it (and spp stays a
// perfect square, as every engine's sample grid needs).
constexpr int kSamplesPerSession = 1024;

}  // namespace

std::string RealisticRendering::describe() const {
  char clamp[64] = "no clamp";
  if (tracing.clampIndirect > 0.0) std::snprintf(clamp, sizeof clamp, "indirect samples clamped at %.2g", tracing.clampIndirect);
  const std::string lamps =
      lampDiameter > 0.0 ? "lamps: discs of " + std::to_string(std::lround(lampDiameter * 100.0)) + " cm facing down"
                         : std::string("point lamps");
  return lamps + ", mirror " + (tracing.mirrorSeenByIndirectRays ? "seen by bounces" : "seen by camera rays only") + ", " +
         std::to_string(tracing.diffuseBounces) + " diffuse and " + std::to_string(tracing.glossyBounces) +
         " glossy bounces, " + clamp + (tracing.filterIndirect ? ", indirect light filtered" : "");
}

RealisticRendering realisticRenderingBefore() {
  RealisticRendering r;
  r.name = "before";
  r.lampDiameter = 0.0;
  r.tracing.mirrorSeenByIndirectRays = true;
  r.spp = 16;
  return r;
}

RealisticRendering realisticRenderingPhysical() {
  RealisticRendering r;
  r.name = "physical";
  r.lampDiameter = 0.5;
  r.spp = 100;
  return r;
}

RealisticRendering realisticRendering() {
  RealisticRendering r = realisticRenderingPhysical();
  r.name = "today";
  r.tracing.filterIndirect = true;
  // Measured (docs/texture-realism.md): at 360 px every frame of the study is >= 35 dB against an
  // unfiltered 1024-spp reference from 36 spp on, at 1.8x the time of an unfiltered 36 spp.
  r.spp = 36;
  return r;
}

RealisticRendering convergedReferenceOf(RealisticRendering setup) {
  setup.name += "_reference";
  setup.tracing.filterIndirect = false;
  return setup;
}

namespace {

// What renderRealistic gives Blender: the hall with the setup's lamps, the settings of one session
// and the options; `sessions` sessions of settings.spp each.
struct RealisticJob {
  Scene scene;
  RenderSettings settings;
  BlenderOptions options;
  int sessions = 1;
};

RealisticJob realisticJob(const Scene& hall, const RealisticRendering& setup, int size, int spp, int seed, double timeoutSeconds) {
  if (spp < 1) throw InputError("realistic rendering: spp must be at least 1");
  RealisticJob job;
  job.scene = hall;
  for (PointLight& lamp : job.scene.lights) lamp.diameter = setup.lampDiameter;
  job.options.timeoutSeconds = timeoutSeconds;
  job.options.pathTracing = setup.tracing;
  job.options.seed = seed;
  job.sessions = std::max(1, (spp + kSamplesPerSession - 1) / kSamplesPerSession);
  if (job.sessions > 1 && spp % kSamplesPerSession != 0)
    throw InputError("realistic rendering: above " + std::to_string(kSamplesPerSession) + " spp, a multiple of it");
  const int sessionSpp = job.sessions > 1 ? kSamplesPerSession : spp;
  job.settings =
      requestedSettings(job.scene.rig.resized(size), {{RequestField::Shading, "lit"}, {RequestField::Spp, int64_t{sessionSpp}}});
  return job;
}

}  // namespace

std::string realisticJobDigest(const Scene& hall, const RobotPose& pose, const RealisticRendering& setup, int size, int spp,
                               int seed) {
  const RealisticJob job = realisticJob(hall, setup, size, spp, seed, 0.0);
  return blenderJobDigest(job.scene, CameraPlacement(pose), job.settings, job.options) + " sessions " + std::to_string(job.sessions);
}

std::vector<ImageRGBA> renderRealistic(const Scene& hall, const std::vector<RobotPose>& poses,
                                       const RealisticRendering& setup, int size, int spp, int seed,
                                       double timeoutSeconds) {
  RealisticJob job = realisticJob(hall, setup, size, spp, seed, timeoutSeconds);
  const Scene& scene = job.scene;
  const RenderSettings& settings = job.settings;
  BlenderOptions& options = job.options;
  const int sessions = job.sessions;
  std::vector<ImageRGBA> sum;
  for (int k = 0; k < sessions; ++k) {
    options.seed = seed + k;
    std::vector<ImageRGBA> images = renderWithBlender(scene, std::vector<CameraPlacement>(poses.begin(), poses.end()), settings, options);
    if (sum.empty()) {
      sum = std::move(images);
      continue;
    }
    for (size_t f = 0; f < sum.size(); ++f)
      for (size_t p = 0; p < sum[f].pixels.size(); p += 4)
        for (size_t c = 0; c < 3; ++c) sum[f].pixels[p + c] += images[f].pixels[p + c];
  }
  if (sessions > 1)
    for (ImageRGBA& image : sum)
      for (size_t p = 0; p < image.pixels.size(); p += 4)
        for (size_t c = 0; c < 3; ++c) image.pixels[p + c] /= static_cast<float>(sessions);
  return sum;
}

}  // namespace omnicam
