#pragma once
// The film every engine exposes (docs/conventions.md §2): each pixel's n×n regular grid of
// samples, taken in one or more time passes, reduced to their mean; the pixel's alpha is the
// fraction of its grid that the camera images (inside the mirror's rim). Beside the colour, the
// film holds the per-pixel ground truth (AOVs) when they are wanted.
//
// Written once and used by the fast renderer, its cube-map and thesis-mesh modes, POV-Ray (a
// frame rendered at n× the size, one ray per grid point) and Blender (Cycles samples randomly
// inside the pixel; its alpha is still the rim on the grid).
#include <functional>
#include <optional>
#include <vector>

#include "aov_frame.h"
#include "camera.h"
#include "image.h"
#include "render_settings.h"

namespace omnicam {

class Film {
 public:
  // A width × height film of n×n samples per pixel; with `wantsAovs`, AOV planes too. Nothing is
  // allocated yet: an engine allocates once it has checked that the frame fits in memory
  // (memory_budget.h), so a frame too large is refused, not attempted.
  Film(int width, int height, int samplesPerAxis, bool wantsAovs = false);
  // The colour's pixels (zeros), unless they are already there at this size (a film reused).
  void allocate();

  int width() const { return width_; }
  int height() const { return height_; }
  int samplesPerAxis() const { return n_; }

  // The raster point of sample (a, b) of pixel (i, j): the one definition of the sample grid.
  static Vec2 sample(int i, int j, int a, int b, int n) { return {i + (a + 0.5) / n, j + (b + 0.5) / n}; }
  Vec2 sample(int i, int j, int a, int b) const { return sample(i, j, a, b, n_); }

  // What one pixel's samples reduce to, for a frame of `passes` time passes: the colour is the
  // sum of its n²·passes samples times weight(passes); the alpha is its imaged grid points over n².
  float weight(int passes = 1) const { return 1.0f / static_cast<float>(n_ * n_ * passes); }
  float alpha(int imagedGridPoints) const { return static_cast<float>(imagedGridPoints) / static_cast<float>(n_ * n_); }
  // Pixel (i, j) from the sum of its samples' radiance.
  // The film must be allocated.
  void setPixel(int i, int j, const float sum[3], float weight, int imagedGridPoints) {
    float* px = image.at(i, j);
    for (int c = 0; c < 3; ++c) px[c] = sum[c] * weight;
    px[3] = alpha(imagedGridPoints);
  }
  // How many of pixel (i, j)'s grid points `camera` images.
  int imagedGridPoints(const Camera& camera, int i, int j) const;
  // Every pixel's alpha from `camera` (an engine whose own samples do not follow the grid).
  void setRimAlpha(const Camera& camera);
  // The colour from a frame rendered at n× the film's size, one sample per grid point, and the
  // rim alpha from `camera`.
  void reduceSupersampled(const ImageRGBA& large, const Camera& camera);
  // Adds to `sums` (3 per pixel) the samples of `large` (n× the film's size) that `taken` picks:
  // for each pixel, pass after pass, sample (a, b) in grid order is added once for each pass it
  // is taken in. Frames rendered in several parts (a moving frame's instants) are summed so, then
  // reduced with setPixel.
  void accumulateSupersampled(const ImageRGBA& large, int passes,
                              const std::function<bool(int i, int j, int a, int b, int pass)>& taken,
                              std::vector<float>& sums) const;

  bool wantsAovs() const { return aovs.has_value(); }
  // std::invalid_argument naming `who` unless this is the film `settings` render into (its size
  // and grid): every engine checks before it writes a pixel.
  void requireFits(const RenderSettings& settings, const char* who) const;

  ImageRGBA image;
  std::optional<AovFrame> aovs;

 private:
  int width_, height_, n_;
};

// The film a request renders into: rig.imageWidth() × rig.imageHeight(), samplesPerAxis(spp) per axis.
// InputError (checkRenderSettings) for settings out of range.
Film filmFor(const RenderSettings& settings, bool wantsAovs = false);

}  // namespace omnicam
