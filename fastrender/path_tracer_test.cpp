// Path shading against closed forms: a white furnace, a disc luminaire's irradiance, a point
// light's inverse-square fall-off; and the determinism frames promise.
#include "path_tracer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include "fast_renderer.h"
#include "image_compare.h"
#include "scene_loader.h"
#include "thread_count_testing.h"

namespace omnicam {
namespace {

Material lambertian(const Vec3f& albedo, const Vec3f& emission = Vec3f::Zero()) {
  Material m;
  m.name = "surface";
  m.color = albedo;
  m.emission = emission;
  return m;
}

// The mean radiance of `paths` paths along one ray (keys 0, 1, …), and its standard error.
struct Estimate {
  Vec3 mean = Vec3::Zero();
  double standardError = 0.0;  // of the first channel
};
Estimate meanRadiance(const FastRenderer& renderer, const Vec3& origin, const Vec3& direction, int paths, int bounces) {
  Vec3 sum = Vec3::Zero();
  double squares = 0.0;
  for (int k = 0; k < paths; ++k) {
    const Vec3 v = renderer.radiance(origin, direction, Shading::Path, static_cast<uint64_t>(k), bounces).cast<double>();
    sum += v;
    squares += v.x() * v.x();
  }
  Estimate e;
  e.mean = sum / paths;
  e.standardError = std::sqrt(std::max(0.0, squares / paths - e.mean.x() * e.mean.x()) / paths);
  return e;
}

// A closed box of albedo ρ whose walls emit E: the radiance everywhere inside is E/(1 − ρ) (the
// sum E·Σ ρ^k of light reflected k times), whatever the box's shape.
TEST(PathTracer, WhiteFurnaceGivesEmissionOverOneMinusAlbedo) {
  for (const double albedo : {0.3, 0.5, 0.8}) {
    Scene s;
    const float e = 0.25f;
    s.materials.push_back(lambertian(Vec3f::Constant(static_cast<float>(albedo)), Vec3f::Constant(e)));
    s.objects.push_back({"box", 0, Box{{0.0, 0.0, 1.0}, {3.0, 2.0, 2.0}, 20.0}, ""});
    const FastRenderer renderer(s);
    // 0.8^200 is nothing: the bounce limit does not cut the sum.
    const Estimate estimate = meanRadiance(renderer, {0.2, -0.1, 1.1}, Vec3(0.3, 0.5, -0.8).normalized(), 20000, 200);
    const double expected = e / (1.0 - albedo);
    EXPECT_NEAR(estimate.mean.x(), expected, 4.0 * estimate.standardError + 1e-6) << "albedo " << albedo;
    EXPECT_LT(estimate.standardError, 0.01 * expected) << "the estimate is too noisy to test anything";
  }
}

// With D bounces the furnace holds light reflected at most D + 1 times: E·(1 − ρ^(D+2))/(1 − ρ).
TEST(PathTracer, BounceLimitKeepsLightReflectedAtMostBouncesPlusOneTimes) {
  const double albedo = 0.5;
  Scene s;
  s.materials.push_back(lambertian(Vec3f::Constant(0.5f), Vec3f::Ones()));
  s.objects.push_back({"box", 0, Box{{0.0, 0.0, 1.0}, {2.0, 2.0, 2.0}, 0.0}, ""});
  const FastRenderer renderer(s);
  for (const int bounces : {0, 1, 2, 4}) {
    const Estimate estimate = meanRadiance(renderer, {0.0, 0.0, 1.0}, Vec3(0, 0, -1), 20000, bounces);
    const double expected = (1.0 - std::pow(albedo, bounces + 2)) / (1.0 - albedo);
    EXPECT_NEAR(estimate.mean.x(), expected, 4.0 * estimate.standardError + 1e-6) << bounces << " bounces";
  }
}

// A floor of albedo ρ under one scene light; the scene light's intensity I means (docs/conventions.md §3):
// a point of radiant intensity π·d₀²·I, d₀ = 3 m; a disc of diameter D facing down, of radiance
// π²·d₀²·I/A, A = π(D/2)².
Scene floorUnder(const PointLight& light, float albedo) {
  Scene s;
  s.materials.push_back(lambertian(Vec3f::Constant(albedo)));
  s.objects.push_back({"floor", 0, Quad{{-100, -100, 0}, {200, 0, 0}, {0, 200, 0}}, ""});
  s.lights.push_back(light);
  return s;
}

TEST(PathTracer, PointLightFallsOffWithTheInverseSquareOfDistance) {
  const double d0 = 3.0, rho = 0.6, intensity = 0.7;
  for (const double height : {1.0, 2.0, 4.0})
    for (const double offset : {0.0, 1.5}) {
      const Scene s = floorUnder({"lamp", {0.0, 0.0, height}, Vec3f::Constant(static_cast<float>(intensity)), 0.0},
                                 static_cast<float>(rho));
      const FastRenderer renderer(s);
      // Looking straight down at the floor `offset` metres from the point under the lamp.
      const Vec3 origin(offset, 0.0, 0.5);
      const double r2 = height * height + offset * offset, cosine = height / std::sqrt(r2);
      const double expected = rho / kPi * (kPi * d0 * d0 * intensity) * cosine / r2;
      // A point light is sampled exactly and the open scene returns nothing else: no noise.
      const Vec3f radiance = renderer.radiance(origin, Vec3(0, 0, -1), Shading::Path, 7, 2);
      EXPECT_NEAR(radiance.x(), expected, 1e-5 * expected) << "height " << height << ", offset " << offset;
    }
}

// Irradiance at a point of a plane parallel to a Lambertian disc of radiance L and radius R, at
// height h below it and a horizontal distance d from its axis (the view-factor closed form):
// E = (πL/2)·(1 − (h² + d² − R²)/√((h² + d² + R²)² − 4R²d²)).
double discIrradiance(double radiance, double radius, double height, double d) {
  const double h2 = height * height, d2 = d * d, r2 = radius * radius;
  return 0.5 * kPi * radiance * (1.0 - (h2 + d2 - r2) / std::sqrt((h2 + d2 + r2) * (h2 + d2 + r2) - 4.0 * r2 * d2));
}

TEST(PathTracer, DiscLuminaireGivesTheClosedFormIrradiance) {
  const double d0 = 3.0, rho = 0.5, intensity = 0.35, diameter = 0.8, height = 1.2;
  const double radius = 0.5 * diameter, area = kPi * radius * radius;
  const double radiance = kPi * kPi * d0 * d0 * intensity / area;
  const Scene s = floorUnder({"lamp", {0.0, 0.0, height}, Vec3f::Constant(static_cast<float>(intensity)), diameter},
                             static_cast<float>(rho));
  const FastRenderer renderer(s);
  for (const double d : {0.0, 0.3, 1.0, 2.5}) {
    const Estimate estimate = meanRadiance(renderer, {d, 0.0, 0.5}, Vec3(0, 0, -1), 20000, 0);
    const double expected = rho / kPi * discIrradiance(radiance, radius, height, d);
    EXPECT_NEAR(estimate.mean.x(), expected, 4.0 * estimate.standardError + 1e-6 * expected) << "d = " << d;
    EXPECT_LT(estimate.standardError, 0.01 * expected) << "d = " << d;
  }
  // Seen from below, the disc is its radiance.
  EXPECT_NEAR(renderer.radiance({0.1, 0.0, 0.5}, Vec3(0, 0, 1), Shading::Path, 1, 2).x(), radiance, 1e-4 * radiance);
  // It emits nothing upward: a ceiling above it, and nothing else, stays dark.
  Scene ceiling;
  ceiling.materials.push_back(lambertian(Vec3f::Constant(0.9f)));
  ceiling.objects.push_back({"ceiling", 0, Quad{{-100, -100, 2.0}, {200, 0, 0}, {0, 200, 0}}, ""});
  ceiling.lights = s.lights;
  const FastRenderer dark(ceiling);
  EXPECT_EQ(meanRadiance(dark, {0.6, 0.0, 1.5}, Vec3(0, 0, 1), 2000, 2).mean.x(), 0.0);
}

// Denoised frames scatter a ray from the first surface for a share of the samples only: the
// expectation stays the closed form (the light sample's MIS weight counts the share), and what a
// denoiser keeps as traced is the light sample alone.
TEST(PathTracer, IndirectShareKeepsTheClosedFormsAndKeepsOnlyTheLightSampleAsDirect) {
  const auto mean = [](const Scene& s, const Vec3& origin, const Vec3& direction, double share, int bounces) {
    const FastRenderer renderer(s);
    PathTracingOptions options;
    options.indirectShare = share;
    options.diffuseBounces = bounces;
    const PathTracer tracer(s, renderer.rays(), options);
    const std::optional<SurfaceHit> first = renderer.rays().intersect(origin, direction);
    const int paths = 40000;
    Vec3 radiance = Vec3::Zero(), direct = Vec3::Zero();
    double squares = 0.0;
    for (int k = 0; k < paths; ++k) {
      // 64 pixels of 625 samples each: the stratified share is exact per pixel.
      const PathSample sample = tracer.cameraRay(origin, direction, first ? &*first : nullptr,
                                                 {static_cast<uint64_t>(k / 625), static_cast<uint32_t>(k % 625)});
      radiance += sample.radiance.cast<double>();
      direct += sample.direct.cast<double>();
      squares += sample.radiance.x() * sample.radiance.x();
    }
    radiance /= paths;
    const double standardError = std::sqrt(std::max(0.0, squares / paths - radiance.x() * radiance.x()) / paths);
    return std::make_tuple(radiance.x(), standardError, direct.x() / paths);
  };
  // A floor 0.3 m beside the axis of a disc 0.5 m above it: the MIS of the scattered ray matters.
  const double d0 = 3.0, rho = 0.5, intensity = 0.35, diameter = 0.8, height = 0.5;
  const double radius = 0.5 * diameter, radiance = kPi * kPi * d0 * d0 * intensity / (kPi * radius * radius);
  const Scene lamp = floorUnder({"lamp", {0.0, 0.0, height}, Vec3f::Constant(static_cast<float>(intensity)), diameter},
                                static_cast<float>(rho));
  const double expected = rho / kPi * discIrradiance(radiance, radius, height, 0.3);
  const auto [full, fullError, fullDirect] = mean(lamp, {0.3, 0.0, 0.2}, Vec3(0, 0, -1), 1.0, 2);
  const auto [quarter, quarterError, quarterDirect] = mean(lamp, {0.3, 0.0, 0.2}, Vec3(0, 0, -1), 0.25, 2);
  EXPECT_NEAR(full, expected, 4.0 * fullError);
  EXPECT_NEAR(quarter, expected, 4.0 * quarterError);
  EXPECT_LT(quarterError, 0.01 * expected);
  // The light sample alone is below the whole: its MIS weight gives the rest to scattered rays,
  // less of it the fewer rays are scattered.
  EXPECT_LT(fullDirect, full - 4.0 * fullError);
  EXPECT_LT(fullDirect, quarterDirect);
  EXPECT_LT(quarterDirect, quarter + 4.0 * quarterError);
  // A furnace: with a quarter of the paths going on, the sum of every reflection still holds.
  Scene furnace;
  furnace.materials.push_back(lambertian(Vec3f::Constant(0.5f), Vec3f::Constant(0.25f)));
  furnace.objects.push_back({"box", 0, Box{{0.0, 0.0, 1.0}, {3.0, 2.0, 2.0}, 20.0}, ""});
  const auto [box, boxError, boxDirect] = mean(furnace, {0.2, -0.1, 1.1}, Vec3(0.3, 0.5, -0.8).normalized(), 0.25, 200);
  EXPECT_NEAR(box, 0.25 / (1.0 - 0.5), 4.0 * boxError + 1e-6);
  EXPECT_FLOAT_EQ(static_cast<float>(boxDirect), 0.25f);  // the first wall's emission, and no light sample
}

TEST(PathTracer, BackgroundIsConstantRadianceSeenAndReflected) {
  Scene s;
  s.background = {0.2f, 0.4f, 0.6f};
  s.materials.push_back(lambertian(Vec3f::Constant(0.5f)));
  s.objects.push_back({"floor", 0, Quad{{-1000, -1000, 0}, {2000, 0, 0}, {0, 2000, 0}}, ""});
  const FastRenderer renderer(s);
  const Vec3f sky = renderer.radiance({0, 0, 1}, Vec3(0.3, 0, 1).normalized(), Shading::Path, 0, 2);
  EXPECT_FLOAT_EQ(sky.z(), 0.6f);
  // An infinite floor under a uniform sky of radiance B has the radiance ρ·B.
  const Estimate floor = meanRadiance(renderer, {0, 0, 1}, Vec3(0, 0, -1), 4000, 2);
  EXPECT_NEAR(floor.mean.x(), 0.5 * 0.2, 1e-3);  // every path sees the sky on its first bounce
}

TEST(PathTracer, FramesAreBitIdenticalForAnyThreadCountAndDependOnTheSeed) {
  const Scene s = loadScene(OMNICAM_SOURCE_DIR "/scenes/tiled-room.json");
  RenderSettings settings;
  settings.rig = s.rig;
  settings.rig.mirrorRig().imageSize = 128;
  settings.spp = 16;  // tens of milliseconds: work enough for four threads to share
  settings.shading = Shading::Path;
  const ImageRGBA one = expectSameFrameOnOneAndFourThreads<FastRenderer>(s, settings);
  settings.seed = 1;
  EXPECT_FALSE(FastRenderer(s).render(s.startPose, settings).pixels == one.pixels);
  settings.denoise = true;  // the denoised frame too
  expectSameFrameOnOneAndFourThreads<FastRenderer>(s, settings);
}

// Two cameras of one robot, mounted apart, draw apart: a stereo pair's noise is not the same in
// both. Mounted a nanometre apart the two images see the same scene, so all that differs is the
// noise: independent draws leave a noise-level gap (tens of dB), shared draws next to none.
TEST(PathTracer, CamerasMountedApartOnOneRobotDrawTheirOwnNoise) {
  const Scene s = loadScene(OMNICAM_SOURCE_DIR "/scenes/tiled-room.json");
  RenderSettings settings;
  settings.rig = s.rig;
  settings.rig.mirrorRig().imageSize = 64;
  settings.spp = 4;
  settings.shading = Shading::Path;
  const FastRenderer renderer(s);
  const auto frameAt = [&](const RobotMount& mount) {
    return renderer.render(CameraPlacement(s.startPose, {}, mount), settings);
  };
  const ImageRGBA left = frameAt({0.0, 1e-9, 0.0}), right = frameAt({0.0, 2e-9, 0.0});
  const double psnr = compareImages(left, right).psnrDb;
  std::printf("two cameras 1 nm apart, path traced at 4 spp: %.1f dB apart\n", psnr);
  EXPECT_LT(psnr, 45.0);
  // The same mount twice is the same frame.
  EXPECT_EQ(frameAt({0.0, 1e-9, 0.0}).pixels, left.pixels);
}

// The mean radiance of a frame's pixels wholly inside the mirror disc (alpha 1) and its standard
// error from their spread (right for a traced frame, whose pixels are independent); and the mean of
// those farther than `window` pixels from any pixel the rim cuts.
struct DiscMeans {
  double all = 0.0, standardError = 0.0, interior = 0.0;
};
DiscMeans discMeans(const ImageRGBA& frame, int window) {
  const auto alpha = [&](int i, int j) { return frame.pixels[4 * (static_cast<size_t>(j) * frame.width + i) + 3]; };
  double squares = 0.0;
  long pixels = 0, interiorPixels = 0;
  DiscMeans m;
  for (int j = 0; j < frame.height; ++j)
    for (int i = 0; i < frame.width; ++i) {
      if (alpha(i, j) < 1.0f) continue;
      const float* px = &frame.pixels[4 * (static_cast<size_t>(j) * frame.width + i)];
      const double grey = (px[0] + px[1] + px[2]) / 3.0;
      bool nearRim = false;
      for (int y = j - window; y <= j + window && !nearRim; ++y)
        for (int x = i - window; x <= i + window && !nearRim; ++x)
          nearRim = x < 0 || y < 0 || x >= frame.width || y >= frame.height || alpha(x, y) < 1.0f;
      m.all += grey;
      squares += grey * grey;
      ++pixels;
      if (!nearRim) {
        m.interior += grey;
        ++interiorPixels;
      }
    }
  m.all /= std::max(1L, pixels);
  m.standardError = std::sqrt(std::max(0.0, squares / std::max(1L, pixels) - m.all * m.all) / std::max(1L, pixels - 1));
  m.interior /= std::max(1L, interiorPixels);
  return m;
}

// Issue #45: denoised closed furnaces read low. Every pixel of a furnace has the same expectation,
// E·(1 − ρ^(D+2))/(1 − ρ), so any weighted mean of neighbours keeps it: what would move it is the
// filter's bias. Up to issue #48 the rim's pixels lent their neighbours light too low by their
// coverage (−1.09 %, −0.65 %, −0.21 % at 64, 128, 360 px); the filter of all the light takes its
// light and its guides over the same samples, and the frame is unbiased to its noise at every
// size (docs/path-tracing.md, "The filter's bias in a closed furnace").
TEST(PathTracer, DenoisedFurnaceIsUnbiasedUpToTheRim) {
  const double albedo = 0.8, emission = 0.2;
  const int bounces = 12;
  const double expected = emission * (1.0 - std::pow(albedo, bounces + 2)) / (1.0 - albedo);
  Scene s;
  s.materials.push_back(lambertian(Vec3f::Constant(static_cast<float>(albedo)), Vec3f::Constant(static_cast<float>(emission))));
  s.objects.push_back({"box", 0, Box{{0.0, 0.0, 1.0}, {4.0, 3.0, 3.0}, 20.0}, ""});
  RenderSettings settings;
  settings.rig = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json").rig;
  settings.spp = kPathDatasetSpp;
  settings.shading = Shading::Path;
  settings.bounces = bounces;
  const RobotPose pose{0.3, -0.2, 20.0};
  const FastRenderer renderer(s);
  const int rimMargin = 5;  // px: where the old filter's bias lay
  for (int size : {64, 128, 360}) {
    settings.rig.mirrorRig().imageSize = size;
    settings.denoise = false;
    const DiscMeans traced = discMeans(renderer.render(pose, settings), rimMargin);
    settings.denoise = true;
    const DiscMeans denoised = discMeans(renderer.render(pose, settings), rimMargin);
    const auto percent = [&](double v) { return 100.0 * (v / expected - 1.0); };
    std::printf("furnace, %d px, %d spp: traced %+.3f %% ± %.3f %%, denoised %+.3f %% (%+.3f %% farther than %d px from the rim)\n",
                size, settings.spp, percent(traced.all), 100.0 * traced.standardError / expected, percent(denoised.all),
                percent(denoised.interior), rimMargin);
    const double noise = 4.0 * 100.0 * traced.standardError / expected;
    EXPECT_NEAR(percent(traced.all), 0.0, noise) << size << " px: the traced frame is unbiased";
    EXPECT_NEAR(percent(denoised.interior), 0.0, noise) << size << " px: the interior is unbiased";
    EXPECT_NEAR(percent(denoised.all), 0.0, noise) << size << " px: so is the whole disc, rim included";
  }
}

// Issue #48: the direct light is filtered too. Under a disc lamp with no bounce, every pixel's
// light is the lamp's direct light (its soft fall-off over the floor) or the lamp itself: a
// denoised 16-spp frame must keep the converged frame's mean and lose much of the traced frame's
// noise without smearing the fall-off, at every size (the filter's reach follows the frame's
// size: with 360 px's two direct levels, a 96-px frame was 4.9 % RMS from converged, worse than
// the traced 3.8 %).
struct LampFrameErrors {
  double traced = 0.0, denoised = 0.0;  // RMS from converged, relative to its mean
  double meanRatio = 0.0;               // denoised / converged
};

// Over the floor's pixels wholly inside the mirror, 3 px or more from the lamp seen directly
// (kept as traced: its edge is the grid's coverage, not noise).
LampFrameErrors lampFrameErrors(const ImageRGBA& converged, const ImageRGBA& traced, const ImageRGBA& denoised) {
  const auto grey = [](const ImageRGBA& f, size_t k) { return (f.pixels[4 * k] + f.pixels[4 * k + 1] + f.pixels[4 * k + 2]) / 3.0; };
  const int width = converged.width, height = converged.height;
  std::vector<char> nearLamp(static_cast<size_t>(width) * height, 0);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      if (grey(converged, static_cast<size_t>(j) * width + i) < 10.0) continue;  // the floor is below 3.2, the lamp 62
      for (int y = std::max(0, j - 3); y <= std::min(height - 1, j + 3); ++y)
        for (int x = std::max(0, i - 3); x <= std::min(width - 1, i + 3); ++x) nearLamp[static_cast<size_t>(y) * width + x] = 1;
    }
  double sumConverged = 0.0, sumDenoised = 0.0, squaresTraced = 0.0, squaresDenoised = 0.0;
  long pixels = 0;
  for (size_t k = 0; k < converged.pixels.size() / 4; ++k) {
    if (converged.pixels[4 * k + 3] < 1.0f || nearLamp[k]) continue;
    const double c = grey(converged, k);
    sumConverged += c;
    sumDenoised += grey(denoised, k);
    squaresTraced += (grey(traced, k) - c) * (grey(traced, k) - c);
    squaresDenoised += (grey(denoised, k) - c) * (grey(denoised, k) - c);
    ++pixels;
  }
  const double mean = sumConverged / std::max(1L, pixels);
  return {std::sqrt(squaresTraced / std::max(1L, pixels)) / mean, std::sqrt(squaresDenoised / std::max(1L, pixels)) / mean,
          sumDenoised / sumConverged};
}

TEST(PathTracer, DenoisedDirectLightUnderALampKeepsItsMeanAndLosesItsNoise) {
  const Scene s = floorUnder({"lamp", {0.0, 0.0, 1.2}, Vec3f::Constant(0.35f), 0.8}, 0.5f);
  RenderSettings settings;
  settings.rig = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json").rig;
  settings.shading = Shading::Path;
  settings.bounces = 0;
  const RobotPose pose{0.4, -0.3, 20.0};
  const FastRenderer renderer(s);
  // Measured: 96 px 3.78 % traced, 3.01 % denoised; 192 px 3.74 %, 2.12 %; 360 px 3.75 %, 1.40 %.
  const std::map<int, double> mostOfTraced{{96, 0.9}, {192, 0.65}};
  for (const auto& [size, share] : mostOfTraced) {
    settings.rig.mirrorRig().imageSize = size;
    settings.denoise = false;
    settings.spp = 1024;
    const ImageRGBA converged = renderer.render(pose, settings);
    settings.spp = 16;
    const ImageRGBA traced = renderer.render(pose, settings);
    settings.denoise = true;
    const LampFrameErrors e = lampFrameErrors(converged, traced, renderer.render(pose, settings));
    std::printf("lamp, direct light, %d px, 16 spp: traced %.3f %% RMS, denoised %.3f %% RMS, mean ratio %.5f\n", size,
                100.0 * e.traced, 100.0 * e.denoised, e.meanRatio);
    EXPECT_NEAR(e.meanRatio, 1.0, 0.003) << size << " px: the filter keeps the direct light's mean";
    EXPECT_LT(e.denoised, share * e.traced) << size << " px: and removes much of its noise";
  }
}

// Issue #48: a denoised pixel is its kept light plus its albedo times its filtered light, and a few
// samples give its surfaces' shares only roughly (2×2 samples see a line a third of a pixel wide
// 0 or 1 times, whatever the seed). A floor of albedo 0.2 under a uniform sky of radiance 0.5, no
// lamp, no bounce, with lines 2.5 cm wide: of albedo 0.9 one way, of albedo 0.5 that also emit
// 0.3 the other way (kept light). A traced sample that scatters sees the sky (or, rarely, a line's
// underside), so the light is nearly the same everywhere and the converged frame (32×32 samples
// per pixel) gives each pixel's shares of the three surfaces. Pixels whose samples disagree are
// traced again on an 8×8 grid to their first surface: the denoised 4-spp frame must come much
// closer to the converged one on the lines' pixels than the traced 4-spp frame, whose shares are
// the 2×2 grid's.
TEST(PathTracer, DenoisedPixelsTakeTheirSurfacesSharesFromAFinerGrid) {
  Scene s;
  s.background = Vec3f::Constant(0.5f);
  s.materials.push_back(lambertian(Vec3f::Constant(0.2f)));
  s.materials.push_back(lambertian(Vec3f::Constant(0.9f)));
  s.materials.push_back(lambertian(Vec3f::Constant(0.5f), Vec3f::Constant(0.3f)));
  s.objects.push_back({"floor", 0, Quad{{-100, -100, 0}, {200, 0, 0}, {0, 200, 0}}, ""});
  for (int line = -6; line <= 6; ++line) {  // 0.5 m apart, 1 mm above the floor
    const double at = 0.5 * line;
    s.objects.push_back({"line", 1, Quad{{at - 0.0125, -4.0, 0.001}, {0.025, 0, 0}, {0, 8.0, 0}}, ""});
    s.objects.push_back({"glowing line", 2, Quad{{-4.0, at - 0.0125, 0.001}, {8.0, 0, 0}, {0, 0.025, 0}}, ""});
  }
  RenderSettings settings;
  settings.rig = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json").rig;
  settings.rig.mirrorRig().imageSize = 128;
  settings.shading = Shading::Path;
  settings.bounces = 0;
  const RobotPose pose{0.1, 0.2, 10.0};
  const FastRenderer renderer(s);
  settings.spp = 1024;
  const ImageRGBA converged = renderer.render(pose, settings);
  settings.spp = 4;
  const ImageRGBA traced = renderer.render(pose, settings);
  settings.denoise = true;
  const ImageRGBA denoised = renderer.render(pose, settings);
  // The lines' pixels: wholly inside the mirror, brighter than bare floor (0.2 × 0.5 = 0.1), not
  // wholly on a glowing line (0.5 × 0.5 + 0.3 = 0.55) and not the sky (0.5).
  double squaresTraced = 0.0, squaresDenoised = 0.0;
  long pixels = 0;
  for (size_t k = 0; k < converged.pixels.size() / 4; ++k) {
    const float c = converged.pixels[4 * k];
    if (converged.pixels[4 * k + 3] < 1.0f || !(c > 0.102f && c < 0.54f) || std::abs(c - 0.5f) < 0.002f) continue;
    squaresTraced += std::pow(traced.pixels[4 * k] - c, 2);
    squaresDenoised += std::pow(denoised.pixels[4 * k] - c, 2);
    ++pixels;
  }
  const double rmsTraced = std::sqrt(squaresTraced / std::max(1L, pixels));
  const double rmsDenoised = std::sqrt(squaresDenoised / std::max(1L, pixels));
  std::printf("lines on a floor, 128 px, 4 spp: %ld pixels on lines; RMS from converged %.4f traced, %.4f denoised\n", pixels,
              rmsTraced, rmsDenoised);
  ASSERT_GT(pixels, 200) << "the lines must be seen";
  EXPECT_GT(rmsTraced, 0.02) << "the 2x2 grid's shares are far off: else the test shows nothing";
  EXPECT_LT(rmsDenoised, 0.4 * rmsTraced) << "the finer grid's shares make the output";
}

TEST(PathTracer, RandomStreamIsUniform) {
  PathRandom random(42);
  int bins[10] = {};
  double sum = 0.0;
  for (int k = 0; k < 100000; ++k) {
    const double u = random.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    ++bins[static_cast<int>(u * 10)];
    sum += u;
  }
  EXPECT_NEAR(sum / 100000, 0.5, 0.003);
  for (int b : bins) EXPECT_NEAR(b, 10000, 400);
}

}  // namespace
}  // namespace omnicam
