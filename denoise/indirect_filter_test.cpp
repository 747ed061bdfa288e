// The indirect-light filter on synthetic passes with known answers: what it must keep exactly
// (direct light, textures, straddling pixels, pixels without a surface), what it must not mix
// (surfaces facing elsewhere or at another depth), and how much white noise it removes.
#include "indirect_filter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "errors.h"

namespace omnicam {
namespace {

constexpr int kSize = 48;

// A plane facing +z at depth 2 with a checker albedo, lit directly by a ramp and indirectly by
// `indirect(i, j)` (irradiance, before the albedo).
template <typename Indirect>
IndirectFilterInputs plane(Indirect indirect) {
  IndirectFilterInputs in;
  in.full = ImageRGBA(kSize, kSize);
  in.direct = ImageRGBA(kSize, kSize);
  in.albedo.assign(3 * kSize * kSize, 0.0f);
  in.normal.assign(3 * kSize * kSize, 0.0f);
  in.depth.assign(kSize * kSize, 2.0f);
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      const size_t k = static_cast<size_t>(j) * kSize + i;
      const float checker = ((i / 3 + j / 3) % 2) ? 0.8f : 0.2f;
      in.normal[3 * k + 2] = 1.0f;
      for (size_t c = 0; c < 3; ++c) {
        const float albedo = checker * (0.5f + 0.25f * static_cast<float>(c));
        in.albedo[3 * k + c] = albedo;
        const float direct = albedo * (0.3f + 0.01f * static_cast<float>(i));
        in.direct.pixels[4 * k + c] = direct;
        in.full.pixels[4 * k + c] = direct + albedo * static_cast<float>(indirect(i, j, c));
      }
      in.full.pixels[4 * k + 3] = in.direct.pixels[4 * k + 3] = 1.0f;
    }
  return in;
}

float maxDifference(const ImageRGBA& a, const ImageRGBA& b) {
  float worst = 0.0f;
  for (size_t k = 0; k < a.pixels.size(); ++k) worst = std::max(worst, std::abs(a.pixels[k] - b.pixels[k]));
  return worst;
}

TEST(IndirectFilter, SmoothIndirectLightOnATexturedPlaneIsKeptAndTheTextureStays) {
  // Constant and linear irradiance: a symmetric window reproduces them wherever it is whole, and a
  // constant everywhere; the checker albedo multiplies back exactly.
  const IndirectFilterInputs constant = plane([](int, int, size_t c) { return 0.1 + 0.05 * c; });
  EXPECT_LT(maxDifference(filterIndirectLight(constant), constant.full), 1e-6f);
  const IndirectFilterInputs ramp = plane([](int i, int j, size_t) { return 0.05 + 0.004 * i + 0.002 * j; });
  const ImageRGBA out = filterIndirectLight(ramp);
  const int r = IndirectFilterParameters{}.radius;
  for (int j = r; j < kSize - r; ++j)
    for (int i = r; i < kSize - r; ++i)
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(out.at(i, j)[c], ramp.full.at(i, j)[c], 1e-6f) << i << "," << j;
}

TEST(IndirectFilter, WithoutIndirectLightTheFrameIsTheDirectLight) {
  const IndirectFilterInputs none = plane([](int, int, size_t) { return 0.0; });
  EXPECT_EQ(filterIndirectLight(none).pixels, none.direct.pixels);
}

TEST(IndirectFilter, WhiteNoiseShrinksByTheWindowsEffectiveSize) {
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<double> field(3 * kSize * kSize);
  for (double& v : field) v = noise(random);
  const IndirectFilterInputs noisy = plane([&](int i, int j, size_t c) { return 0.2 + field[3 * (j * kSize + i) + c]; });
  const ImageRGBA out = filterIndirectLight(noisy);
  // Interior pixels: the filtered irradiance's variance is σ² Σw² / (Σw)² (weights all spatial here).
  const IndirectFilterParameters p;
  double sum = 0.0, sumSquares = 0.0;
  for (int dy = -p.radius; dy <= p.radius; ++dy)
    for (int dx = -p.radius; dx <= p.radius; ++dx) {
      const double w = std::exp(-(dx * dx + dy * dy) / (2.0 * p.spatialSigmaPx * p.spatialSigmaPx));
      sum += w;
      sumSquares += w * w;
    }
  const double expectedSigma = 0.05 * std::sqrt(sumSquares) / sum;  // 0.05 / 10.4 for radius 5, σ 3
  double error = 0.0;
  long n = 0;
  for (int j = p.radius; j < kSize - p.radius; ++j)
    for (int i = p.radius; i < kSize - p.radius; ++i)
      for (size_t c = 0; c < 3; ++c) {
        const size_t k = static_cast<size_t>(j) * kSize + i;
        const double irradiance = (out.pixels[4 * k + c] - noisy.direct.pixels[4 * k + c]) / noisy.albedo[3 * k + c];
        error += (irradiance - 0.2) * (irradiance - 0.2);
        ++n;
      }
  const double sigma = std::sqrt(error / n);
  EXPECT_NEAR(sigma, expectedSigma, 0.2 * expectedSigma) << "expected σ " << expectedSigma;
  EXPECT_LT(sigma, 0.05 / 8.0);
}

// The mean and standard deviation of the filtered irradiance over columns [from, to) of the rows
// at least `margin` from the top and bottom.
std::pair<double, double> irradianceStats(const ImageRGBA& out, const IndirectFilterInputs& in, int from, int to, int margin) {
  double sum = 0.0, squares = 0.0;
  long n = 0;
  for (int j = margin; j < kSize - margin; ++j)
    for (int i = from; i < to; ++i) {
      const size_t k = static_cast<size_t>(j) * kSize + i;
      const double e = (out.pixels[4 * k] - in.direct.pixels[4 * k]) / in.albedo[3 * k];
      sum += e;
      squares += e * e;
      ++n;
    }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, squares / n - mean * mean))};
}

TEST(IndirectFilter, SurfacesFacingElsewhereOrFartherAwayAreNotMixedIn) {
  // Left half: the plane, noisy indirect light around 0.1; right half: a wall facing +x, then (second
  // case) a surface facing the same way 3x farther, with indirect light 0.6. The left half's noise
  // shrinks, and nothing of the right half arrives: the left column next to it stays at 0.1.
  std::mt19937 random(11);
  std::uniform_real_distribution<double> noise(-0.05, 0.05);
  std::vector<double> field(kSize * kSize);
  for (double& v : field) v = noise(random);
  const auto indirect = [&](int i, int j, size_t) { return i < kSize / 2 ? 0.1 + field[j * kSize + i] : 0.6; };
  const int r = IndirectFilterParameters{}.radius;
  for (int facingOrFarther = 0; facingOrFarther < 2; ++facingOrFarther) {
    IndirectFilterInputs in = plane(indirect);
    for (int j = 0; j < kSize; ++j)
      for (int i = kSize / 2; i < kSize; ++i) {
        const size_t k = static_cast<size_t>(j) * kSize + i;
        if (facingOrFarther == 0) {
          in.normal[3 * k] = 1.0f;
          in.normal[3 * k + 2] = 0.0f;
        } else {
          in.depth[k] = 6.0f;  // exp(-|6 - 2| / (0.05 · 2)) = e^-40
        }
      }
    const ImageRGBA out = filterIndirectLight(in);
    const auto [tracedMean, tracedSigma] = irradianceStats(in.full, in, r, kSize / 2, r);
    const auto [besideMean, besideSigma] = irradianceStats(out, in, kSize / 2 - 1, kSize / 2, r);
    const auto [innerMean, innerSigma] = irradianceStats(out, in, r, kSize / 2 - r, r);
    EXPECT_NEAR(tracedSigma, 0.1 / std::sqrt(12.0), 0.005) << facingOrFarther;  // uniform noise as made
    EXPECT_NEAR(besideMean, 0.1, 0.01) << facingOrFarther;  // 0.6 leaking in by 1 % would show as 0.105
    EXPECT_NEAR(innerMean, 0.1, 0.005) << facingOrFarther;
    EXPECT_LT(innerSigma, tracedSigma / 5.0) << facingOrFarther;
    EXPECT_LT(besideSigma, tracedSigma / 3.0) << facingOrFarther;  // half a window: still averaged
  }
}

TEST(IndirectFilter, StraddlingPixelsAndPixelsWithoutASurfaceKeepTheirTracedValue) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> noise(0.0, 0.4);
  IndirectFilterInputs in = plane([&](int, int, size_t) { return noise(random); });
  const size_t crease = static_cast<size_t>(10) * kSize + 10, rim = static_cast<size_t>(20) * kSize + 30;
  in.normal[3 * crease] = 0.5f;  // the mean of two unit normals: |n| = 0.87
  in.normal[3 * crease + 2] = 0.7f;
  for (size_t c = 0; c < 3; ++c) in.albedo[3 * rim + c] = 0.0f;  // the rim mask, a lamp
  const ImageRGBA out = filterIndirectLight(in);
  for (size_t c = 0; c < 4; ++c) {
    EXPECT_EQ(out.pixels[4 * crease + c], in.full.pixels[4 * crease + c]);
    EXPECT_EQ(out.pixels[4 * rim + c], in.full.pixels[4 * rim + c]);
  }
  // ... and neither is used by its neighbours: a huge value there changes nothing next door, nor
  // does a NaN in any pass.
  IndirectFilterInputs loud = in;
  for (size_t c = 0; c < 3; ++c) loud.full.pixels[4 * crease + c] = loud.full.pixels[4 * rim + c] = 1e6f;
  const size_t broken = static_cast<size_t>(30) * kSize + 30;
  loud.normal[3 * broken] = std::nanf("");
  const ImageRGBA louder = filterIndirectLight(loud);
  EXPECT_EQ(louder.at(11, 10)[0], out.at(11, 10)[0]);
  EXPECT_EQ(louder.at(31, 20)[0], out.at(31, 20)[0]);
  EXPECT_TRUE(std::isfinite(louder.at(31, 30)[0]));
  EXPECT_EQ(louder.at(30, 30)[0], loud.full.at(30, 30)[0]);
}

// filterStraddling (the fast renderer's path frames used it until #48's filter of all the light):
// a crease pixel takes its neighbours' light,
// whatever their normals, and still lends none of its own.
TEST(IndirectFilter, StraddlingPixelsCanBeFilteredFromTheirNeighboursAlone) {
  IndirectFilterInputs in = plane([](int i, int j, size_t) { return (i + j) % 2 ? 0.3 : 0.1; });  // mean 0.2
  const size_t crease = static_cast<size_t>(20) * kSize + 20;
  in.normal[3 * crease] = 0.5f;  // |n| = 0.87
  in.normal[3 * crease + 2] = 0.7f;
  IndirectFilterParameters parameters;
  parameters.filterStraddling = true;
  const ImageRGBA out = filterIndirectLight(in, parameters);
  for (size_t c = 0; c < 3; ++c) {
    const float albedo = in.albedo[3 * crease + c];
    const float filteredIndirect = (out.pixels[4 * crease + c] - in.direct.pixels[4 * crease + c]) / albedo;
    EXPECT_NEAR(filteredIndirect, 0.2f, 0.02f) << "channel " << c;  // traced: 0.3 or 0.1
  }
  IndirectFilterInputs loud = in;
  for (size_t c = 0; c < 3; ++c) loud.full.pixels[4 * crease + c] = 1e6f;
  EXPECT_EQ(filterIndirectLight(loud, parameters).at(21, 20)[0], out.at(21, 20)[0]);
}

TEST(IndirectFilter, ABlackChannelLendsNothingToItsNeighbours) {
  // A yellow patch (no blue albedo) on the plane: its blue channel has no irradiance to tell, so the
  // blue irradiance next to it stays what it is (0.3), not pulled towards 0.
  IndirectFilterInputs in = plane([](int, int, size_t) { return 0.3; });
  for (int j = 20; j < 28; ++j)
    for (int i = 20; i < 28; ++i) {
      const size_t k = static_cast<size_t>(j) * kSize + i;
      in.albedo[3 * k + 2] = 0.0f;
      in.direct.pixels[4 * k + 2] = in.full.pixels[4 * k + 2] = 0.0f;
    }
  const ImageRGBA out = filterIndirectLight(in);
  const size_t beside = static_cast<size_t>(24) * kSize + 28;
  EXPECT_NEAR((out.pixels[4 * beside + 2] - in.direct.pixels[4 * beside + 2]) / in.albedo[3 * beside + 2], 0.3, 1e-6);
  EXPECT_EQ(out.at(24, 24)[2], 0.0f);
}

TEST(IndirectFilter, MismatchedPassesAndBadParametersAreRefused) {
  IndirectFilterInputs in = plane([](int, int, size_t) { return 0.1; });
  in.depth.pop_back();
  EXPECT_THROW(filterIndirectLight(in), InputError);
  in = plane([](int, int, size_t) { return 0.1; });
  IndirectFilterParameters p;
  p.spatialSigmaPx = 0.0;
  EXPECT_THROW(filterIndirectLight(in, p), InputError);
}

}  // namespace
}  // namespace omnicam
