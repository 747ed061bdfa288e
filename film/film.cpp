#include "film.h"

#include <algorithm>
#include <stdexcept>

namespace omnicam {

Film::Film(int width, int height, int samplesPerAxis, bool wantsAovs)
    : width_(width), height_(height), n_(samplesPerAxis) {
  if (wantsAovs) {
    aovs_.emplace();
    aovs_->width = width;
    aovs_->height = height;
  }
}

void Film::begin() {
  if (image_.width == width_ && image_.height == height_ && image_.pixels.size() == static_cast<size_t>(width_) * height_ * 4)
    std::fill(image_.pixels.begin(), image_.pixels.end(), 0.0f);
  else
    image_ = ImageRGBA(width_, height_);
}

void Film::resolve(int passes) {
  const float w = weight(passes);
  for (size_t p = 0; p < image_.pixels.size(); p += 4)
    for (int c = 0; c < 3; ++c) image_.pixels[p + c] *= w;
}

int Film::imagedGridPoints(const Camera& camera, int i, int j) const {
  int inside = 0;
  for (int b = 0; b < n_; ++b)
    for (int a = 0; a < n_; ++a) inside += camera.images(sample(i, j, a, b));
  return inside;
}

void Film::setRimAlpha(const Camera& camera) {
  if (image_.width != width_ || image_.height != height_) throw std::invalid_argument("Film::setRimAlpha: the image is not the film's size");
  for (int j = 0; j < height(); ++j)
    for (int i = 0; i < width(); ++i) setImagedGridPoints(i, j, imagedGridPoints(camera, i, j));
}

void Film::setResolvedColour(ImageRGBA&& colour) {
  if (colour.width != width_ || colour.height != height_) throw std::invalid_argument("Film: a finished colour must be the film's size");
  image_ = std::move(colour);
}

void Film::reuseAovPlanes(AovFrame&& planes) {
  if (!aovs_) throw std::invalid_argument("Film: AOV planes handed to a film without AOVs");
  aovs_ = std::move(planes);
}

AovFrame Film::takeAovs() {
  if (!aovs_) throw std::invalid_argument("Film: no AOVs to take");
  return std::move(*aovs_);
}

void Film::beginAovs() {
  aovs_->width = width_, aovs_->height = height_;
  const size_t pixels = static_cast<size_t>(width_) * height_;
  aovs_->depth.resize(pixels);
  aovs_->instance.resize(pixels);
  aovs_->normal.resize(3 * pixels);
}

void Film::requireFits(const RenderSettings& settings, const char* who) const {
  const auto n = omnicam::samplesPerAxis(settings.spp);
  if (width_ != settings.rig.imageWidth() || height_ != settings.rig.imageHeight() || !n || *n != n_)
    throw std::invalid_argument(std::string(who) + ": the film does not match the settings");
}

namespace {

void requireSupersampled(const ImageRGBA& large, int width, int height, int n) {
  if (large.width != width * n || large.height != height * n)
    throw std::invalid_argument("Film: a supersampled frame must be n times the film's size");
}

}  // namespace

void Film::accumulateSupersampled(const ImageRGBA& large, int passes,
                                  const std::function<bool(int, int, int, int, int)>& taken) {
  requireSupersampled(large, width_, height_, n_);
  for (int j = 0; j < height_; ++j)
    for (int i = 0; i < width_; ++i) {
      float* sum = image_.at(i, j);
      for (int pass = 0; pass < passes; ++pass)
        for (int b = 0; b < n_; ++b)
          for (int a = 0; a < n_; ++a)
            if (taken(i, j, a, b, pass))
              for (int c = 0; c < 3; ++c) sum[c] += large.at(i * n_ + a, j * n_ + b)[c];
    }
}

void Film::reduceSupersampled(const ImageRGBA& large, const Camera& camera) {
  requireSupersampled(large, width_, height_, n_);
  begin();
  for (int j = 0; j < height(); ++j)
    for (int i = 0; i < width(); ++i) {
      float sum[3] = {0, 0, 0};
      for (int b = 0; b < n_; ++b)
        for (int a = 0; a < n_; ++a) {
          const float* px = large.at(i * n_ + a, j * n_ + b);
          for (int c = 0; c < 3; ++c) sum[c] += px[c];
        }
      addSamples(i, j, sum);
      setImagedGridPoints(i, j, imagedGridPoints(camera, i, j));
    }
  resolve();
}

Film filmFor(const RenderSettings& settings, bool wantsAovs) {
  checkRenderSettings(settings);
  return Film(settings.rig.imageWidth(), settings.rig.imageHeight(), *samplesPerAxis(settings.spp), wantsAovs);
}

}  // namespace omnicam
