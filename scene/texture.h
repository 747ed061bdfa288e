#pragma once
// Bilinear texture lookup with texel centres at +0.5 and repeat wrapping (docs/conventions.md §2, the same
// as POV-Ray's `interpolate 2`). UV (0, 0) is the image's bottom-left corner, as in POV-Ray.
#include <memory>
#include <string>
#include <vector>

#include "geometry.h"

namespace omnicam {

class Texture {
 public:
  static std::shared_ptr<const Texture> load(const std::string& path);
  Texture(int width, int height, std::vector<float> rgbLinear);
  Vec3f sample(double u, double v) const;
  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<float>& rgbLinear() const { return rgb_; }

 private:
  int width_, height_;
  std::vector<float> rgb_;
};

}  // namespace omnicam
