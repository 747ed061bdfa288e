#include "aov_preview.h"

#include <algorithm>
#include <cmath>

#include "coco.h"
#include "errors.h"
#include "geometry.h"

namespace omnicam {

namespace {

void setPixel(ImageRGBA& image, int i, int j, const Vec3f& colour) {
  if (i < 0 || j < 0 || i >= image.width || j >= image.height) return;
  float* px = image.at(i, j);
  for (int c = 0; c < 3; ++c) px[c] = colour[c];
  px[3] = 1.0f;
}

// A few stops of a yellow → red → purple → dark blue ramp (linear RGB).
Vec3f ramp(double t) {
  static const Vec3f stops[] = {{1.0f, 0.9f, 0.1f}, {0.9f, 0.25f, 0.05f}, {0.45f, 0.05f, 0.4f}, {0.03f, 0.03f, 0.25f}};
  t = std::clamp(t, 0.0, 1.0) * 3.0;
  const int k = std::min(2, static_cast<int>(t));
  const float f = static_cast<float>(t - k);
  return stops[k] * (1.0f - f) + stops[k + 1] * f;
}

}  // namespace

ImageRGBA depthPreview(const DataImage& depth, double farMetres) {
  ImageRGBA image(depth.width, depth.height);
  for (int j = 0; j < depth.height; ++j)
    for (int i = 0; i < depth.width; ++i) {
      const float d = depth.values[static_cast<size_t>(j) * depth.width + i];
      setPixel(image, i, j, d > 0.0f ? ramp(std::sqrt(d / farMetres)) : Vec3f::Zero());
    }
  return image;
}

ImageRGBA idPreview(const std::vector<uint16_t>& ids, int width, int height) {
  ImageRGBA image(width, height);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const uint32_t id = ids[static_cast<size_t>(j) * width + i];
      if (id == 0) {
        setPixel(image, i, j, Vec3f::Zero());
        continue;
      }
      // Golden-ratio hues: consecutive ids land far apart on the colour wheel.
      const double hue = std::fmod(id * 0.618033988749895, 1.0) * 6.0;
      const int sector = static_cast<int>(hue);
      const float f = static_cast<float>(hue - sector);
      const Vec3f wheel[6] = {{1, f, 0}, {1 - f, 1, 0}, {0, 1, f}, {0, 1 - f, 1}, {f, 0, 1}, {1, 0, 1 - f}};
      setPixel(image, i, j, Vec3f((0.15f + 0.75f * wheel[sector].array()).pow(2.2f).matrix()));
    }
  return image;
}

ImageRGBA drawLandmarkAnnotations(const ImageRGBA& image, const nlohmann::json& annotations) {
  ImageRGBA out = image;
  for (const auto& lm : annotations.at("landmarks")) {
    if (!lm.at("in_view").get<bool>() || lm.at("bbox").is_null()) continue;
    const Vec3f colour = lm.at("visible").get<bool>() ? Vec3f(0.1f, 1.0f, 0.1f) : Vec3f(1.0f, 0.05f, 0.05f);
    const auto& b = lm.at("bbox");
    // The box's edges run along pixel rows/columns through its continuous bounds.
    const int i0 = static_cast<int>(std::floor(b[0].get<double>())), j0 = static_cast<int>(std::floor(b[1].get<double>()));
    const int i1 = static_cast<int>(std::floor(b[2].get<double>())), j1 = static_cast<int>(std::floor(b[3].get<double>()));
    for (int i = i0; i <= i1; ++i) setPixel(out, i, j0, colour), setPixel(out, i, j1, colour);
    for (int j = j0; j <= j1; ++j) setPixel(out, i0, j, colour), setPixel(out, i1, j, colour);
    const int ci = static_cast<int>(std::floor(lm.at("centre")[0].get<double>()));
    const int cj = static_cast<int>(std::floor(lm.at("centre")[1].get<double>()));
    for (int d = -2; d <= 2; ++d) setPixel(out, ci + d, cj, colour), setPixel(out, ci, cj + d, colour);
  }
  return out;
}

ImageRGBA drawCocoAnnotations(const ImageRGBA& image, const nlohmann::json& coco, int imageId) {
  ImageRGBA out = image;
  for (const auto& a : coco.at("annotations")) {
    if (a.at("image_id") != imageId || !a.contains("segmentation")) continue;  // the landmarks: keypoints only
    const uint16_t category = a.at("category_id").get<uint16_t>();
    const ImageRGBA swatch = idPreview({category}, 1, 1);  // the category's colour, as the semantic preview has it
    const Vec3f colour(swatch.at(0, 0)[0], swatch.at(0, 0)[1], swatch.at(0, 0)[2]);
    const auto& size = a.at("segmentation").at("size");
    const int h = size.at(0).get<int>(), w = size.at(1).get<int>();
    if (w != out.width || h != out.height) throw InputError("coco: annotation " + a.at("id").dump() + ": size is not the image's");
    // Runs over the pixels in column-major order, 0s first.
    int64_t pixel = 0;
    bool on = false;
    for (const uint32_t run : cocoRunsFromCounts(a.at("segmentation").at("counts").get<std::string>(), "coco")) {
      for (uint32_t k = 0; on && k < run; ++k) {
        const int64_t p = pixel + k;
        if (p >= int64_t{w} * h) break;
        float* px = out.at(static_cast<int>(p / h), static_cast<int>(p % h));
        for (int c = 0; c < 3; ++c) px[c] = 0.45f * px[c] + 0.55f * colour[c] * px[3];
      }
      pixel += run;
      on = !on;
    }
    const auto& b = a.at("bbox");
    const int i0 = b[0].get<int>(), j0 = b[1].get<int>(), i1 = i0 + b[2].get<int>() - 1, j1 = j0 + b[3].get<int>() - 1;
    for (int i = i0; i <= i1; ++i) setPixel(out, i, j0, colour), setPixel(out, i, j1, colour);
    for (int j = j0; j <= j1; ++j) setPixel(out, i0, j, colour), setPixel(out, i1, j, colour);
  }
  return out;
}

}  // namespace omnicam
