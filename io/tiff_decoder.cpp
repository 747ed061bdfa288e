// TIFF through libtiff. Grey and RGB images of 8-, 16- or 32-bit samples are read as stored
// (strips of interleaved channels a row at a time; tiles and separate planes whole); any other
// layout libtiff can show as RGBA (palette, CMYK, YCbCr, 1-bit, min-is-white) as its 8-bit RGBA.
#include <tiffio.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

#include "errors.h"
#include "image_decoder.h"
#include "memory_budget.h"

namespace omnicam::image_io {

namespace {

// The most libtiff may allocate at once (its strip and tile buffers, tag arrays): a forged header
// is refused, a real strip or tile is far smaller.
constexpr tmsize_t kMaxTiffAllocation = tmsize_t{256} << 20;

struct TiffMessage {
  char text[200] = "no details";
};

// libtiff's per-file handler: the last error kept, warnings dropped, nothing on stderr.
int keepTiffError(TIFF*, void* user, const char*, const char* format, va_list args) {
  std::vsnprintf(static_cast<TiffMessage*>(user)->text, sizeof(TiffMessage::text), format, args);
  return 1;
}
int dropTiffWarning(TIFF*, void*, const char*, const char*, va_list) { return 1; }

// An image in memory as libtiff's client I/O.
struct MemoryFile {
  std::string_view bytes;
  toff_t at = 0;
};
tmsize_t readMemory(thandle_t handle, void* out, tmsize_t n) {
  auto* file = static_cast<MemoryFile*>(handle);
  if (n < 0 || file->at >= file->bytes.size()) return 0;
  const size_t count = std::min<size_t>(static_cast<size_t>(n), file->bytes.size() - file->at);
  std::memcpy(out, file->bytes.data() + file->at, count);
  file->at += count;
  return static_cast<tmsize_t>(count);
}
tmsize_t writeNothing(thandle_t, void*, tmsize_t) { return 0; }
toff_t seekMemory(thandle_t handle, toff_t offset, int whence) {
  auto* file = static_cast<MemoryFile*>(handle);
  const toff_t base = whence == SEEK_CUR ? file->at : whence == SEEK_END ? file->bytes.size() : 0;
  file->at = base + offset;
  return file->at;
}
int closeNothing(thandle_t) { return 0; }
toff_t sizeOfMemory(thandle_t handle) { return static_cast<MemoryFile*>(handle)->bytes.size(); }
int mapNothing(thandle_t, void**, toff_t*) { return 0; }
void unmapNothing(thandle_t, void*, toff_t) {}

class TiffDecoder final : public ImageDecoder {
 public:
  explicit TiffDecoder(const ImageSource& source) : ImageDecoder(source.name) {
    const std::unique_ptr<TIFFOpenOptions, void (*)(TIFFOpenOptions*)> options(TIFFOpenOptionsAlloc(), TIFFOpenOptionsFree);
    if (!options) throw std::bad_alloc();
    TIFFOpenOptionsSetErrorHandlerExtR(options.get(), keepTiffError, &message_);
    TIFFOpenOptionsSetWarningHandlerExtR(options.get(), dropTiffWarning, nullptr);
    TIFFOpenOptionsSetMaxSingleMemAlloc(options.get(), kMaxTiffAllocation);
    if (source.inMemory()) {
      memory_.bytes = source.bytes;
      tiff_.reset(TIFFClientOpenExt("memory.tif", "r", &memory_, readMemory, writeNothing, seekMemory, closeNothing,
                                    sizeOfMemory, mapNothing, unmapNothing, options.get()));
    } else {
      tiff_.reset(TIFFOpenExt(source.path.c_str(), "r", options.get()));
    }
    if (!tiff_) fail("cannot read image");
    readHeader();
  }

  std::string_view format() const override { return "tiff"; }

  int64_t wholeBytes() const override {
    return decodesWhole() ? header_.width * header_.height * header_.channels * static_cast<int64_t>(sampleBytes(header_.type)) : 0;
  }

  void readNativeRows(int first, int count, void* samples) override {
    if (first != next_) throw std::logic_error(name_ + ": TIFF rows asked for out of order");
    auto* out = static_cast<unsigned char*>(samples);
    const size_t rowBytes = static_cast<size_t>(header_.width) * header_.channels * sampleBytes(header_.type);
    if (decodesWhole()) {
      if (whole_.empty()) readWhole(rowBytes);
      std::memcpy(out, whole_.data() + static_cast<size_t>(first) * rowBytes, static_cast<size_t>(count) * rowBytes);
    } else {
      if (static_cast<tmsize_t>(rowBytes) != TIFFScanlineSize(tiff_.get())) fail("cannot decode image");
      for (int r = 0; r < count; ++r)
        if (TIFFReadScanline(tiff_.get(), out + static_cast<size_t>(r) * rowBytes, static_cast<uint32_t>(first + r), 0) < 0)
          fail("cannot decode image");
    }
    next_ = first + count;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(name_ + ": " + what + " (TIFF read error: " + message_.text + ")");
  }

  // Tiles, separate planes and libtiff's RGBA conversion are decoded whole at the first read.
  bool decodesWhole() const { return asRgba_ || separate_ || TIFFIsTiled(tiff_.get()); }

  template <typename T>
  T field(ttag_t tag, T fallback) const {
    T value = fallback;
    return TIFFGetFieldDefaulted(tiff_.get(), tag, &value) == 1 ? value : fallback;
  }

  void readHeader() {
    TIFF* tiff = tiff_.get();
    const uint32_t width = field<uint32_t>(TIFFTAG_IMAGEWIDTH, 0), height = field<uint32_t>(TIFFTAG_IMAGELENGTH, 0);
    header_.width = width, header_.height = height;
    const uint16_t samples = field<uint16_t>(TIFFTAG_SAMPLESPERPIXEL, 1), bits = field<uint16_t>(TIFFTAG_BITSPERSAMPLE, 1);
    const uint16_t format = field<uint16_t>(TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_UINT);
    const uint16_t planar = field<uint16_t>(TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    const uint16_t photometric = field<uint16_t>(TIFFTAG_PHOTOMETRIC, samples >= 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK);
    // VOID: "untyped", which old writers meant as unsigned.
    const bool integer = (format == SAMPLEFORMAT_UINT || format == SAMPLEFORMAT_VOID) && (bits == 8 || bits == 16 || bits == 32);
    const bool real = format == SAMPLEFORMAT_IEEEFP && bits == 32;
    const bool asStored = (photometric == PHOTOMETRIC_MINISBLACK || photometric == PHOTOMETRIC_RGB) && (integer || real);
    separate_ = planar == PLANARCONFIG_SEPARATE && samples > 1;
    if (format != SAMPLEFORMAT_UINT && format != SAMPLEFORMAT_VOID && !real)
      throw InputError(name_ + ": cannot read image (TIFF of " + std::to_string(bits) + "-bit " +
                       (format == SAMPLEFORMAT_INT ? "signed" : format == SAMPLEFORMAT_IEEEFP ? "float" : "other") +
                       " samples: unsigned integers of 8, 16 or 32 bits and 32-bit floats are read)");
    if (!asStored) {
      char problem[1024] = "";
      if (!TIFFRGBAImageOK(tiff, problem))
        throw InputError(name_ + ": cannot read image (TIFF layout not read: " + problem + ")");
      asRgba_ = true;
      header_.channels = 4;
      header_.type = SampleType::Uint8;
      header_.alphaChannel = 3;
      header_.unassociatedAlpha = true;  // made straight by readRgba
      return;
    }
    header_.channels = samples;
    header_.type = real ? SampleType::Float : bits == 8 ? SampleType::Uint8 : bits == 16 ? SampleType::Uint16 : SampleType::Uint32;
    // Alpha as OpenImageIO reads it: the fourth channel by default, then as ExtraSamples says.
    header_.alphaChannel = samples >= 4 ? 3 : -1;
    uint16_t extras = 0;
    uint16_t* kinds = nullptr;
    if (TIFFGetField(tiff, TIFFTAG_EXTRASAMPLES, &extras, &kinds) == 1 && kinds) {
      const int colourChannels = photometric == PHOTOMETRIC_RGB ? 3 : 1;
      for (int i = 0, c = colourChannels; i < extras && c < samples; ++i, ++c) {
        if (kinds[i] == EXTRASAMPLE_ASSOCALPHA) {
          header_.alphaChannel = c;
        } else if (kinds[i] == EXTRASAMPLE_UNASSALPHA) {
          header_.alphaChannel = c;
          header_.unassociatedAlpha = true;
        } else if (header_.alphaChannel == c) {
          header_.alphaChannel = -1;  // an extra channel that is not alpha
        }
      }
    }
  }

  void readWhole(size_t rowBytes) {
    requireMemory(wholeBytes(), name_ + ": decoding a " + std::to_string(header_.width) + "x" + std::to_string(header_.height) +
                                    " TIFF whole (tiles, planes or a converted layout)");
    whole_.resize(rowBytes * static_cast<size_t>(header_.height));
    if (asRgba_) return readRgba();
    const size_t planes = separate_ ? static_cast<size_t>(header_.channels) : 1;
    // Plane by plane (one plane when the channels are together), each scattered into whole_.
    const size_t pixelBytes = rowBytes / static_cast<size_t>(header_.width), planePixelBytes = pixelBytes / planes;
    const auto place = [&](size_t plane, uint32_t y, uint32_t x, const unsigned char* from, uint32_t columns) {
      unsigned char* to = whole_.data() + size_t{y} * rowBytes + size_t{x} * pixelBytes + plane * planePixelBytes;
      if (planes == 1) return (void)std::memcpy(to, from, size_t{columns} * pixelBytes);
      for (uint32_t i = 0; i < columns; ++i) std::memcpy(to + i * pixelBytes, from + i * planePixelBytes, planePixelBytes);
    };
    if (TIFFIsTiled(tiff_.get())) readTiles(planes, planePixelBytes, place);
    else readStrips(planes, planePixelBytes, place);
  }

  // libtiff's RGBA: 8-bit, alpha associated; made straight, as PNG's, since image.cpp associates
  // integer images' alpha itself.
  void readRgba() {
    const auto width = static_cast<uint32_t>(header_.width), height = static_cast<uint32_t>(header_.height);
    // Each pixel is ABGR in a 32-bit word: on this little-endian machine, R, G, B, A in memory.
    if (!TIFFReadRGBAImageOriented(tiff_.get(), width, height, reinterpret_cast<uint32_t*>(whole_.data()), ORIENTATION_TOPLEFT, 0))
      fail("cannot decode image");
    for (size_t p = 0; p < whole_.size(); p += 4) {
      const unsigned alpha = whole_[p + 3];
      if (alpha == 0 || alpha == 255) continue;
      for (size_t c = 0; c < 3; ++c) whole_[p + c] = static_cast<unsigned char>(std::min(255u, (whole_[p + c] * 255u + alpha / 2) / alpha));
    }
  }

  template <typename Place>
  void readStrips(size_t planes, size_t planePixelBytes, const Place& place) {
    TIFF* tiff = tiff_.get();
    const auto width = static_cast<uint32_t>(header_.width), height = static_cast<uint32_t>(header_.height);
    std::vector<unsigned char> line(static_cast<size_t>(std::max<tmsize_t>(TIFFScanlineSize(tiff), 0)));
    if (line.size() != size_t{width} * planePixelBytes) fail("cannot decode image");
    for (size_t plane = 0; plane < planes; ++plane)
      for (uint32_t y = 0; y < height; ++y) {
        if (TIFFReadScanline(tiff, line.data(), y, static_cast<uint16_t>(plane)) < 0) fail("cannot decode image");
        place(plane, y, 0, line.data(), width);
      }
  }

  template <typename Place>
  void readTiles(size_t planes, size_t planePixelBytes, const Place& place) {
    TIFF* tiff = tiff_.get();
    const auto width = static_cast<uint32_t>(header_.width), height = static_cast<uint32_t>(header_.height);
    const uint32_t tileW = field<uint32_t>(TIFFTAG_TILEWIDTH, 0), tileH = field<uint32_t>(TIFFTAG_TILELENGTH, 0);
    // Tiles no larger than the image rounded up to TIFF's 16-pixel tile multiple, or 1024: a forged
    // tile size would otherwise size the buffer below.
    const auto bound = [](uint32_t side) { return std::max<uint64_t>(1024, (uint64_t{side} + 15) / 16 * 16); };
    if (tileW == 0 || tileH == 0 || tileW > bound(width) || tileH > bound(height))
      throw InputError(name_ + ": cannot decode image (TIFF tiles of " + std::to_string(tileW) + "x" + std::to_string(tileH) +
                       " for a " + std::to_string(width) + "x" + std::to_string(height) + " image)");
    const tmsize_t tileBytes = TIFFTileSize(tiff);
    if (tileBytes != static_cast<tmsize_t>(size_t{tileW} * tileH * planePixelBytes)) fail("cannot decode image");
    // The sides alone do not bound the area: a 1 x 16384 image may claim 1024 x 16384 tiles.
    if (tileBytes > std::max<int64_t>(wholeBytes(), kMaxTiffAllocation))
      throw InputError(name_ + ": cannot decode image (TIFF tiles of " + std::to_string(tileBytes) + " bytes for a " +
                       std::to_string(width) + "x" + std::to_string(height) + " image)");
    requireMemory(tileBytes, name_ + ": a TIFF tile");
    std::vector<unsigned char> tile(static_cast<size_t>(tileBytes));
    for (size_t plane = 0; plane < planes; ++plane)
      for (uint32_t y = 0; y < height; y += tileH)
        for (uint32_t x = 0; x < width; x += tileW) {
          if (TIFFReadTile(tiff, tile.data(), x, y, 0, static_cast<uint16_t>(plane)) < 0) fail("cannot decode image");
          const uint32_t rows = std::min(tileH, height - y), columns = std::min(tileW, width - x);
          for (uint32_t r = 0; r < rows; ++r) place(plane, y + r, x, tile.data() + size_t{r} * tileW * planePixelBytes, columns);
        }
  }

  TiffMessage message_;
  MemoryFile memory_;
  std::unique_ptr<TIFF, void (*)(TIFF*)> tiff_{nullptr, &TIFFClose};
  bool asRgba_ = false, separate_ = false;
  int next_ = 0;
  std::vector<unsigned char> whole_;
};

}  // namespace

std::unique_ptr<ImageDecoder> openTiffDecoder(const ImageSource& source) { return std::make_unique<TiffDecoder>(source); }

}  // namespace omnicam::image_io
