#include "image.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "atomic_file.h"
#include "errors.h"

namespace omnicam {

namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return ext;
}

}  // namespace

float srgbToLinear(float e) {
  return e <= 0.04045f ? e / 12.92f : std::pow((e + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float l) {
  l = std::clamp(l, 0.0f, 1.0f);
  return l <= 0.0031308f ? 12.92f * l : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
}

namespace {

// 8-bit sRGB encoding without pow per pixel, exactly where lround(linearToSrgb(l) * 255)
// would round: the code is looked up in a 4096-bin table over linear [0, 1] and fixed up with
// one comparison against the next rounding threshold. One step suffices because no bin holds
// two thresholds (bin width 1/4096 < the smallest threshold gap, 1/(12.92·255)).
class SrgbEncoder {
 public:
  SrgbEncoder() {
    for (int k = 0; k < 255; ++k) thresholds_[k] = srgbToLinear((k + 0.5f) / 255.0f);
    for (int i = 0; i <= kBins; ++i) codeAtBin_[i] = exact(static_cast<float>(i) / kBins);
  }
  unsigned char operator()(float linear) const {
    linear = std::clamp(linear, 0.0f, 1.0f);
    int k = codeAtBin_[static_cast<int>(linear * kBins)];
    if (k < 255 && linear >= thresholds_[k]) ++k;
    return static_cast<unsigned char>(k);
  }

 private:
  static constexpr int kBins = 4096;
  unsigned char exact(float linear) const {
    return static_cast<unsigned char>(std::upper_bound(thresholds_, thresholds_ + 255, linear) - thresholds_);
  }
  float thresholds_[255];
  unsigned char codeAtBin_[kBins + 1];
};

}  // namespace

bool isSupportedImageOutput(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".png" || ext == ".exr";
}

ImageRGBA readImage(const std::string& path) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // we associate ourselves, after decoding
  auto input = OIIO::ImageInput::open(path, &config);
  if (!input) throw InputError(path + ": cannot read image (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec& spec = input->spec();
  const int channels = spec.nchannels;
  std::vector<float> raw(static_cast<size_t>(spec.width) * spec.height * channels);
  if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, raw.data()))
    throw InputError(path + ": cannot decode image (" + input->geterror() + ")");
  const bool eightBit = spec.format.basetype == OIIO::TypeDesc::UINT8 ||
                        spec.format.basetype == OIIO::TypeDesc::INT8;
  const bool linear = !eightBit;  // EXR/HDR/float TIFF are linear (spec §3)
  const bool unassociated = eightBit || spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0;
  ImageRGBA image(spec.width, spec.height);
  for (size_t p = 0; p < static_cast<size_t>(spec.width) * spec.height; ++p) {
    const float* src = &raw[p * channels];
    float rgb[3];
    for (int c = 0; c < 3; ++c) {
      const float v = src[std::min(c, channels == 2 ? 0 : channels - 1)];
      rgb[c] = linear ? v : srgbToLinear(v);
    }
    if (channels < 3) rgb[1] = rgb[2] = rgb[0];
    const float alpha = (channels == 4 || channels == 2) ? src[channels - 1] : 1.0f;
    float* dst = &image.pixels[p * 4];
    for (int c = 0; c < 3; ++c) dst[c] = unassociated ? rgb[c] * alpha : rgb[c];
    dst[3] = alpha;
  }
  return image;
}

void writeImageAtomic(const std::string& path, const ImageRGBA& image) {
  const std::string ext = lowerExtension(path);
  if (ext != ".png" && ext != ".exr")
    throw InputError(path + ": output must end in .png or .exr");
  writeAtomically(path, [&](const std::string& tmp) {
    auto out = OIIO::ImageOutput::create(tmp);
    if (!out) throw InputError(path + ": no image writer (" + OIIO::geterror() + ")");
    if (ext == ".exr") {
      OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::FLOAT);
      spec.attribute("compression", "zip");
      if (!out->open(tmp, spec) ||
          !out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()) || !out->close())
        throw InputError(path + ": cannot write EXR (" + out->geterror() + ")");
      return;
    }
    static const SrgbEncoder encode;
    std::vector<unsigned char> bytes(image.pixels.size());
    for (size_t p = 0; p < image.pixels.size() / 4; ++p) {
      const float* src = &image.pixels[p * 4];
      const float alpha = src[3];
      for (int c = 0; c < 3; ++c) bytes[p * 4 + c] = encode(alpha > 0.0f ? src[c] / alpha : 0.0f);
      bytes[p * 4 + 3] = static_cast<unsigned char>(std::lround(std::clamp(alpha, 0.0f, 1.0f) * 255.0f));
    }
    OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:UnassociatedAlpha", 1);
    spec.attribute("oiio:ColorSpace", "sRGB");
    spec.attribute("png:compressionLevel", 1);  // sequences: speed over the last few percent of size
    if (!out->open(tmp, spec) || !out->write_image(OIIO::TypeDesc::UINT8, bytes.data()) ||
        !out->close())
      throw InputError(path + ": cannot write PNG (" + out->geterror() + ")");
  });
}

}  // namespace omnicam
