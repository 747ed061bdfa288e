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

  int width() const { return width_; }
  int height() const { return height_; }
  int samplesPerAxis() const { return n_; }

  // The raster point of sample (a, b) of pixel (i, j): the one definition of the sample grid.
  static Vec2 sample(int i, int j, int a, int b, int n) { return {i + (a + 0.5) / n, j + (b + 0.5) / n}; }
  Vec2 sample(int i, int j, int a, int b) const { return sample(i, j, a, b, n_); }

  // What one sample weighs in its pixel's mean, for a frame of `passes` time passes.
  float weight(int passes = 1) const { return 1.0f / static_cast<float>(n_ * n_ * passes); }

  // --- The colour, accumulated as pbrt's Film::AddSample and Mitsuba's ImageBlock::put do ---
  // Starts a frame: the colour's sums are zero (allocated at the film's size unless they are
  // already there: a film reused from frame to frame).
  void begin();
  // Adds radiance to pixel (i, j)'s sum: one sample's, or the sum of several (an engine that sums
  // a pixel's samples in a register hands them over at once). Threads may add to different pixels
  // at once, never to the same one.
  void addSamples(int i, int j, const float radiance[3]) {
    float* px = image_.at(i, j);
    for (int c = 0; c < 3; ++c) px[c] += radiance[c];
  }
  // Pixel (i, j)'s alpha: the fraction of its n×n grid points the camera images.
  void setImagedGridPoints(int i, int j, int imagedGridPoints) { image_.at(i, j)[3] = alpha(imagedGridPoints); }
  // Every pixel's alpha from `camera` (an engine whose own samples do not follow the grid).
  void setRimAlpha(const Camera& camera);
  // Ends a frame of `passes` time passes: each pixel's colour becomes the mean of its n²·passes
  // samples (samples beyond the rim count as black, so the rim's pixels blend to black).
  void resolve(int passes = 1);
  // Adds to each pixel the samples of `large` (n× the film's size) that `taken` picks: pass after
  // pass, sample (a, b) in grid order once for each pass it is taken in. Frames rendered in
  // several parts (a moving frame's instants) are summed so, then resolved.
  void accumulateSupersampled(const ImageRGBA& large, int passes,
                              const std::function<bool(int i, int j, int a, int b, int pass)>& taken);
  // A whole frame from an image rendered at n× the film's size, one sample per grid point, and the
  // rim alpha from `camera`: begin, accumulate, alpha, resolve.
  void reduceSupersampled(const ImageRGBA& large, const Camera& camera);
  // A colour an engine finished itself (Cycles samples in its own pattern, a batch rendered ahead,
  // a denoised or recorded frame): std::invalid_argument unless it is the film's size.
  void setResolvedColour(ImageRGBA&& colour);

  const ImageRGBA& image() const { return image_; }
  // The colour, moved out (the film is empty after).
  ImageRGBA takeImage() { return std::move(image_); }

  // --- The ground truth (AOVs) at each pixel centre, point-sampled (aov_frame.h) ---
  bool wantsAovs() const { return aovs_.has_value(); }
  const AovFrame* aovs() const { return aovs_ ? &*aovs_ : nullptr; }
  // Planes to write this film's AOVs into, their memory reused (a dataset's frames); the film
  // must want AOVs.
  void reuseAovPlanes(AovFrame&& planes);
  AovFrame takeAovs();
  // Sizes the AOV planes for a frame. Every pixel is then written, by recordAov or recordNoHit,
  // so a reused frame costs no clearing.
  void beginAovs();
  void recordAov(size_t pixel, float depth, uint16_t instance, const Vec3& normal) {
    aovs_->depth[pixel] = depth;
    aovs_->instance[pixel] = instance;
    for (int c = 0; c < 3; ++c) aovs_->normal[3 * pixel + c] = static_cast<float>(normal[c]);
  }
  void recordNoHit(size_t pixel) {
    aovs_->depth[pixel] = 0.0f;
    aovs_->instance[pixel] = 0;
    for (int c = 0; c < 3; ++c) aovs_->normal[3 * pixel + c] = 0.0f;
  }

  // How many of pixel (i, j)'s grid points `camera` images.
  int imagedGridPoints(const Camera& camera, int i, int j) const;
  // std::invalid_argument naming `who` unless this is the film `settings` render into (its size
  // and grid): every engine checks before it writes a pixel.
  void requireFits(const RenderSettings& settings, const char* who) const;

 private:
  float alpha(int imagedGridPoints) const { return static_cast<float>(imagedGridPoints) / static_cast<float>(n_ * n_); }
  int width_, height_, n_;
  ImageRGBA image_;
  std::optional<AovFrame> aovs_;
};

// The film a request renders into: rig.imageWidth() × rig.imageHeight(), samplesPerAxis(spp) per axis.
// InputError (checkRenderSettings) for settings out of range.
Film filmFor(const RenderSettings& settings, bool wantsAovs = false);

}  // namespace omnicam
