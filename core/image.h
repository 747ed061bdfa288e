#pragma once
// Linear RGBA float images with associated (premultiplied) alpha, and their files.
// PNG/JPEG are sRGB-encoded 8-bit on disk; EXR is linear half/float (spec §3).
#include <string>
#include <vector>

namespace omnicam {

struct ImageRGBA {
  int width = 0, height = 0;
  std::vector<float> pixels;  // row-major, 4 floats per pixel, v down

  ImageRGBA() = default;
  ImageRGBA(int w, int h) : width(w), height(h), pixels(static_cast<size_t>(w) * h * 4, 0.0f) {}
  float* at(int i, int j) { return &pixels[(static_cast<size_t>(j) * width + i) * 4]; }
  const float* at(int i, int j) const { return &pixels[(static_cast<size_t>(j) * width + i) * 4]; }
};

float srgbToLinear(float encoded);
float linearToSrgb(float linear);

// Reads any OpenImageIO-supported file as linear premultiplied RGBA (8-bit files are
// sRGB-decoded; missing alpha becomes 1). Throws InputError naming the file.
ImageRGBA readImage(const std::string& path);
// Writes .png (sRGB 8-bit, straight alpha) or .exr (linear float, associated alpha) through a
// temporary file and a rename. Throws InputError for an unsupported extension.
void writeImageAtomic(const std::string& path, const ImageRGBA& image);
bool isSupportedImageOutput(const std::string& path);

}  // namespace omnicam
