#include "texture_image.h"

namespace omnicam {

ImageRGBA opaqueImage(const Texture& texture, const Vec3f& tint) {
  ImageRGBA image(texture.width(), texture.height());
  const std::vector<float>& rgb = texture.rgbLinear();
  for (size_t p = 0; p < rgb.size() / 3; ++p) {
    for (int c = 0; c < 3; ++c) image.pixels[4 * p + c] = rgb[3 * p + c] * tint[c];
    image.pixels[4 * p + 3] = 1.0f;
  }
  return image;
}

}  // namespace omnicam
