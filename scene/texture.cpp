#include "texture.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "errors.h"
#include "image.h"
#include "number_format.h"

namespace omnicam {

std::shared_ptr<const Texture> Texture::load(const std::string& path) {
  const ImageRGBA image = readImage(path);
  return fromPremultiplied(image.width, image.height, image.pixels.data(), showPath(path));
}

std::shared_ptr<const Texture> Texture::fromPremultiplied(int width, int height, const float* rgba, const std::string& name) {
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
  std::vector<float> rgb(pixels * 3);
  // An albedo reflects at most what arrives: a texel above 1 (an HDR or EXR image of radiance) would
  // make a surface that gains energy, which the engines would each treat their own way. A
  // half-float or lossy texel may stray past 0 or 1 by a step of its precision (half: 2^-10 at 1),
  // and an 8-bit one by its association undone in float: noise, read as it is.
  constexpr float kNoise = 1.0f / 512.0f;
  for (size_t p = 0; p < pixels; ++p) {
    const float alpha = rgba[p * 4 + 3];
    for (int c = 0; c < 3; ++c) {  // textures are opaque albedo: undo association
      const float albedo = alpha > 0.0f ? rgba[p * 4 + c] / alpha : 0.0f;
      if (!(albedo >= -kNoise && albedo <= 1.0f + kNoise))
        throw InputError(name + ": texel (" + std::to_string(p % static_cast<size_t>(width)) + ", " +
                         std::to_string(p / static_cast<size_t>(width)) + ") is " + shortNumber(albedo) +
                         ": an albedo texture holds values from 0 to 1 (an image of radiance, HDR or EXR, is not one)");
      rgb[p * 3 + c] = albedo;
    }
  }
  return std::make_shared<Texture>(width, height, std::move(rgb));
}

namespace {

// Each value's index among the distinct values of `values` (by their bits), when there are at most
// 256; empty otherwise. One pass with a small open-addressing table: a float texture gives up at
// its 257th value.
struct Palette {
  std::vector<uint8_t> indices;
  std::vector<float> values;
};

Palette paletteOf(const std::vector<float>& values) {
  constexpr size_t kSlots = 1024;  // a power of two, four times the most entries: short probes
  uint32_t keys[kSlots];
  int16_t slots[kSlots];
  std::fill(slots, slots + kSlots, int16_t{-1});
  Palette palette;
  palette.indices.resize(values.size());
  for (size_t k = 0; k < values.size(); ++k) {
    const uint32_t bits = std::bit_cast<uint32_t>(values[k]);
    size_t slot = (bits * 0x9e3779b1u) >> 22;  // the top 10 bits of a Fibonacci hash
    while (slots[slot] >= 0 && keys[slot] != bits) slot = (slot + 1) & (kSlots - 1);
    if (slots[slot] < 0) {
      if (palette.values.size() == 256) return {};
      keys[slot] = bits;
      slots[slot] = static_cast<int16_t>(palette.values.size());
      palette.values.push_back(values[k]);
    }
    palette.indices[k] = static_cast<uint8_t>(slots[slot]);
  }
  return palette;
}

}  // namespace

Texture::Texture(int width, int height, std::vector<float> rgbLinear)
    : width_(width), height_(height), rgb_(std::move(rgbLinear)) {
  Palette palette = paletteOf(rgb_);
  indices_ = std::move(palette.indices);
  palette_ = std::move(palette.values);
}

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
    const size_t first = (static_cast<size_t>(row) * width_ + column) * 3;
    if (!palette_.empty())
      return Vec3f(palette_[indices_[first]], palette_[indices_[first + 1]], palette_[indices_[first + 2]]);
    const float* p = &rgb_[first];
    return Vec3f(p[0], p[1], p[2]);
  };
  const Vec3f top = (1.0f - fx) * at(left, above) + fx * at(right, above);
  const Vec3f bottom = (1.0f - fx) * at(left, below) + fx * at(right, below);
  return (1.0f - fy) * top + fy * bottom;
}

}  // namespace omnicam
