#include "film.h"

#include <stdexcept>

namespace omnicam {

Film::Film(int width, int height, int samplesPerAxis, bool wantsAovs)
    : width_(width), height_(height), n_(samplesPerAxis) {
  if (wantsAovs) {
    aovs.emplace();
    aovs->width = width;
    aovs->height = height;
  }
}

void Film::allocate() {
  if (image.width == width_ && image.height == height_ && image.pixels.size() == static_cast<size_t>(width_) * height_ * 4)
    return;
  image = ImageRGBA(width_, height_);
}

int Film::imagedGridPoints(const Camera& camera, int i, int j) const {
  int inside = 0;
  for (int b = 0; b < n_; ++b)
    for (int a = 0; a < n_; ++a) inside += camera.images(sample(i, j, a, b));
  return inside;
}

void Film::setRimAlpha(const Camera& camera) {
  if (image.width != width_ || image.height != height_) throw std::invalid_argument("Film::setRimAlpha: the image is not the film's size");
  for (int j = 0; j < height(); ++j)
    for (int i = 0; i < width(); ++i) image.at(i, j)[3] = alpha(imagedGridPoints(camera, i, j));
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
                                  const std::function<bool(int, int, int, int, int)>& taken,
                                  std::vector<float>& sums) const {
  requireSupersampled(large, width_, height_, n_);
  sums.resize(static_cast<size_t>(width_) * height_ * 3, 0.0f);
  for (int j = 0; j < height_; ++j)
    for (int i = 0; i < width_; ++i) {
      float* sum = &sums[(static_cast<size_t>(j) * width_ + i) * 3];
      for (int pass = 0; pass < passes; ++pass)
        for (int b = 0; b < n_; ++b)
          for (int a = 0; a < n_; ++a)
            if (taken(i, j, a, b, pass))
              for (int c = 0; c < 3; ++c) sum[c] += large.at(i * n_ + a, j * n_ + b)[c];
    }
}

void Film::reduceSupersampled(const ImageRGBA& large, const Camera& camera) {
  requireSupersampled(large, width_, height_, n_);
  allocate();
  const float w = weight();
  for (int j = 0; j < height(); ++j)
    for (int i = 0; i < width(); ++i) {
      float sum[3] = {0, 0, 0};
      for (int b = 0; b < n_; ++b)
        for (int a = 0; a < n_; ++a) {
          const float* px = large.at(i * n_ + a, j * n_ + b);
          for (int c = 0; c < 3; ++c) sum[c] += px[c];
        }
      setPixel(i, j, sum, w, imagedGridPoints(camera, i, j));
    }
}

Film filmFor(const RenderSettings& settings, bool wantsAovs) {
  checkRenderSettings(settings);
  return Film(settings.rig.imageWidth(), settings.rig.imageHeight(), *samplesPerAxis(settings.spp), wantsAovs);
}

}  // namespace omnicam
