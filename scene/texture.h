#pragma once
// Bilinear texture lookup with texel centres at +0.5 and repeat wrapping (docs/conventions.md §2, the same
// as POV-Ray's `interpolate 2`). UV (0, 0) is the image's bottom-left corner, as in POV-Ray.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geometry.h"

namespace omnicam {

class Texture {
 public:
  // An albedo texture: InputError naming the file for a texel outside [0, 1] (or unreadable).
  static std::shared_ptr<const Texture> load(const std::string& path);
  // The same from premultiplied RGBA (width × height × 4 floats, an image as decoded), `name`
  // naming it in the InputError: every albedo texture, a file's or a glTF's, is read by this.
  static std::shared_ptr<const Texture> fromPremultiplied(int width, int height, const float* rgba, const std::string& name);
  Texture(int width, int height, std::vector<float> rgbLinear);
  Vec3f sample(double u, double v) const;
  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<float>& rgbLinear() const { return rgb_; }
  // The texels are held as indices into at most 256 distinct values (an 8-bit image, decoded).
  bool paletted() const { return !palette_.empty(); }

 private:
  int width_, height_;
  std::vector<float> rgb_;
  // A texture of at most 256 distinct values is looked up through indices into them: the same
  // floats in a quarter of the memory, so look-ups stay in the cache (texture look-ups were a
  // tenth of a path-traced frame's time, most of it waiting for memory).
  std::vector<uint8_t> indices_;
  std::vector<float> palette_;
};

}  // namespace omnicam
