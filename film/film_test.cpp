// The film against closed forms: its sample grid, the mean of a pixel's samples over passes, and
// the rim alpha as the fraction of the grid inside the rim's circle.
#include "film.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "make_camera.h"
#include "rig.h"

namespace omnicam {
namespace {

TEST(Film, TheSampleGridIsRegularInsideEachPixel) {
  EXPECT_EQ(Film::sample(2, 3, 0, 0, 1), Vec2(2.5, 3.5));  // one sample: the pixel centre
  EXPECT_EQ(Film::sample(2, 3, 0, 0, 2), Vec2(2.25, 3.25));
  EXPECT_EQ(Film::sample(2, 3, 1, 0, 2), Vec2(2.75, 3.25));
  EXPECT_EQ(Film::sample(2, 3, 1, 1, 2), Vec2(2.75, 3.75));
  EXPECT_EQ(Film::sample(0, 0, 3, 0, 4), Vec2(0.875, 0.125));
}

// A frame rendered at n× the size reduces to each pixel's block mean; summed over passes, to the
// mean of every sample of every pass.
TEST(Film, ASupersampledFrameReducesToTheMeanOfEachPixelsBlock) {
  const int n = 3;
  ImageRGBA large(2 * n, 2 * n);
  for (int y = 0; y < 2 * n; ++y)
    for (int x = 0; x < 2 * n; ++x) {
      float* p = large.at(x, y);
      p[0] = static_cast<float>(x), p[1] = static_cast<float>(y), p[2] = static_cast<float>(x * y), p[3] = 1.0f;
    }
  Film film(2, 2, n);
  film.begin();
  film.accumulateSupersampled(large, 1, [](int, int, int, int, int) { return true; });
  film.resolve(1);
  // Pixel (1, 0) covers x = 3…5, y = 0…2: mean x 4, mean y 1, mean x·y = 4 · 1.
  EXPECT_FLOAT_EQ(film.image().at(1, 0)[0], 4.0f);
  EXPECT_FLOAT_EQ(film.image().at(1, 0)[1], 1.0f);
  EXPECT_FLOAT_EQ(film.image().at(1, 0)[2], 4.0f);
  // Two passes, each sample taken once in each: the same mean. One pass of two taking only the
  // left column (a = 0): its mean weighted as a third of a two-pass pixel.
  film.begin();
  film.accumulateSupersampled(large, 2, [](int, int, int, int, int) { return true; });
  film.resolve(2);
  EXPECT_FLOAT_EQ(film.image().at(1, 1)[0], 4.0f);
  film.begin();
  film.accumulateSupersampled(large, 2, [](int, int, int a, int, int pass) { return pass == 0 && a == 0; });
  film.resolve(2);
  EXPECT_FLOAT_EQ(film.image().at(1, 1)[0], 3.0f * 3 / 18);  // x = 3 on 3 of the 18 samples
  // A film reused for a frame starts from zero.
  film.begin();
  film.resolve(1);
  EXPECT_EQ(film.image().at(0, 0)[0], 0.0f);
}

// Alpha is the fraction of a pixel's grid inside the mirror's rim: the rim is a circle about the
// image centre (the ideal rig's closed form), so each pixel's alpha is a count of grid points.
TEST(Film, TheRimAlphaIsTheShareOfThePixelsGridInsideTheRimCircle) {
  RigSpec rig = RigSpec{}.resized(24);
  const auto camera = makeCamera(rig);
  const CentralModel model = centralModelOf(*camera);
  ASSERT_TRUE(model.rimRadiusPx.has_value());
  const double r = *model.rimRadiusPx, cx = model.intrinsics.cx + 0.5, cy = model.intrinsics.cy + 0.5;
  const int n = 4;
  Film film(24, 24, n);
  film.begin();
  film.setRimAlpha(*camera);
  int partial = 0;
  for (int j = 0; j < 24; ++j)
    for (int i = 0; i < 24; ++i) {
      int inside = 0;
      for (int b = 0; b < n; ++b)
        for (int a = 0; a < n; ++a) {
          const Vec2 s(i + (a + 0.5) / n, j + (b + 0.5) / n);
          inside += std::hypot(s.x() - cx, s.y() - cy) < r;
        }
      EXPECT_FLOAT_EQ(film.image().at(i, j)[3], inside / 16.0f) << i << ", " << j;
      partial += inside > 0 && inside < 16;
    }
  EXPECT_GT(partial, 20);  // the rim crosses pixels: the test sees fractions, not only 0 and 1
}

TEST(Film, AColourOfAnotherSizeOrSettingsForAnotherFilmAreRefused) {
  Film film(8, 6, 2);
  EXPECT_THROW(film.setResolvedColour(ImageRGBA(6, 8)), std::invalid_argument);
  EXPECT_NO_THROW(film.setResolvedColour(ImageRGBA(8, 6)));
  RenderSettings settings;
  settings.rig = RigSpec{}.resized(8);
  settings.spp = 4;
  EXPECT_THROW(film.requireFits(settings, "test"), std::invalid_argument);  // 8 × 8, not 8 × 6
  const Film fits = filmFor(settings);
  EXPECT_NO_THROW(fits.requireFits(settings, "test"));
  EXPECT_EQ(fits.samplesPerAxis(), 2);
}

}  // namespace
}  // namespace omnicam
