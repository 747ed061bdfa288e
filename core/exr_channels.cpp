#include "exr_channels.h"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <cstring>
#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "errors.h"
#include "input_limits.h"

namespace omnicam {

namespace {

// Channels a decoded file may have: far more than a dataset frame's dozen.
constexpr size_t kMaxExrChannels = 64;

class MemoryExrOutput : public Imf::OStream {
 public:
  explicit MemoryExrOutput(std::vector<unsigned char>& bytes) : Imf::OStream("memory.exr"), bytes_(bytes) {}
  void write(const char c[], int n) override {
    if (position_ + static_cast<uint64_t>(n) > bytes_.size()) bytes_.resize(position_ + n);
    std::memcpy(bytes_.data() + position_, c, static_cast<size_t>(n));
    position_ += static_cast<uint64_t>(n);
  }
  uint64_t tellp() override { return position_; }
  void seekp(uint64_t pos) override { position_ = pos; }

 private:
  std::vector<unsigned char>& bytes_;
  uint64_t position_ = 0;
};

class MemoryExrInput : public Imf::IStream {
 public:
  explicit MemoryExrInput(std::string_view bytes) : Imf::IStream("memory.exr"), bytes_(bytes) {}
  bool read(char c[], int n) override {
    if (n < 0 || position_ + static_cast<uint64_t>(n) > bytes_.size()) throw std::runtime_error("unexpected end of file");
    std::memcpy(c, bytes_.data() + position_, static_cast<size_t>(n));
    position_ += static_cast<uint64_t>(n);
    return position_ < bytes_.size();
  }
  uint64_t tellg() override { return position_; }
  void seekg(uint64_t pos) override { position_ = pos; }

 private:
  std::string_view bytes_;
  uint64_t position_ = 0;
};

// Every `stride`-th float of `values` as half (round to nearest even), n of them. The CPU's
// F16C instruction where it has one (the same rounding as Imath's software conversion, which
// costs as much as the compression of the rest).
#if defined(__x86_64__)
__attribute__((target("f16c"))) void toHalvesF16c(const float* values, size_t stride, size_t n, Imath::half* out) {
  for (size_t p = 0; p < n; ++p)
    out[p].setBits(_cvtss_sh(values[p * stride], _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC));
}
#endif

void toHalves(const float* values, size_t stride, size_t n, Imath::half* out) {
#if defined(__x86_64__)
  static const bool f16c = __builtin_cpu_supports("f16c");
  if (f16c) return toHalvesF16c(values, stride, n, out);
#endif
  for (size_t p = 0; p < n; ++p) out[p] = Imath::half(values[p * stride]);
}

Imf::PixelType pixelType(ExrSampleType type) {
  switch (type) {
    case ExrSampleType::Half: return Imf::HALF;
    case ExrSampleType::Float: return Imf::FLOAT;
    case ExrSampleType::Uint: return Imf::UINT;
  }
  return Imf::FLOAT;
}

Imf::Compression compressionOf(ExrCompression compression) {
  switch (compression) {
    case ExrCompression::None: return Imf::NO_COMPRESSION;
    case ExrCompression::Rle: return Imf::RLE_COMPRESSION;
    case ExrCompression::Zips: return Imf::ZIPS_COMPRESSION;
    case ExrCompression::Zip: return Imf::ZIP_COMPRESSION;
    case ExrCompression::Piz: return Imf::PIZ_COMPRESSION;
  }
  return Imf::ZIP_COMPRESSION;
}

}  // namespace

std::vector<unsigned char> encodeExrChannels(const std::string& path, int width, int height,
                                             const std::vector<ExrChannelSource>& channels, const ExrWriteOptions& options) {
  std::vector<unsigned char> bytes;
  try {
    Imf::Header header(width, height);
    header.compression() = compressionOf(options.compression);
    header.zipCompressionLevel() = options.zipLevel;
    for (const auto& [key, value] : options.text) header.insert(key, Imf::StringAttribute(value));
    // OpenEXR writes each channel from a buffer of its stored type: half channels are converted
    // here (planar), float and uint ones are read in place.
    std::vector<std::vector<Imath::half>> halves;
    halves.reserve(channels.size());
    Imf::FrameBuffer frameBuffer;
    const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
    for (const ExrChannelSource& channel : channels) {
      header.channels().insert(channel.name, Imf::Channel(pixelType(channel.stored)));
      const bool uint = channel.stored == ExrSampleType::Uint;
      if (uint ? !channel.uints : !channel.floats) throw std::logic_error("encodeExrChannels: " + channel.name + " has no values");
      if (channel.stored == ExrSampleType::Half) {
        std::vector<Imath::half>& plane = halves.emplace_back(pixels);
        toHalves(channel.floats, channel.pixelStride, pixels, plane.data());
        frameBuffer.insert(channel.name, Imf::Slice(Imf::HALF, reinterpret_cast<char*>(plane.data()), sizeof(Imath::half),
                                                    sizeof(Imath::half) * static_cast<size_t>(width)));
        continue;
      }
      const size_t stride = 4 * channel.pixelStride;  // float and uint32 alike
      char* base = uint ? reinterpret_cast<char*>(const_cast<uint32_t*>(channel.uints))
                        : reinterpret_cast<char*>(const_cast<float*>(channel.floats));
      frameBuffer.insert(channel.name, Imf::Slice(pixelType(channel.stored), base, stride, stride * static_cast<size_t>(width)));
    }
    MemoryExrOutput stream(bytes);
    Imf::OutputFile file(stream, header, 0);
    file.setFrameBuffer(frameBuffer);
    file.writePixels(height);
  } catch (const std::logic_error&) {
    throw;
  } catch (const std::exception& e) {
    throw OutputError(showPath(path) + ": cannot encode EXR (" + oneLine(e.what()) + ")");
  }
  return bytes;
}

ExrChannels decodeExrChannels(std::string_view bytes, const std::string& name, bool headerOnly) {
  ExrChannels out;
  try {
    MemoryExrInput stream(bytes);
    Imf::InputFile file(stream, 0);
    const Imath::Box2i window = file.header().dataWindow();
    if (window.min.x != 0 || window.min.y != 0) throw InputError(name + ": OpenEXR data window does not start at pixel (0, 0)");
    const int64_t width = int64_t{window.max.x} + 1, height = int64_t{window.max.y} + 1;
    if (width < 1 || height < 1 || width > limits::kMaxImageDimension || height > limits::kMaxImageDimension ||
        width * height > limits::kMaxImagePixels)
      throw InputError(name + ": image is " + std::to_string(width) + "x" + std::to_string(height) + " pixels; the limit is " +
                       std::to_string(limits::kMaxImageDimension) + " per side and " + std::to_string(limits::kMaxImagePixels) +
                       " in all");
    out.width = static_cast<int>(width), out.height = static_cast<int>(height);
    for (auto it = file.header().begin(); it != file.header().end(); ++it)
      if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) out.text[it.name()] = text->value();
    Imf::FrameBuffer frameBuffer;
    const size_t pixels = static_cast<size_t>(width * height);
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
      if (out.types.size() == kMaxExrChannels)
        throw InputError(name + ": more than " + std::to_string(kMaxExrChannels) + " channels");
      if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
        throw InputError(name + ": channel " + quote(it.name()) + " is subsampled");
      const bool uint = it.channel().type == Imf::UINT;
      out.types[it.name()] = uint ? ExrSampleType::Uint : it.channel().type == Imf::HALF ? ExrSampleType::Half : ExrSampleType::Float;
      if (headerOnly) continue;
      char* base;
      if (uint) base = reinterpret_cast<char*>(out.uints[it.name()].assign(pixels, 0), out.uints[it.name()].data());
      else base = reinterpret_cast<char*>(out.floats[it.name()].assign(pixels, 0.0f), out.floats[it.name()].data());
      frameBuffer.insert(it.name(), Imf::Slice(uint ? Imf::UINT : Imf::FLOAT, base, 4, 4 * static_cast<size_t>(width)));
    }
    if (!headerOnly) {
      file.setFrameBuffer(frameBuffer);
      file.readPixels(0, out.height - 1);
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(name + ": cannot read OpenEXR (" + oneLine(e.what()) + ")");
  }
  return out;
}

}  // namespace omnicam
