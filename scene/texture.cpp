#include "texture.h"

#include <cmath>

#include "image.h"

namespace omnicam {

std::shared_ptr<const Texture> Texture::load(const std::string& path) {
  const ImageRGBA image = readImage(path);
  std::vector<float> rgb(static_cast<size_t>(image.width) * image.height * 3);
  for (size_t p = 0; p < static_cast<size_t>(image.width) * image.height; ++p) {
    const float alpha = image.pixels[p * 4 + 3];
    for (int c = 0; c < 3; ++c)  // textures are opaque albedo: undo association
      rgb[p * 3 + c] = alpha > 0.0f ? image.pixels[p * 4 + c] / alpha : 0.0f;
  }
  return std::make_shared<Texture>(image.width, image.height, std::move(rgb));
}

Texture::Texture(int width, int height, std::vector<float> rgbLinear)
    : width_(width), height_(height), rgb_(std::move(rgbLinear)) {}

Vec3f Texture::sample(double u, double v) const {
  // Repeat wrapping first, so that any finite UV (a scale of 1e6, say) stays in int range.
  if (!(std::isfinite(u) && std::isfinite(v))) u = v = 0.0;
  u -= std::floor(u);
  v -= std::floor(v);
  // Continuous texel coordinates with row 0 at the top of the image (v = 1).
  const double x = u * width_ - 0.5;
  const double y = (1.0 - v) * height_ - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const float fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
  // x ∈ [−0.5, width − 0.5): the four texels are at most one off the image, wrapped without a
  // division (texture look-ups are a tenth of a path-traced frame's time).
  const int i = static_cast<int>(x0), j = static_cast<int>(y0);
  const int left = i < 0 ? width_ - 1 : i, right = i + 1 >= width_ ? 0 : i + 1;
  const int above = j < 0 ? height_ - 1 : j, below = j + 1 >= height_ ? 0 : j + 1;
  const auto at = [this](int column, int row) {
    const float* p = &rgb_[(static_cast<size_t>(row) * width_ + column) * 3];
    return Vec3f(p[0], p[1], p[2]);
  };
  const Vec3f top = (1.0f - fx) * at(left, above) + fx * at(right, above);
  const Vec3f bottom = (1.0f - fx) * at(left, below) + fx * at(right, below);
  return (1.0f - fy) * top + fy * bottom;
}

}  // namespace omnicam
