#include "exr_channels.h"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/openexr.h>

#include <algorithm>
#include <cstring>
#if defined(__x86_64__)
#include <cpuid.h>
#include <immintrin.h>
#endif

#include "errors.h"
#include "exr_chunks.h"
#include "input_limits.h"

namespace omnicam {

namespace {

// Channels a decoded file may have: far more than a dataset frame's dozen.
constexpr size_t kMaxExrChannels = 64;

// An OpenEXR file written into memory by the core API, and its last message.
struct MemoryExrFile {
  std::vector<unsigned char> bytes;
  std::string message;
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

// Every `stride`-th float of `values` as half (round to nearest even), n of them: with the CPU's
// F16C instructions, 8 at a time, where it has them (the same rounding as Imath's software
// conversion, about a tenth of an encode).
#if defined(__x86_64__)
__attribute__((target("avx,f16c"))) void toHalvesF16c(const float* values, size_t stride, size_t n, Imath::half* out) {
  size_t p = 0;
  for (; p + 8 <= n; p += 8) {
    const float* v = values + p * stride;
    const __m256 eight = stride == 1 ? _mm256_loadu_ps(v)
                                     : _mm256_setr_ps(v[0], v[stride], v[2 * stride], v[3 * stride], v[4 * stride],
                                                      v[5 * stride], v[6 * stride], v[7 * stride]);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + p), _mm256_cvtps_ph(eight, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC));
  }
  for (; p < n; ++p) {
    const __m128i one = _mm_cvtps_ph(_mm_set_ss(values[p * stride]), _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
    out[p].setBits(static_cast<uint16_t>(_mm_cvtsi128_si32(one) & 0xffff));
  }
}

bool hasF16c() {
  unsigned a = 0, b = 0, c = 0, d = 0;
  return __builtin_cpu_supports("avx") && __get_cpuid(1, &a, &b, &c, &d) && (c & bit_F16C);
}
#endif

void toHalves(const float* values, size_t stride, size_t n, Imath::half* out) {
#if defined(__x86_64__)
  static const bool f16c = hasF16c();
  if (f16c) return toHalvesF16c(values, stride, n, out);
#endif
  for (size_t p = 0; p < n; ++p) out[p] = Imath::half(values[p * stride]);
}

}  // namespace

namespace {

// The core API's messages, collected for the one line an error becomes.
// Both are called from OpenEXR's C code: nothing may be thrown through it.
void keepMessage(exr_const_context_t ctxt, exr_result_t, const char* message) noexcept {
  void* user = nullptr;
  if (exr_get_user_data(ctxt, &user) != EXR_ERR_SUCCESS || !user) return;
  try {
    static_cast<MemoryExrFile*>(user)->message = message ? message : "";
  } catch (...) {
  }
}

int64_t writeToMemory(exr_const_context_t, void* user, const void* buffer, uint64_t size, uint64_t offset,
                      exr_stream_error_func_ptr_t) noexcept {
  std::vector<unsigned char>& bytes = static_cast<MemoryExrFile*>(user)->bytes;
  try {
    if (offset + size > bytes.size()) bytes.resize(offset + size);
  } catch (...) {
    return -1;  // OpenEXR reports a failed write
  }
  std::memcpy(bytes.data() + offset, buffer, size);
  return static_cast<int64_t>(size);
}

void check(exr_result_t result, const MemoryExrFile& file, const char* step) {
  if (result != EXR_ERR_SUCCESS)
    throw std::runtime_error(std::string(step) + ": " + (file.message.empty() ? exr_get_default_error_message(result) : file.message));
}

struct ChunkFormat {
  exr_compression_t file;
  ExrChunkCompression chunk;
  int lines;  // scanlines per chunk
};

ChunkFormat chunkFormat(ExrCompression compression) {
  switch (compression) {
    case ExrCompression::None: return {EXR_COMPRESSION_NONE, ExrChunkCompression::None, 1};
    case ExrCompression::Rle: return {EXR_COMPRESSION_RLE, ExrChunkCompression::Rle, 1};
    case ExrCompression::Zips: return {EXR_COMPRESSION_ZIPS, ExrChunkCompression::Zip, 1};
    case ExrCompression::Zip: return {EXR_COMPRESSION_ZIP, ExrChunkCompression::Zip, 16};
  }
  return {EXR_COMPRESSION_ZIP, ExrChunkCompression::Zip, 16};
}

// One channel's values as the file stores them: half planes converted here, float and uint
// values read in place (4 bytes each, little-endian like the file).
struct PackedChannel {
  const ExrChannelSource* source;
  std::vector<Imath::half> halves;
  size_t bytes() const { return source->stored == ExrSampleType::Half ? 2 : 4; }
};

// Scanlines [y0, y1) of every channel, in the file's order: line by line, channel by channel.
void packLines(const std::vector<PackedChannel>& channels, int width, int y0, int y1, std::vector<unsigned char>& packed) {
  packed.clear();
  for (int y = y0; y < y1; ++y) {
    const size_t row = static_cast<size_t>(y) * width;
    for (const PackedChannel& c : channels) {
      const size_t at = packed.size();
      packed.resize(at + c.bytes() * width);
      unsigned char* out = packed.data() + at;
      const ExrChannelSource& s = *c.source;
      if (s.stored == ExrSampleType::Half) {
        std::memcpy(out, c.halves.data() + row, 2 * static_cast<size_t>(width));
      } else if (s.pixelStride == 1) {
        std::memcpy(out, s.stored == ExrSampleType::Uint ? static_cast<const void*>(s.uints + row) : s.floats + row,
                    4 * static_cast<size_t>(width));
      } else {
        for (int x = 0; x < width; ++x) {
          const size_t p = (row + x) * s.pixelStride;
          std::memcpy(out + 4 * static_cast<size_t>(x),
                      s.stored == ExrSampleType::Uint ? static_cast<const void*>(s.uints + p) : s.floats + p, 4);
        }
      }
    }
  }
}

}  // namespace

std::vector<unsigned char> encodeExrChannels(const std::string& path, int width, int height,
                                             const std::vector<ExrChannelSource>& channels, const ExrWriteOptions& options) {
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "OpenEXR files are little-endian, like this machine's memory");
  const ChunkFormat format = chunkFormat(options.compression);
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
  // The file orders channels by name (byte order); each is converted once.
  std::vector<PackedChannel> packedChannels;
  for (const ExrChannelSource& channel : channels) {
    if (channel.stored == ExrSampleType::Uint ? !channel.uints : !channel.floats)
      throw std::logic_error("encodeExrChannels: " + channel.name + " has no values");
    PackedChannel& c = packedChannels.emplace_back(PackedChannel{&channel, {}});
    if (channel.stored == ExrSampleType::Half) {
      c.halves.resize(pixels);
      toHalves(channel.floats, channel.pixelStride, pixels, c.halves.data());
    }
  }
  std::sort(packedChannels.begin(), packedChannels.end(),
            [](const PackedChannel& a, const PackedChannel& b) { return a.source->name < b.source->name; });

  MemoryExrFile file;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.user_data = &file;
  init.write_fn = &writeToMemory;
  init.error_handler_fn = &keepMessage;
  exr_context_t context = nullptr;
  try {
    check(exr_start_write(&context, path.c_str(), EXR_WRITE_FILE_DIRECTLY, &init), file, "start");
    int part = 0;
    check(exr_add_part(context, nullptr, EXR_STORAGE_SCANLINE, &part), file, "part");
    check(exr_initialize_required_attr_simple(context, part, width, height, format.file), file, "header");
    for (const PackedChannel& c : packedChannels) {
      const exr_pixel_type_t type = c.source->stored == ExrSampleType::Half    ? EXR_PIXEL_HALF
                                    : c.source->stored == ExrSampleType::Float ? EXR_PIXEL_FLOAT
                                                                               : EXR_PIXEL_UINT;
      check(exr_add_channel(context, part, c.source->name.c_str(), type, EXR_PERCEPTUALLY_LINEAR, 1, 1), file, "channel");
    }
    for (const auto& [key, value] : options.text) check(exr_attr_set_string(context, part, key.c_str(), value.c_str()), file, "attribute");
    check(exr_write_header(context), file, "header");
    std::vector<unsigned char> packed, scratch, compressed;
    for (int y = 0; y < height; y += format.lines) {
      packLines(packedChannels, width, y, std::min(height, y + format.lines), packed);
      const bool smaller = compressExrChunk(format.chunk, packed.data(), packed.size(), options.zipLevel, scratch, compressed);
      const std::vector<unsigned char>& chunk = smaller ? compressed : packed;
      check(exr_write_scanline_chunk(context, part, y, chunk.data(), chunk.size()), file, "chunk");
    }
    check(exr_finish(&context), file, "finish");
  } catch (const std::exception& e) {
    if (context) exr_finish(&context);
    throw OutputError(showPath(path) + ": cannot encode EXR (" + oneLine(e.what()) + ")");
  }
  return std::move(file.bytes);
}

ExrChannels decodeExrChannels(std::string_view bytes, const std::string& name, bool headerOnly,
                              const std::set<std::string>* channels) {
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
      if (headerOnly || (channels && !channels->count(it.name()))) continue;
      if (static_cast<int64_t>(out.floats.size() + out.uints.size() + 1) * width * height > kMaxDecodedExrSamples)
        throw InputError(name + ": " + std::to_string(width) + "x" + std::to_string(height) + " pixels of " +
                         std::to_string(out.floats.size() + out.uints.size() + 1) + " channels are more than " +
                         std::to_string(kMaxDecodedExrSamples) + " values to decode");
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
