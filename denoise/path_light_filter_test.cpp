// The path-light filter on synthetic passes with known answers: what it must reproduce exactly
// (constant and linear light, the texture, the light kept as traced, pixels and channels without
// a surface), what it must not mix (surfaces facing elsewhere or at another depth, pixels
// straddling a crease), which borders it keeps (a shadow the noise cannot explain) and how much
// white noise of a known (or unknown) variance it removes.
#include "path_light_filter.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "errors.h"

namespace omnicam {
namespace {

constexpr int kSize = 96;

size_t at(int i, int j) { return static_cast<size_t>(j) * kSize + i; }

// A plane facing +z at depth 2 with a checker albedo; its direct and indirect irradiance (before
// the albedo) per pixel and channel, with the variances the renderer would report; a little
// light kept as traced (an emitting surface).
template <typename Direct, typename Indirect>
PathLightInputs plane(Direct direct, Indirect indirect, float directVariance = 0.0f, float indirectVariance = 0.0f) {
  PathLightInputs in;
  in.width = in.height = kSize;
  const size_t pixels = static_cast<size_t>(kSize) * kSize;
  for (std::vector<float>* p : {&in.full, &in.kept, &in.direct, &in.indirect, &in.albedo, &in.normal}) p->assign(3 * pixels, 0.0f);
  in.depth.assign(pixels, 2.0f);
  in.directVariance.assign(pixels, directVariance);
  in.indirectVariance.assign(pixels, indirectVariance);
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      const size_t k = at(i, j);
      const float checker = ((i / 3 + j / 3) % 2) ? 0.8f : 0.2f;
      in.normal[3 * k + 2] = 1.0f;
      for (int c = 0; c < 3; ++c) {
        const float albedo = checker * (0.5f + 0.25f * static_cast<float>(c));
        in.albedo[3 * k + c] = albedo;
        in.kept[3 * k + c] = 0.01f * static_cast<float>(c);
        in.direct[3 * k + c] = albedo * static_cast<float>(direct(i, j, c));
        in.indirect[3 * k + c] = albedo * static_cast<float>(indirect(i, j, c));
        in.full[3 * k + c] = in.kept[3 * k + c] + in.direct[3 * k + c] + in.indirect[3 * k + c];
      }
    }
  return in;
}

// The largest difference over pixels at least `margin` from the border.
float maxDifference(const std::vector<float>& a, const std::vector<float>& b, int margin = 0) {
  float worst = 0.0f;
  for (int j = margin; j < kSize - margin; ++j)
    for (int i = margin; i < kSize - margin; ++i)
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(a[3 * at(i, j) + c] - b[3 * at(i, j) + c]));
  return worst;
}

TEST(PathLightFilter, ConstantAndLinearLightOnATexturedPlaneAreKeptWithTheTexture) {
  // Weights normalised per pixel reproduce a constant everywhere; symmetric weights reproduce a
  // ramp wherever every level's taps are inside (31 px from the border); the checker albedo and
  // the kept light come back exactly.
  const PathLightInputs constant = plane([](int, int, int c) { return 0.3 + 0.1 * c; },
                                         [](int, int, int c) { return 0.1 + 0.05 * c; }, 1e-3f, 1e-2f);
  EXPECT_LT(maxDifference(filterPathLight(constant), constant.full), 2e-6f);
  const PathLightInputs ramp = plane([](int i, int, int) { return 0.2 + 0.003 * i; },
                                     [](int i, int j, int) { return 0.05 + 0.004 * i + 0.002 * j; }, 1e-3f, 1e-2f);
  EXPECT_LT(maxDifference(filterPathLight(ramp), ramp.full, 31), 2e-5f);
}

TEST(PathLightFilter, WhiteNoiseOfTheReportedVarianceIsRemoved) {
  // Independent noise of standard deviation 0.05 in each part's irradiance, reported as such:
  // the indirect light's 5 levels and the direct light's 2 leave far less.
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<double> directNoise(static_cast<size_t>(kSize) * kSize), indirectNoise(directNoise.size());
  for (size_t k = 0; k < directNoise.size(); ++k) {
    directNoise[k] = noise(random);
    indirectNoise[k] = noise(random);
  }
  const auto direct = [&](int i, int j, int) { return 0.5 + directNoise[at(i, j)]; };
  const auto indirect = [&](int i, int j, int) { return 0.2 + indirectNoise[at(i, j)]; };
  const float variance = 0.05f * 0.05f;
  const PathLightInputs noisy = plane(direct, indirect, variance, variance);
  const PathLightInputs clean = plane([](int, int, int) { return 0.5; }, [](int, int, int) { return 0.2; });
  PathLightFilterParameters directOnly, indirectOnly;
  directOnly.indirect.levels = 0;
  indirectOnly.direct.levels = 0;
  const auto rms = [&](const std::vector<float>& out, const std::vector<float>& truth) {
    double sum = 0.0;
    size_t count = 0;
    for (int j = 31; j < kSize - 31; ++j)
      for (int i = 31; i < kSize - 31; ++i, ++count) {
        const double albedo = noisy.albedo[3 * at(i, j) + 1];
        const double d = (out[3 * at(i, j) + 1] - truth[3 * at(i, j) + 1]) / albedo;  // green, in irradiance
        sum += d * d;
      }
    return std::sqrt(sum / count);
  };
  // Unfiltered, each part alone leaves 0.05; its filter reduces it.
  EXPECT_LT(rms(filterPathLight(noisy, indirectOnly), clean.full), 0.05 * std::sqrt(1.0 + 1.0 / 25.0));
  const double direct2 = rms(filterPathLight(noisy, directOnly), clean.full);
  const double both = rms(filterPathLight(noisy), clean.full);
  EXPECT_LT(direct2, 0.05 * std::sqrt(1.0 + 1.0 / 4.0)) << "the direct light's filter alone";
  EXPECT_LT(both, 0.025) << "both parts filtered";
}

TEST(PathLightFilter, PixelsOfOneSampleTakeTheirNoiseFromTheirNeighbours) {
  // The same noise reported as unknown (−1: one sample per pixel): each pixel's variance comes
  // from its 3×3 neighbours' spread, and the filter still removes most of the noise.
  std::mt19937 random(11);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<double> values(static_cast<size_t>(kSize) * kSize);
  for (double& v : values) v = noise(random);
  const PathLightInputs noisy =
      plane([&](int i, int j, int) { return 0.5 + values[at(i, j)]; }, [&](int i, int j, int) { return 0.2 + values[at(j, i)]; }, -1.0f, -1.0f);
  const PathLightInputs clean = plane([](int, int, int) { return 0.5; }, [](int, int, int) { return 0.2; });
  const std::vector<float> out = filterPathLight(noisy);
  double sum = 0.0;
  size_t count = 0;
  for (int j = 31; j < kSize - 31; ++j)
    for (int i = 31; i < kSize - 31; ++i, ++count) {
      const double d = (out[3 * at(i, j) + 1] - clean.full[3 * at(i, j) + 1]) / noisy.albedo[3 * at(i, j) + 1];
      sum += d * d;
    }
  EXPECT_LT(std::sqrt(sum / count), 0.025) << "unfiltered: 0.05 * sqrt(2)";
}

TEST(PathLightFilter, AShadowBorderTheNoiseCannotExplainIsKeptOneItCanIsSmoothed) {
  // Direct light 1.0 left of column 48 and 0.1 right of it: with the small variance of a
  // converged render, the border is kept sharp; reported as noisy as the step, it is smoothed.
  const auto shadow = [](int i, int, int) { return i < 48 ? 1.0 : 0.1; };
  const auto none = [](int, int, int) { return 0.0; };
  PathLightFilterParameters directOnly;
  directOnly.indirect.levels = 0;
  const PathLightInputs converged = plane(shadow, none, 1e-6f, 0.0f);
  const std::vector<float> kept = filterPathLight(converged, directOnly);
  const size_t left = at(47, 40), right = at(48, 40);
  EXPECT_NEAR(kept[3 * left + 1] / converged.albedo[3 * left + 1] - 0.01f / converged.albedo[3 * left + 1], 1.0, 1e-3);
  EXPECT_NEAR(kept[3 * right + 1] / converged.albedo[3 * right + 1] - 0.01f / converged.albedo[3 * right + 1], 0.1, 1e-3);
  const PathLightInputs noisy = plane(shadow, none, 0.5f, 0.0f);
  const std::vector<float> smoothed = filterPathLight(noisy, directOnly);
  EXPECT_LT(smoothed[3 * left + 1] / noisy.albedo[3 * left + 1] - 0.01f / noisy.albedo[3 * left + 1], 0.9);
}

TEST(PathLightFilter, SurfacesFacingElsewhereDoNotMix) {
  // The right half faces +x and is lit ten times brighter; the left half's light stays its own.
  PathLightInputs in = plane([](int, int, int) { return 0.1; }, [](int i, int, int) { return i < 48 ? 0.1 : 1.0; }, 1e-3f, 1.0f);
  for (int j = 0; j < kSize; ++j)
    for (int i = 48; i < kSize; ++i) {
      in.normal[3 * at(i, j) + 0] = 1.0f;
      in.normal[3 * at(i, j) + 2] = 0.0f;
    }
  const std::vector<float> out = filterPathLight(in);
  for (int i = 0; i < 48; ++i) EXPECT_NEAR(out[3 * at(i, 50) + 1], in.full[3 * at(i, 50) + 1], 1e-5f) << "column " << i;
}

TEST(PathLightFilter, SurfacesAtAnotherDepthDoNotMix) {
  // Both halves face +z; the right half lies twice as far (a step the depth's gradient, zero on
  // each half, does not explain) and is lit ten times brighter.
  PathLightInputs in = plane([](int, int, int) { return 0.1; }, [](int i, int, int) { return i < 48 ? 0.1 : 1.0; }, 1e-3f, 1.0f);
  for (int j = 0; j < kSize; ++j)
    for (int i = 48; i < kSize; ++i) in.depth[at(i, j)] = 4.0f;
  const std::vector<float> out = filterPathLight(in);
  for (int i = 0; i < 48; ++i) EXPECT_NEAR(out[3 * at(i, 50) + 1], in.full[3 * at(i, 50) + 1], 1e-5f) << "column " << i;
}

TEST(PathLightFilter, PixelsStraddlingSurfacesGatherButLendNothing) {
  // Column 48 straddles a crease (its mean normal is short) and carries ten times the light: its
  // neighbours ignore it, and it takes its neighbours' light.
  PathLightInputs in = plane([](int, int, int) { return 0.1; }, [](int i, int, int) { return i == 48 ? 1.0 : 0.1; }, 1e-3f, 1e-2f);
  for (int j = 0; j < kSize; ++j) in.normal[3 * at(48, j) + 2] = 0.8f;
  const std::vector<float> out = filterPathLight(in);
  const PathLightInputs clean = plane([](int, int, int) { return 0.1; }, [](int, int, int) { return 0.1; });
  for (int i = 40; i < 57; ++i) {
    if (i == 48) continue;
    EXPECT_NEAR(out[3 * at(i, 50) + 1], clean.full[3 * at(i, 50) + 1], 1e-5f) << "column " << i;
  }
  // It keeps a little of its own (it is in its own sum at every level): a tenth of its excess at most.
  const size_t k = at(48, 50);
  EXPECT_LT(std::abs(out[3 * k + 1] - clean.full[3 * k + 1]), 0.1f * (in.full[3 * k + 1] - clean.full[3 * k + 1]));
}

TEST(PathLightFilter, AChannelWithoutAlbedoKeepsItsLight) {
  // One pixel's green albedo is below the floor: its green light (a lamp's glow, say) is kept as
  // traced; its red and blue are filtered as their neighbours'.
  PathLightInputs in = plane([](int, int, int) { return 0.5; }, [](int, int, int) { return 0.2; }, 1e-3f, 1e-2f);
  const size_t k = at(40, 40);
  in.albedo[3 * k + 1] = 1e-4f;
  in.full[3 * k + 1] = 0.37f;
  const std::vector<float> out = filterPathLight(in);
  EXPECT_EQ(out[3 * k + 1], 0.37f);
  EXPECT_NEAR(out[3 * k + 0], in.full[3 * k + 0], 1e-5f);
}

TEST(PathLightFilter, PixelsWithoutASurfaceOrWithNaNAreKeptAndLendNothing) {
  PathLightInputs in = plane([](int, int, int) { return 0.5; }, [](int, int, int) { return 0.2; }, 1e-3f, 1e-2f);
  // A lamp seen directly (no albedo) and a pixel with a NaN, both very bright.
  const size_t lamp = at(40, 40), broken = at(44, 40);
  for (int c = 0; c < 3; ++c) {
    in.albedo[3 * lamp + c] = 0.0f;
    in.full[3 * lamp + c] = in.kept[3 * lamp + c] = 50.0f;
    in.full[3 * broken + c] = 50.0f;
    in.indirect[3 * broken + c] = std::nanf("");
  }
  const std::vector<float> out = filterPathLight(in);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(out[3 * lamp + c], 50.0f);
    EXPECT_EQ(out[3 * broken + c], 50.0f);
  }
  const PathLightInputs clean = plane([](int, int, int) { return 0.5; }, [](int, int, int) { return 0.2; });
  for (int i = 41; i < 44; ++i) EXPECT_NEAR(out[3 * at(i, 40) + 1], clean.full[3 * at(i, 40) + 1], 1e-5f);
}

// A renderer that traced a pixel's surfaces on a finer grid gives their kept light and albedo
// (coverageKept, coverageAlbedo): the output is those times the filtered light, which under a
// constant light is that light exactly, whatever the pixel's own samples' albedo was.
TEST(PathLightFilter, APixelsSurfacesFromAFinerGridMakeItsOutput) {
  PathLightInputs in = plane([](int, int, int c) { return 0.3 + 0.1 * c; }, [](int, int, int c) { return 0.1 + 0.05 * c; });
  in.coverageKept = in.kept;
  in.coverageAlbedo = in.albedo;
  const size_t refined = at(40, 50), unknown = at(41, 50);
  for (int c = 0; c < 3; ++c) {
    in.coverageKept[3 * refined + c] = 0.05f;
    in.coverageAlbedo[3 * refined + c] = 0.35f;
  }
  in.coverageAlbedo[3 * unknown + 1] = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> out = filterPathLight(in);
  for (int c = 0; c < 3; ++c) {
    const double light = (0.3 + 0.1 * c) + (0.1 + 0.05 * c);
    EXPECT_NEAR(out[3 * refined + c], 0.05 + 0.35 * light, 2e-6) << "channel " << c;
    EXPECT_EQ(out[3 * unknown + c], in.full[3 * unknown + c]) << "a pixel with a non-finite pass is kept as traced";
  }
  in.coverageAlbedo.pop_back();
  EXPECT_THROW(filterPathLight(in), InputError);
}

TEST(PathLightFilter, TheResultDoesNotDependOnTheThreadCount) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> light(static_cast<size_t>(kSize) * kSize);
  for (double& v : light) v = u(random);
  const PathLightInputs in = plane([&](int i, int j, int) { return light[at(i, j)]; },
                                   [&](int i, int j, int) { return 0.5 * light[at(j, i)]; }, 0.05f, 0.05f);
  std::vector<float> one, two;
  {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
    one = filterPathLight(in);
  }
  {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
    two = filterPathLight(in);
  }
  EXPECT_EQ(one, two);
}

TEST(PathLightFilter, PassesOfOtherSizesAndBadParametersAreInputErrors) {
  PathLightInputs in = plane([](int, int, int) { return 0.5; }, [](int, int, int) { return 0.2; });
  in.depth.pop_back();
  EXPECT_THROW(filterPathLight(in), InputError);
  const PathLightInputs good = plane([](int, int, int) { return 0.5; }, [](int, int, int) { return 0.2; });
  PathLightFilterParameters p;
  p.direct.levels = 9;
  EXPECT_THROW(filterPathLight(good, p), InputError);
  p = {};
  p.indirect.luminanceSigma = 0.0;
  EXPECT_THROW(filterPathLight(good, p), InputError);
}

}  // namespace
}  // namespace omnicam
