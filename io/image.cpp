#include "image.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <filesystem>

#include "atomic_file.h"
#include "errors.h"
#include "exr_channels.h"
#include "image_decoder.h"
#include "jpeg_codec.h"
#include "memory_budget.h"
#include "png_codec.h"

namespace omnicam {

using namespace image_io;

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

namespace {

// How an image file's integer code values map to linear light: by the colour space the file
// declares, not by its bit depth. Float data is linear.
struct Transfer {
  enum Kind { Linear, Srgb, Gamma } kind = Srgb;
  float gamma = 1.0f;
  float operator()(float v) const {
    switch (kind) {
      case Linear: return v;
      case Gamma: return v > 0.0f ? std::pow(v, gamma) : 0.0f;
      default: return srgbToLinear(v);
    }
  }
};

Transfer transferOf(const ImageHeader& header) {
  if (header.type == SampleType::Float) return {Transfer::Linear};
  std::string cs = header.colourSpace;
  std::transform(cs.begin(), cs.end(), cs.begin(), [](unsigned char ch) { return std::tolower(ch); });
  if (cs == "linear" || cs == "scene_linear" || cs == "lin_srgb" || cs == "lin_rec709") return {Transfer::Linear};
  if (cs.rfind("gammacorrected", 0) == 0 || cs.rfind("gamma", 0) == 0) {
    const size_t digits = cs.find_first_of("0123456789");
    const float g = digits == std::string::npos ? 0.0f : std::strtof(cs.c_str() + digits, nullptr);
    if (g > 0.1f && g < 10.0f) return {Transfer::Gamma, g};
  }
  return {Transfer::Srgb};  // integer images without a declaration: the web's and cameras' default
}

// The decoded channels as floats, then the RGBA image.
int64_t decodeBytes(const ImageHeader& header) {
  return static_cast<int64_t>(header.width) * header.height * (4 * header.channels + 16);
}

std::unique_ptr<ImageDecoder> openImageFile(const std::string& path) { return openImageDecoder(ImageSource::file(path)); }

std::unique_ptr<ImageDecoder> openImageMemory(const unsigned char* data, size_t size, const std::string& name) {
  return openImageDecoder(ImageSource::memory(std::string_view(reinterpret_cast<const char*>(data), size), name));
}

// How a file's decoded channels become linear premultiplied RGBA.
struct PixelDecoding {
  int channels = 0, alphaChannel = -1;
  Transfer transfer;
  bool unassociated = false;

  explicit PixelDecoding(const ImageHeader& header)
      : channels(header.channels),
        alphaChannel(header.alphaChannel >= 0 ? header.alphaChannel : (channels == 2 || channels == 4 ? channels - 1 : -1)),
        transfer(transferOf(header)),
        unassociated(transfer.kind != Transfer::Linear || header.unassociatedAlpha) {}

  // `count` pixels of `raw` (channels floats each) into `rgba` (4 floats each). A value that is
  // not finite (NaN, ±∞) becomes 0; returns how many pixels had one.
  size_t apply(const float* raw, size_t count, float* rgba) const {
    const int colourChannels = channels >= 3 ? 3 : 1;
    size_t nonFinite = 0;
    for (size_t p = 0; p < count; ++p) {
      const float* src = &raw[p * channels];
      bool finite = true;
      float rgb[3];
      for (int c = 0; c < 3; ++c) {
        const float v = src[std::min(c, colourChannels - 1)];
        finite = finite && std::isfinite(v);
        rgb[c] = std::isfinite(v) ? transfer(v) : 0.0f;
      }
      float alpha = alphaChannel >= 0 ? src[alphaChannel] : 1.0f;
      if (!std::isfinite(alpha)) alpha = 0.0f, finite = false;
      float* dst = &rgba[p * 4];
      for (int c = 0; c < 3; ++c) dst[c] = unassociated ? rgb[c] * alpha : rgb[c];
      dst[3] = alpha;
      nonFinite += !finite;
    }
    return nonFinite;
  }

  // How many of the file's first channels are read as colour.
  int colourChannelCount() const { return channels >= 3 ? 3 : 1; }

  // Whether the channels read as colour are named as an image's are (docs in image.h): R, G, B
  // (or Red, Green, Blue, in any case, as the EXR decoder orders them), or one grey channel.
  static bool colourNames(const ImageHeader& header) {
    const std::vector<std::string>& names = header.channelNames;
    if (names.empty()) return true;  // formats without channel names hold colour
    auto named = [&](size_t c, std::initializer_list<std::string_view> choices) {
      const size_t dot = names[c].rfind('.');
      const std::string_view suffix = dot == std::string::npos ? std::string_view(names[c]) : std::string_view(names[c]).substr(dot + 1);
      return std::any_of(choices.begin(), choices.end(), [&](std::string_view choice) {
        return suffix.size() == choice.size() && std::equal(suffix.begin(), suffix.end(), choice.begin(),
                                                            [](char x, char y) { return std::tolower(x) == std::tolower(y); });
      });
    };
    if (PixelDecoding(header).colourChannelCount() == 1) return named(0, {"Y", "R", "Red", "G", "Green", "B", "Blue"});
    return named(0, {"R", "Red"}) && named(1, {"G", "Green"}) && named(2, {"B", "Blue"});
  }
};

// The whole image; `nonFinite`, if given, counts the pixels with a value that is not finite.
ImageRGBA decode(ImageDecoder& decoder, size_t* nonFinite = nullptr) {
  const ImageHeader& header = decoder.header();
  requireMemory(decodeBytes(header), decoder.name() + ": decoding " + std::to_string(header.width) + "x" +
                                         std::to_string(header.height) + " pixels");
  const std::vector<float> raw = decoder.readAllRows();
  ImageRGBA image(static_cast<int>(header.width), static_cast<int>(header.height));
  const size_t count = PixelDecoding(header).apply(raw.data(), static_cast<size_t>(header.width) * header.height, image.pixels.data());
  if (nonFinite) *nonFinite = count;
  return image;
}

}  // namespace

struct ImageRowReader::State {
  std::unique_ptr<ImageDecoder> decoder;
  int next = 0;  // the first row not yet read
  std::vector<float> raw;
  long nonFinitePixels = 0;
};

ImageRowReader::ImageRowReader(std::unique_ptr<State> state) : state_(std::move(state)) {}
ImageRowReader::ImageRowReader(ImageRowReader&&) noexcept = default;
ImageRowReader& ImageRowReader::operator=(ImageRowReader&&) noexcept = default;
ImageRowReader::~ImageRowReader() = default;

ImageRowReader ImageRowReader::openFile(const std::string& path) {
  auto state = std::make_unique<State>();
  state->decoder = openImageFile(path);
  return ImageRowReader(std::move(state));
}

ImageRowReader ImageRowReader::openMemory(const unsigned char* data, size_t size, const std::string& name) {
  auto state = std::make_unique<State>();
  state->decoder = openImageMemory(data, size, name);
  return ImageRowReader(std::move(state));
}

int ImageRowReader::width() const { return static_cast<int>(state_->decoder->header().width); }
int ImageRowReader::height() const { return static_cast<int>(state_->decoder->header().height); }
int64_t ImageRowReader::rowBytes() const { return decodeBytes(state_->decoder->header()) / height(); }
int64_t ImageRowReader::wholeBytes() const { return state_->decoder->wholeBytes(); }

void ImageRowReader::readRows(int first, int count, float* rgba) {
  const ImageHeader& header = state_->decoder->header();
  if (first != state_->next || count < 0 || first + count > header.height)
    throw std::logic_error(state_->decoder->name() + ": rows " + std::to_string(first) + " to " + std::to_string(first + count) +
                           " asked for out of order (next " + std::to_string(state_->next) + " of " + std::to_string(header.height) + ")");
  const size_t pixels = static_cast<size_t>(header.width) * count;
  state_->raw.resize(pixels * header.channels);
  state_->decoder->readRows(first, count, state_->raw.data());
  state_->nonFinitePixels += static_cast<long>(PixelDecoding(header).apply(state_->raw.data(), pixels, rgba));
  state_->next = first + count;
}

long ImageRowReader::nonFinitePixels() const { return state_->nonFinitePixels; }
const std::vector<std::string>& ImageRowReader::channelNames() const { return state_->decoder->header().channelNames; }
bool ImageRowReader::holdsColour() const { return PixelDecoding::colourNames(state_->decoder->header()); }
bool ImageRowReader::holdsAlpha() const { return PixelDecoding(state_->decoder->header()).alphaChannel >= 0; }

void ImageRowReader::requireColour() const {
  if (holdsColour()) return;
  const std::vector<std::string>& names = channelNames();
  const size_t read = static_cast<size_t>(PixelDecoding(state_->decoder->header()).colourChannelCount());
  std::string readAsColour;
  for (size_t c = 0; c < read; ++c) readAsColour += (c ? ", " : "") + quote(names[c]);
  throw InputError(state_->decoder->name() + ": not a colour image: its first channels, " + readAsColour + " (of " +
                   std::to_string(names.size()) + "), would be read as colour; an image's are R, G, B or one grey channel");
}

ImageRGBA ImageRowReader::readRemaining() {
  ImageRGBA image(width(), height());
  const int first = state_->next;
  readRows(first, height() - first, image.pixels.data() + static_cast<size_t>(first) * width() * 4);
  return image;
}

ImageRGBA readImage(const std::string& path) { return decode(*openImageFile(path)); }

int64_t imageDecodeBytes(const std::string& path) {
  const auto decoder = openImageFile(path);
  return decodeBytes(decoder->header()) + decoder->wholeBytes();
}

ImageRGBA readImageFromMemory(const unsigned char* data, size_t size, const std::string& name) {
  return decode(*openImageMemory(data, size, name));
}

ImageRGBA readFiniteImageFromMemory(const unsigned char* data, size_t size, const std::string& name) {
  size_t nonFinite = 0;
  ImageRGBA image = decode(*openImageMemory(data, size, name), &nonFinite);
  if (nonFinite > 0)
    throw InputError(name + ": " + std::to_string(nonFinite) + (nonFinite == 1 ? " pixel holds" : " pixels hold") +
                     " a value that is not finite (NaN or ±∞)");
  return image;
}

std::vector<unsigned char> srgb8Codes(const ImageRGBA& image) {
  static const SrgbEncoder encode;
  std::vector<unsigned char> codes(image.pixels.size());
  for (size_t p = 0; p < image.pixels.size() / 4; ++p) {
    const float* src = &image.pixels[p * 4];
    const float alpha = src[3];
    for (int c = 0; c < 3; ++c) codes[p * 4 + c] = encode(alpha > 0.0f ? src[c] / alpha : 0.0f);
    codes[p * 4 + 3] = static_cast<unsigned char>(std::lround(std::clamp(alpha, 0.0f, 1.0f) * 255.0f));
  }
  return codes;
}

std::vector<unsigned char> encodeImage(const std::string& path, const ImageRGBA& image) {
  const std::string ext = lowerExtension(path);
  if (ext == ".exr") {
    std::vector<ExrChannelSource> channels;
    for (int c = 0; c < 4; ++c) channels.push_back({std::string(1, "RGBA"[c]), ExrSampleType::Float, image.pixels.data() + c, nullptr, 4});
    return encodeExrChannels(path, image.width, image.height, channels, {});
  }
  if (ext != ".png") throw InputError(showPath(path) + ": output must end in .png or .exr");
  const std::vector<unsigned char> codes = srgb8Codes(image);
  return encodePng(path, image.width, image.height, 4, 8, codes.data(), true);
}

std::vector<unsigned char> readRgb8Codes(std::string_view bytes, const std::string& name, int& width, int& height) {
  const auto decoder = openImageDecoder(ImageSource::memory(bytes, name));
  const ImageHeader& header = decoder->header();
  if (header.type != SampleType::Uint8) throw InputError(name + ": not an 8-bit image (its codes would be rounded)");
  width = static_cast<int>(header.width), height = static_cast<int>(header.height);
  const size_t pixels = static_cast<size_t>(width) * height, channels = static_cast<size_t>(header.channels);
  std::vector<unsigned char> stored(pixels * channels), rgb(pixels * 3);
  decoder->readNativeRows(0, height, stored.data());
  const size_t colours = channels >= 3 ? 3 : 1;
  for (size_t p = 0; p < pixels; ++p)
    for (size_t c = 0; c < 3; ++c) rgb[3 * p + c] = stored[p * channels + std::min(c, colours - 1)];
  return rgb;
}

std::vector<unsigned char> jpegCompressed(const std::vector<unsigned char>& rgb, int width, int height, int quality) {
  const std::vector<unsigned char> jpeg = encodeJpeg("frame.jpg", width, height, 3, rgb.data(), quality);
  const auto decoder = openImageDecoder(ImageSource::memory(std::string_view(reinterpret_cast<const char*>(jpeg.data()), jpeg.size()), "frame.jpg"));
  std::vector<unsigned char> codes(rgb.size());
  decoder->readNativeRows(0, height, codes.data());
  return codes;
}

void writeImageAtomic(const std::string& path, const ImageRGBA& image) {
  const std::vector<unsigned char> bytes = encodeImage(path, image);
  writeBytesAtomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace omnicam
