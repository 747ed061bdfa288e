// The environment as a light: its sampling density against quadrature, and the path tracer under
// a sky against the irradiance the sky's image gives by quadrature.
#include "environment_light.h"

#include <gtest/gtest.h>

#include <cmath>

#include "fast_renderer.h"
#include "path_tracer.h"
#include "ray_scene.h"

namespace omnicam {
namespace {

// A 64×32 sky: brighter towards the zenith, a dim ground, and a sun of 2×2 texels 500 times the
// sky, turned by 40°: what a sampler that ignores the image would estimate with a large error.
Environment testSky(double rotationDeg = 40.0) {
  const int width = 64, height = 32;
  std::vector<float> rgb(static_cast<size_t>(width) * height * 3);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const double elevation = kPi * (0.5 - (j + 0.5) / height);
      float* texel = &rgb[(static_cast<size_t>(j) * width + i) * 3];
      const float sky = elevation > 0.0 ? static_cast<float>(0.3 + 0.7 * std::sin(elevation)) : 0.05f;
      texel[0] = 0.8f * sky, texel[1] = 0.9f * sky, texel[2] = sky;
      if ((i == 20 || i == 21) && (j == 9 || j == 10)) texel[0] = texel[1] = texel[2] = 500.0f;
    }
  Environment environment;
  environment.image = std::make_shared<Texture>(width, height, std::move(rgb));
  environment.strength = 1.5f;
  environment.rotationDeg = rotationDeg;
  return environment;
}

// ∫ f(d) dω over the sphere by the midpoint rule on an (u, v) grid, dω = 2π²·cos(elevation) du dv;
// 32 × 32 points per texel of the test sky.
template <typename F>
double sphereIntegral(F f) {
  const int columns = 2048, rows = 1024;
  double sum = 0.0;
  for (int j = 0; j < rows; ++j) {
    const double v = (j + 0.5) / rows;
    const double weight = 2.0 * kPi * kPi * std::cos(kPi * (v - 0.5)) / (double(columns) * rows);
    for (int i = 0; i < columns; ++i) sum += weight * f(directionFromEquirect({(i + 0.5) / columns, v}));
  }
  return sum;
}

// The irradiance of an unoccluded surface of normal +Z under the sky, by quadrature of its image.
double irradianceFromAbove(const Environment& sky) {
  return sphereIntegral([&](const Vec3& d) { return sky.radiance(d).x() * std::max(0.0, d.z()); });
}

TEST(EnvironmentLight, ItsDensityIntegratesToOneOverTheSphere) {
  const Environment sky = testSky();
  const EnvironmentLight light(sky);
  EXPECT_NEAR(sphereIntegral([&](const Vec3& d) { return light.pdf(d); }), 1.0, 1e-6);
}

TEST(EnvironmentLight, SamplesCarryTheDensityAndRadianceOfTheirDirection) {
  const Environment sky = testSky();
  const EnvironmentLight light(sky);
  int sunSamples = 0;
  for (uint32_t k = 0; k < 4096; ++k) {
    const EnvironmentLight::Sample s = light.sample(PixelSequence(3, k).point(0));
    ASSERT_NEAR(s.direction.norm(), 1.0, 1e-12);
    EXPECT_NEAR(light.pdf(s.direction), s.pdf, 1e-6 * s.pdf) << k;
    const Vec3f expected = sky.radiance(s.direction);
    EXPECT_NEAR(s.radiance.x(), expected.x(), 1e-4 * expected.x()) << k;
    sunSamples += s.radiance.x() > 100.0f;
  }
  // The sun (4 of 2048 texels, about a third of the image's weight) draws its share.
  EXPECT_GT(sunSamples, 4096 / 5);
}

// The light's estimate of the sky's irradiance, L·cos/pdf averaged over its samples, against
// quadrature: unbiased, and with a sun in the sky still within 1.5 % from 4096 samples (measured
// 1.1 %; directions drawn uniformly over the sphere would leave about 10 %).
TEST(EnvironmentLight, ItsSamplesEstimateTheIrradianceWithoutBias) {
  for (const double rotation : {0.0, 40.0, -135.0}) {
    const Environment sky = testSky(rotation);
    const EnvironmentLight light(sky);
    const double expected = irradianceFromAbove(sky);
    const int n = 4096;
    double sum = 0.0, squares = 0.0;
    for (uint32_t k = 0; k < n; ++k) {
      const EnvironmentLight::Sample s = light.sample(PixelSequence(11, k).point(0));
      const double value = s.direction.z() > 0.0 ? s.radiance.x() * s.direction.z() / s.pdf : 0.0;
      sum += value;
      squares += value * value;
    }
    const double mean = sum / n, standardError = std::sqrt((squares / n - mean * mean) / n);
    EXPECT_NEAR(mean, expected, 4.0 * standardError + 1e-3 * expected) << "rotation " << rotation;
    EXPECT_LT(standardError, 0.015 * expected) << "rotation " << rotation;
  }
}

TEST(EnvironmentLight, ItsIrradianceEstimateIsExactForUniformAndHemisphereSkies) {
  Environment uniform;
  uniform.image = std::make_shared<Texture>(16, 8, std::vector<float>(16 * 8 * 3, 2.0f));
  const EnvironmentLight all(uniform);
  EXPECT_NEAR(all.irradianceEstimate({0, 0, 1}), 2.0 * kPi, 1e-9);
  EXPECT_NEAR(all.irradianceEstimate(Vec3(1, 2, -3).normalized()), 2.0 * kPi, 1e-9);
  std::vector<float> upper(16 * 8 * 3, 0.0f);
  std::fill(upper.begin(), upper.begin() + 16 * 4 * 3, 2.0f);  // the rows above the horizon
  Environment hemisphere;
  hemisphere.image = std::make_shared<Texture>(16, 8, upper);
  const EnvironmentLight half(hemisphere);
  // Texel rows approximate the spherical harmonics' integrals: within a percent.
  EXPECT_NEAR(half.irradianceEstimate({0, 0, 1}), 2.0 * kPi, 0.01 * 2.0 * kPi);
  EXPECT_NEAR(half.irradianceEstimate({0, 0, -1}), 0.0, 0.01 * 2.0 * kPi);
  Environment black;
  black.image = std::make_shared<Texture>(4, 2, std::vector<float>(4 * 2 * 3, 0.0f));
  EXPECT_FALSE(EnvironmentLight(black).emits());
}

// A floor of albedo 0.6 under the test sky.
Scene floorUnderTheSky() {
  Scene scene;
  scene.environment = testSky();
  Material floor;
  floor.name = "floor";
  floor.color = Vec3f::Constant(0.6f);
  scene.materials.push_back(floor);
  scene.objects.push_back({"floor", 0, Quad{{-100, -100, 0}, {200, 0, 0}, {0, 200, 0}}, ""});
  return scene;
}

// A floor of albedo ρ under the sky: its radiance is ρ/π times the irradiance of the sky's upper
// hemisphere, which the light samples and the scattered rays that leave the scene share by MIS.
TEST(EnvironmentLight, AFloorUnderTheSkyReflectsItsIrradiance) {
  const Scene scene = floorUnderTheSky();
  const FastRenderer renderer(scene);
  const double expected = 0.6 / kPi * irradianceFromAbove(*scene.environment);
  const int paths = 8192;
  double sum = 0.0, squares = 0.0;
  for (int k = 0; k < paths; ++k) {
    const double v = renderer.radiance({0.3, 0.2, 0.5}, Vec3(0.1, 0.0, -1.0).normalized(), Shading::Path, k, 2).x();
    sum += v;
    squares += v * v;
  }
  const double mean = sum / paths, standardError = std::sqrt((squares / paths - mean * mean) / paths);
  std::printf("floor under the sky: %.5f (± %.5f), quadrature %.5f\n", mean, standardError, expected);
  EXPECT_NEAR(mean, expected, 4.0 * standardError + 1e-3 * expected);
  EXPECT_LT(standardError, 0.01 * expected);
  // A ray that leaves the scene sees the sky itself, noiseless.
  const Vec3 up = Vec3(0.2, -0.3, 0.9).normalized();
  const Vec3f seen = renderer.radiance({0.0, 0.0, 0.5}, up, Shading::Path, 1, 2);
  EXPECT_FLOAT_EQ(seen.z(), scene.environment->radiance(up).z());
}

// The same floor when only a quarter of the first surfaces scatter a ray (denoised frames): the
// light samples' MIS weights count the scattered rays' share, the scattered rays their weight.
TEST(EnvironmentLight, AFloorUnderTheSkyKeepsItsIrradianceWhenAQuarterOfTheSamplesScatter) {
  const Scene scene = floorUnderTheSky();
  const RayScene rays(scene);
  PathTracingOptions options;
  options.indirectShare = 0.25;
  const PathTracer tracer(scene, rays, options);
  const Vec3 origin(0.3, 0.2, 0.5), direction = Vec3(0.1, 0.0, -1.0).normalized();
  const std::optional<SurfaceHit> first = rays.intersect(origin, direction);
  ASSERT_TRUE(first);
  const double expected = 0.6 / kPi * irradianceFromAbove(*scene.environment);
  const int paths = 16384;
  double sum = 0.0, squares = 0.0;
  for (int k = 0; k < paths; ++k) {
    const double v = tracer.cameraRay(origin, direction, &*first, {11, static_cast<uint32_t>(k)}).radiance.x();
    sum += v;
    squares += v * v;
  }
  const double mean = sum / paths, standardError = std::sqrt((squares / paths - mean * mean) / paths);
  EXPECT_NEAR(mean, expected, 4.0 * standardError + 1e-3 * expected);
  EXPECT_LT(standardError, 0.01 * expected);
}

}  // namespace
}  // namespace omnicam
