#include "image.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <filesystem>
#include <OpenImageIO/filesystem.h>

#include "atomic_file.h"
#include "errors.h"
#include "memory_budget.h"
#include "oiio_support.h"

namespace omnicam {

using namespace image_io;  // OpenImageIO, quietly and in one-line messages

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
// declares (OpenImageIO's oiio:ColorSpace), not by its bit depth. Float data is linear.
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

Transfer transferOf(const OIIO::ImageSpec& spec) {
  const auto base = spec.format.basetype;
  if (base == OIIO::TypeDesc::FLOAT || base == OIIO::TypeDesc::HALF || base == OIIO::TypeDesc::DOUBLE)
    return {Transfer::Linear};
  std::string cs = spec.get_string_attribute("oiio:ColorSpace");
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
int64_t decodeBytes(const OIIO::ImageSpec& spec) {
  return static_cast<int64_t>(spec.width) * spec.height * (4 * spec.nchannels + 16);
}

std::unique_ptr<OIIO::ImageInput> openImageFile(const std::string& path) {
  // Only regular files: a FIFO or a device (/dev/zero) would be read forever.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(showPath(path) + ": cannot read image (" +
                     (std::filesystem::exists(path, ec) ? "not a regular file" : "no such file") + ")");
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // we associate ourselves, after decoding
  const QuietStderr quiet;
  auto input = OIIO::ImageInput::open(path, &config);
  if (!input) throw InputError(showPath(path) + ": cannot read image (" + firstLine(OIIO::geterror()) + ")");
  return input;
}

// How a file's decoded channels become linear premultiplied RGBA.
struct PixelDecoding {
  int channels = 0, alphaChannel = -1;
  Transfer transfer;
  bool unassociated = false;

  explicit PixelDecoding(const OIIO::ImageSpec& spec)
      : channels(spec.nchannels),
        alphaChannel(spec.alpha_channel >= 0 ? spec.alpha_channel : (channels == 2 || channels == 4 ? channels - 1 : -1)),
        transfer(transferOf(spec)),
        unassociated(transfer.kind != Transfer::Linear || spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0) {}

  // `count` pixels of `raw` (channels floats each) into `rgba` (4 floats each).
  void apply(const float* raw, size_t count, float* rgba) const {
    const int colourChannels = channels >= 3 ? 3 : 1;
    for (size_t p = 0; p < count; ++p) {
      const float* src = &raw[p * channels];
      float rgb[3];
      for (int c = 0; c < 3; ++c) {
        const float v = src[std::min(c, colourChannels - 1)];
        rgb[c] = std::isfinite(v) ? transfer(v) : 0.0f;
      }
      float alpha = alphaChannel >= 0 ? src[alphaChannel] : 1.0f;
      if (!std::isfinite(alpha)) alpha = 0.0f;
      float* dst = &rgba[p * 4];
      for (int c = 0; c < 3; ++c) dst[c] = unassociated ? rgb[c] * alpha : rgb[c];
      dst[3] = alpha;
    }
  }
};

ImageRGBA decode(OIIO::ImageInput& input, const std::string& name) {
  const OIIO::ImageSpec& spec = input.spec();
  checkHeader(spec, name);
  requireMemory(decodeBytes(spec), name + ": decoding " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " pixels");
  const int channels = spec.nchannels;
  std::vector<float> raw(static_cast<size_t>(spec.width) * spec.height * channels);
  if (!input.read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, raw.data()))
    throw InputError(name + ": cannot decode image (" + firstLine(input.geterror()) + ")");
  ImageRGBA image(spec.width, spec.height);
  PixelDecoding(spec).apply(raw.data(), static_cast<size_t>(spec.width) * spec.height, image.pixels.data());
  return image;
}

// OpenImageIO's reader of an image in memory, by the bytes' signature, never by a name the data
// chose; `reader` must outlive it.
std::unique_ptr<OIIO::ImageInput> openImageMemory(const unsigned char* data, size_t size, const std::string& name,
                                                  OIIO::Filesystem::IOMemReader& reader) {
  const char* format = nullptr;
  if (size >= 8 && std::memcmp(data, "\x89PNG\r\n\x1a\n", 8) == 0) format = "memory.png";
  else if (size >= 3 && data[0] == 0xFF && data[1] == 0xD8 && data[2] == 0xFF) format = "memory.jpg";
  else if (size >= 4 && std::memcmp(data, "\x76\x2f\x31\x01", 4) == 0) format = "memory.exr";
  if (!format) throw InputError(name + ": not a PNG, JPEG or EXR image");
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  void* proxy = &reader;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  const QuietStderr quiet;
  auto input = OIIO::ImageInput::open(format, &config);
  if (!input) throw InputError(name + ": cannot read image (" + firstLine(OIIO::geterror()) + ")");
  return input;
}

}  // namespace

struct ImageRowReader::State {
  std::unique_ptr<OIIO::Filesystem::IOMemReader> memory;  // the proxy of an image in memory
  std::unique_ptr<OIIO::ImageInput> input;
  std::string name;
  int next = 0;  // the first row not yet read
  std::vector<float> raw;
};

ImageRowReader::ImageRowReader(std::unique_ptr<State> state) : state_(std::move(state)) {
  checkHeader(state_->input->spec(), state_->name);
}
ImageRowReader::ImageRowReader(ImageRowReader&&) noexcept = default;
ImageRowReader& ImageRowReader::operator=(ImageRowReader&&) noexcept = default;
ImageRowReader::~ImageRowReader() = default;

ImageRowReader ImageRowReader::openFile(const std::string& path) {
  auto state = std::make_unique<State>();
  state->input = openImageFile(path);
  state->name = showPath(path);
  return ImageRowReader(std::move(state));
}

ImageRowReader ImageRowReader::openMemory(const unsigned char* data, size_t size, const std::string& name) {
  auto state = std::make_unique<State>();
  state->memory = std::make_unique<OIIO::Filesystem::IOMemReader>(const_cast<unsigned char*>(data), size);
  state->input = openImageMemory(data, size, name, *state->memory);
  state->name = name;
  return ImageRowReader(std::move(state));
}

int ImageRowReader::width() const { return state_->input->spec().width; }
int ImageRowReader::height() const { return state_->input->spec().height; }
int64_t ImageRowReader::rowBytes() const { return decodeBytes(state_->input->spec()) / height(); }

void ImageRowReader::readRows(int first, int count, float* rgba) {
  const OIIO::ImageSpec& spec = state_->input->spec();
  if (first != state_->next || count < 0 || first + count > spec.height)
    throw std::logic_error(state_->name + ": rows " + std::to_string(first) + " to " + std::to_string(first + count) +
                           " asked for out of order (next " + std::to_string(state_->next) + " of " + std::to_string(spec.height) + ")");
  const size_t pixels = static_cast<size_t>(spec.width) * count;
  state_->raw.resize(pixels * spec.nchannels);
  const QuietStderr quiet;
  if (!state_->input->read_scanlines(0, 0, first, first + count, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, state_->raw.data()))
    throw InputError(state_->name + ": cannot decode image (" + firstLine(state_->input->geterror()) + ")");
  PixelDecoding(spec).apply(state_->raw.data(), pixels, rgba);
  state_->next = first + count;
}

ImageRGBA readImage(const std::string& path) {
  const auto input = openImageFile(path);
  const QuietStderr quiet;
  return decode(*input, showPath(path));  // decode names it in messages only
}

int64_t imageDecodeBytes(const std::string& path) {
  const auto input = openImageFile(path);
  checkHeader(input->spec(), showPath(path));
  return decodeBytes(input->spec());
}

ImageRGBA readImageFromMemory(const unsigned char* data, size_t size, const std::string& name) {
  OIIO::Filesystem::IOMemReader reader(const_cast<unsigned char*>(data), size);
  const auto input = openImageMemory(data, size, name, reader);
  const QuietStderr quiet;
  return decode(*input, name);
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
  if (ext != ".png" && ext != ".exr") throw InputError(showPath(path) + ": output must end in .png or .exr");
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput sink(bytes);
  void* proxy = &sink;
  const std::string format = "memory" + ext;
  auto out = OIIO::ImageOutput::create(format);
  if (!out) throw OutputError(showPath(path) + ": no image writer (" + firstLine(OIIO::geterror()) + ")");
  if (ext == ".exr") {
    OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::FLOAT);
    spec.attribute("compression", "zip");
    spec.attribute("DateTime", "");  // no timestamp: identical pixels give identical bytes
    spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    if (!out->open(format, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()) || !out->close())
      throw OutputError(showPath(path) + ": cannot encode EXR (" + firstLine(out->geterror()) + ")");
    return bytes;
  }
  const std::vector<unsigned char> codes = srgb8Codes(image);
  OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);
  spec.attribute("oiio:ColorSpace", "sRGB");
  spec.attribute("png:compressionLevel", 1);  // sequences: speed over the last few percent of size
  spec.attribute("png:filter", kPngFilterSub);
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  if (!out->open(format, spec) || !out->write_image(OIIO::TypeDesc::UINT8, codes.data()) || !out->close())
    throw OutputError(showPath(path) + ": cannot encode PNG (" + firstLine(out->geterror()) + ")");
  return bytes;
}

void writeImageAtomic(const std::string& path, const ImageRGBA& image) {
  const std::vector<unsigned char> bytes = encodeImage(path, image);
  writeBytesAtomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace omnicam
