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
#include <filesystem>

#include <tbb/parallel_for.h>
#if defined(__x86_64__)
#include <cpuid.h>
#include <immintrin.h>
#endif

#include "errors.h"
#include "exr_chunks.h"
#include "exr_memory_input.h"
#include "input_limits.h"
#include "memory_budget.h"

namespace omnicam {

namespace {

// Channels a decoded file may have: far more than a dataset frame's dozen.
constexpr size_t kMaxExrChannels = 64;

// An OpenEXR file written into memory by the core API, and its last message.
struct MemoryExrFile {
  std::vector<unsigned char> bytes;
  std::string message;
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

// The smallest packed size a chunk of `unpacked` bytes can have under `compression`: RLE codes a
// run of up to 128 equal bytes in 2, deflate at best about 1:1032. PIZ (Huffman with runs), PXR24
// (deflate after a transform), B44 and DWA (a flat DWAB frame packs 11 000:1) are not bounded:
// only their chunks' places in the file are checked.
uint64_t smallestPackedSize(uint8_t compression, uint64_t unpacked) {
  switch (compression) {
    case EXR_COMPRESSION_NONE: return unpacked;
    case EXR_COMPRESSION_RLE: return unpacked / 64;
    case EXR_COMPRESSION_ZIPS:
    case EXR_COMPRESSION_ZIP: return unpacked / 1100;
    default: return 0;
  }
}

// What is wrong with one chunk as its leader states it ("" if nothing): missing, past the file's
// end, or too small for the lines it unpacks to.
std::string chunkProblem(bool read, const exr_chunk_info_t& chunk, uint64_t fileSize, const std::string& which) {
  if (!read) return "the chunk of " + which + " is missing or damaged";
  if (chunk.data_offset > fileSize || chunk.packed_size > fileSize - chunk.data_offset)
    return "the chunk of " + which + " runs past the end of the file";
  if (chunk.packed_size < smallestPackedSize(chunk.compression, chunk.unpacked_size))
    return "the chunk of " + which + " holds " + std::to_string(chunk.packed_size) + " bytes, too few for its " +
           std::to_string(chunk.unpacked_size) + " unpacked bytes";
  return "";
}

struct MemoryExrSource {
  std::string_view bytes;
};

int64_t readFromMemory(exr_const_context_t, void* user, void* buffer, uint64_t size, uint64_t offset,
                       exr_stream_error_func_ptr_t) noexcept {
  const std::string_view bytes = static_cast<MemoryExrSource*>(user)->bytes;
  if (offset >= bytes.size()) return 0;
  const uint64_t n = std::min<uint64_t>(size, bytes.size() - offset);
  std::memcpy(buffer, bytes.data() + offset, n);
  return static_cast<int64_t>(n);
}

int64_t sizeOfMemory(exr_const_context_t, void* user) noexcept {
  return static_cast<int64_t>(static_cast<MemoryExrSource*>(user)->bytes.size());
}

void ignoreMessage(exr_const_context_t, exr_result_t, const char*) noexcept {}

}  // namespace

void checkExrChunksPresent(std::string_view bytes, const std::string& path, const std::string& name) {
  MemoryExrSource source{bytes};
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = &ignoreMessage;
  uint64_t fileSize = bytes.size();
  if (path.empty()) {
    init.user_data = &source;
    init.read_fn = &readFromMemory;
    init.size_fn = &sizeOfMemory;
  } else {
    std::error_code ec;
    fileSize = std::filesystem::file_size(path, ec);
    if (ec) throw InputError(name + ": cannot read OpenEXR (" + ec.message() + ")");
  }
  exr_context_t context = nullptr;
  if (exr_start_read(&context, path.empty() ? "memory.exr" : path.c_str(), &init) != EXR_ERR_SUCCESS) {
    if (context) exr_finish(&context);
    throw InputError(name + ": cannot read OpenEXR (a header OpenEXR's reader refuses)");
  }
  std::string problem;
  exr_storage_t storage = EXR_STORAGE_LAST_TYPE;
  int32_t chunks = 0;
  if (exr_get_storage(context, 0, &storage) != EXR_ERR_SUCCESS || exr_get_chunk_count(context, 0, &chunks) != EXR_ERR_SUCCESS ||
      chunks < 0)
    problem = "no chunk table";
  else if (uint64_t{8} * static_cast<uint64_t>(chunks) * 2 > fileSize)
    problem = "its " + std::to_string(chunks) + " chunks cannot fit in " + std::to_string(fileSize) + " bytes";
  if (problem.empty() && storage == EXR_STORAGE_SCANLINE) {
    exr_attr_box2i_t window{};
    int32_t lines = 0;
    if (exr_get_data_window(context, 0, &window) != EXR_ERR_SUCCESS || exr_get_scanlines_per_chunk(context, 0, &lines) != EXR_ERR_SUCCESS ||
        lines < 1)
      problem = "no data window";
    for (int64_t y = window.min.y; problem.empty() && y <= window.max.y; y += lines) {
      exr_chunk_info_t chunk{};
      const bool read = exr_read_scanline_chunk_info(context, 0, static_cast<int>(y), &chunk) == EXR_ERR_SUCCESS;
      problem = chunkProblem(read, chunk, fileSize, "line " + std::to_string(y));
    }
  } else if (problem.empty() && storage == EXR_STORAGE_TILED) {
    // The level the reader decodes (0, 0), tile by tile, as above.
    int32_t tileW = 0, tileH = 0, levelW = 0, levelH = 0;
    if (exr_get_tile_sizes(context, 0, 0, 0, &tileW, &tileH) != EXR_ERR_SUCCESS ||
        exr_get_level_sizes(context, 0, 0, 0, &levelW, &levelH) != EXR_ERR_SUCCESS || tileW < 1 || tileH < 1)
      problem = "no tiles";
    const int32_t tilesX = tileW > 0 ? static_cast<int32_t>((int64_t{levelW} + tileW - 1) / tileW) : 0;
    const int32_t tilesY = tileH > 0 ? static_cast<int32_t>((int64_t{levelH} + tileH - 1) / tileH) : 0;
    for (int32_t ty = 0; problem.empty() && ty < tilesY; ++ty)
      for (int32_t tx = 0; problem.empty() && tx < tilesX; ++tx) {
        exr_chunk_info_t chunk{};
        const bool read = exr_read_tile_chunk_info(context, 0, tx, ty, 0, 0, &chunk) == EXR_ERR_SUCCESS;
        problem = chunkProblem(read, chunk, fileSize, "tile (" + std::to_string(tx) + ", " + std::to_string(ty) + ")");
      }
  } else if (problem.empty()) {
    problem = "not a single-part scanline or tiled image";
  }
  exr_finish(&context);
  if (!problem.empty()) throw InputError(name + ": cannot read OpenEXR (" + problem + ": the file cannot hold the pixels its header claims)");
}

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
    // Chunks are packed and compressed in parallel, a batch at a time (about 8 MB of pixels, each
    // chunk with its packed, scratch and compressed buffers: some 32 MB, so a large image needs
    // little more memory than its file), and written in order: the same bytes as one at a time.
    size_t lineBytes = 0;
    for (const PackedChannel& c : packedChannels) lineBytes += c.bytes() * static_cast<size_t>(width);
    const size_t chunkBytes = std::max<size_t>(1, lineBytes * static_cast<size_t>(format.lines));
    const int chunkCount = (height + format.lines - 1) / format.lines;
    const int batch = static_cast<int>(std::clamp<size_t>((size_t{8} << 20) / chunkBytes, 1, 64));
    struct ChunkBuffers {
      std::vector<unsigned char> packed, scratch, compressed;
      bool smaller = false;
    };
    std::vector<ChunkBuffers> buffers(static_cast<size_t>(std::min(batch, chunkCount)));
    for (int first = 0; first < chunkCount; first += batch) {
      const int count = std::min(batch, chunkCount - first);
      tbb::parallel_for(0, count, [&](int k) {
        ChunkBuffers& b = buffers[static_cast<size_t>(k)];
        const int y = (first + k) * format.lines;
        packLines(packedChannels, width, y, std::min(height, y + format.lines), b.packed);
        b.smaller = compressExrChunk(format.chunk, b.packed.data(), b.packed.size(), options.zipLevel, b.scratch, b.compressed);
      });
      for (int k = 0; k < count; ++k) {
        const ChunkBuffers& b = buffers[static_cast<size_t>(k)];
        const std::vector<unsigned char>& chunk = b.smaller ? b.compressed : b.packed;
        check(exr_write_scanline_chunk(context, part, (first + k) * format.lines, chunk.data(), chunk.size()), file, "chunk");
      }
      if (options.onLines) options.onLines(std::min(height, (first + count) * format.lines), height);
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
    MemoryExrInput stream(bytes, name);
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
    if (!headerOnly) checkExrChunksPresent(bytes, "", name);
    for (auto it = file.header().begin(); it != file.header().end(); ++it)
      if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) out.text[it.name()] = text->value();
    Imf::FrameBuffer frameBuffer;
    const size_t pixels = static_cast<size_t>(width * height);
    // Every plane to decode, sized before any is allocated.
    int64_t decoded = 0;
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it)
      decoded += !headerOnly && (!channels || channels->count(it.name()));
    if (decoded > 0)
      requireMemory(decoded * width * height * 4, name + ": decoding " + std::to_string(decoded) + " channels of " +
                                                      std::to_string(width) + "x" + std::to_string(height) + " pixels");
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
    if (!headerOnly && decoded > 0) {  // OpenEXR refuses to read into no channel at all
      file.setFrameBuffer(frameBuffer);
      file.readPixels(0, out.height - 1);
    }
  } catch (const InputError&) {
    throw;
  } catch (const MemoryShortage&) {
    throw;  // the machine's, not the file's: exit 5
  } catch (const std::bad_alloc&) {
    throw MemoryShortage(name + ": decoding " + std::to_string(out.width) + "x" + std::to_string(out.height) +
                         " pixels ran out of memory");
  } catch (const std::exception& e) {
    throw InputError(name + ": cannot read OpenEXR (" + oneLine(e.what()) + ")");
  }
  return out;
}

}  // namespace omnicam
