// PNG through libpng's low-level API: the codes as stored, the colour space as declared, no gamma
// conversion (image.cpp applies the declared curve exactly). libpng reports errors by longjmp, so
// every call into it runs inside pngGuarded, whose work holds nothing that needs destroying.
#include "png_codec.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
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

// libpng's last error, kept in a fixed buffer: nothing may throw inside libpng's callbacks.
struct PngMessage {
  char text[200] = "no details";
};

[[noreturn]] void onPngError(png_structp png, png_const_charp message) {
  auto* kept = static_cast<PngMessage*>(png_get_error_ptr(png));
  std::snprintf(kept->text, sizeof kept->text, "%s", message ? message : "no details");
  png_longjmp(png, 1);
}

void onPngWarning(png_structp, png_const_charp) {}  // warnings are not failures; stderr stays quiet

// Runs `work` (calls into libpng only) and says whether libpng completed it.
template <typename Work>
bool pngGuarded(png_structp png, const Work& work) {
  if (setjmp(png_jmpbuf(png))) return false;
  work();
  return true;
}

struct MemoryReader {
  std::string_view bytes;
  size_t at = 0;
};

void readFromMemory(png_structp png, png_bytep out, png_size_t n) {
  auto* reader = static_cast<MemoryReader*>(png_get_io_ptr(png));
  if (n > reader->bytes.size() - reader->at) png_error(png, "unexpected end of data");
  std::memcpy(out, reader->bytes.data() + reader->at, n);
  reader->at += n;
}

// OpenImageIO's name for a PNG's declared colour space: an sRGB chunk, else gAMA's exponent
// rounded to hundredths ("linear" for 1), else sRGB.
std::string colourSpaceOf(png_structp png, png_infop info) {
  int intent = 0;
  double fileGamma = 0.0;
  if (png_get_sRGB(png, info, &intent)) return "sRGB";
  if (png_get_gAMA(png, info, &fileGamma) && fileGamma > 0.0) {
    float g = static_cast<float>(1.0 / fileGamma);
    g = static_cast<float>(std::round(100.0 * g) / 100.0);
    if (g == 1.0f) return "linear";
    char name[32];
    std::snprintf(name, sizeof name, "Gamma%.2g", static_cast<double>(g));
    return name;
  }
  return "sRGB";
}

class PngDecoder final : public ImageDecoder {
 public:
  explicit PngDecoder(const ImageSource& source) : ImageDecoder(source.name) {
    read_.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &message_, onPngError, onPngWarning);
    if (read_.png) read_.info = png_create_info_struct(read_.png);
    if (!read_.png || !read_.info) throw std::bad_alloc();
    if (source.inMemory()) {
      memory_.bytes = source.bytes;
      png_set_read_fn(read_.png, &memory_, readFromMemory);
    } else {
      file_.reset(std::fopen(source.path.c_str(), "rb"));
      if (!file_) throw InputError(name_ + ": cannot read image (cannot open the file)");
      png_init_io(read_.png, file_.get());
    }
    readHeader();
  }

  std::string_view format() const override { return "png"; }

  int64_t wholeBytes() const override { return passes_ > 1 ? static_cast<int64_t>(rowBytes_) * header_.height : 0; }

  void readNativeRows(int first, int count, void* samples) override {
    if (first != next_) throw std::logic_error(name_ + ": PNG rows asked for out of order");
    auto* out = static_cast<unsigned char*>(samples);
    if (passes_ > 1) {
      // Interlaced: every pass covers the whole image, so it is decoded whole, once.
      if (whole_.empty()) readWhole();
      std::memcpy(out, whole_.data() + static_cast<size_t>(first) * rowBytes_, static_cast<size_t>(count) * rowBytes_);
    } else {
      png_structp png = read_.png;
      const size_t rowBytes = rowBytes_;
      if (!pngGuarded(png, [&] {
            for (int r = 0; r < count; ++r) png_read_row(png, out + static_cast<size_t>(r) * rowBytes, nullptr);
          }))
        fail("cannot decode image");
    }
    next_ = first + count;
  }

 private:
  struct ReadStructs {
    png_structp png = nullptr;
    png_infop info = nullptr;
    ~ReadStructs() {
      if (png) png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    }
  };

  [[noreturn]] void fail(const char* what) const {
    throw InputError(name_ + ": " + what + " (PNG read error: " + message_.text + ")");
  }

  void readHeader() {
    png_structp png = read_.png;
    png_infop info = read_.info;
    int passes = 1;
    if (!pngGuarded(png, [&] {
          png_read_info(png, info);
          png_set_expand(png);  // palette to RGB, 1/2/4-bit grey to 8 bits, tRNS to alpha
          png_set_swap(png);    // 16-bit samples in this machine's (little-endian) order
          passes = png_set_interlace_handling(png);
          png_read_update_info(png, info);
        }))
      fail("cannot read image");
    passes_ = passes;
    header_.width = png_get_image_width(png, info);
    header_.height = png_get_image_height(png, info);
    header_.channels = png_get_channels(png, info);
    header_.type = png_get_bit_depth(png, info) == 16 ? SampleType::Uint16 : SampleType::Uint8;
    header_.colourSpace = colourSpaceOf(png, info);
    header_.originX = png_get_x_offset_pixels(png, info);
    header_.originY = png_get_y_offset_pixels(png, info);
    if (header_.channels == 2 || header_.channels == 4) {
      header_.alphaChannel = header_.channels - 1;
      header_.unassociatedAlpha = true;  // PNG stores straight alpha
    }
    rowBytes_ = png_get_rowbytes(png, info);
  }

  void readWhole() {
    requireMemory(wholeBytes(), name_ + ": decoding an interlaced " + std::to_string(header_.width) + "x" +
                                    std::to_string(header_.height) + " PNG whole");
    whole_.resize(rowBytes_ * static_cast<size_t>(header_.height));
    std::vector<png_bytep> rows(static_cast<size_t>(header_.height));
    for (size_t r = 0; r < rows.size(); ++r) rows[r] = whole_.data() + r * rowBytes_;
    png_structp png = read_.png;
    png_bytepp rowPointers = rows.data();
    if (!pngGuarded(png, [&] { png_read_image(png, rowPointers); })) fail("cannot decode image");
  }

  PngMessage message_;
  MemoryReader memory_;
  std::unique_ptr<FILE, int (*)(FILE*)> file_{nullptr, &std::fclose};
  ReadStructs read_;  // after file_: destroyed before the file is closed
  int passes_ = 1, next_ = 0;
  size_t rowBytes_ = 0;
  std::vector<unsigned char> whole_;
};

struct PngSink {
  std::vector<unsigned char> bytes;
  bool outOfMemory = false;
};

void writeToVector(png_structp png, png_bytep data, png_size_t n) {
  auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
  try {
    sink->bytes.insert(sink->bytes.end(), data, data + n);
  } catch (const std::bad_alloc&) {
    sink->outOfMemory = true;
  }
  if (sink->outOfMemory) png_error(png, "out of memory");  // outside the handler: longjmp must not leave a catch
}

void flushNothing(png_structp) {}

struct WriteStructs {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~WriteStructs() {
    if (png) png_destroy_write_struct(&png, info ? &info : nullptr);
  }
};

}  // namespace

std::unique_ptr<ImageDecoder> openPngDecoder(const ImageSource& source) { return std::make_unique<PngDecoder>(source); }

std::vector<unsigned char> encodePng(const std::string& name, int width, int height, int channels, int bitDepth,
                                     const void* samples, bool srgb) {
  static constexpr int kColourTypes[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGBA};
  if (channels < 1 || channels > 4 || (bitDepth != 8 && bitDepth != 16) || width < 1 || height < 1)
    throw std::logic_error("encodePng: 1 to 4 channels of 8 or 16 bits, at least one pixel");
  PngMessage message;
  PngSink sink;
  WriteStructs structs;
  structs.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &message, onPngError, onPngWarning);
  if (structs.png) structs.info = png_create_info_struct(structs.png);
  if (!structs.png || !structs.info) throw std::bad_alloc();
  png_structp png = structs.png;
  png_infop info = structs.info;
  const size_t rowBytes = static_cast<size_t>(width) * static_cast<size_t>(channels) * static_cast<size_t>(bitDepth / 8);
  const auto* rows = static_cast<const unsigned char*>(samples);
  const bool written = pngGuarded(png, [&] {
    png_set_write_fn(png, &sink, writeToVector, flushNothing);
    png_set_compression_level(png, 1);  // sequences: speed over the last few percent of size
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);  // one cheap filter, not libpng's five-way trial
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), bitDepth,
                 kColourTypes[channels - 1], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (srgb) png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    if (bitDepth == 16) png_set_swap(png);
    for (int r = 0; r < height; ++r) png_write_row(png, rows + static_cast<size_t>(r) * rowBytes);
    png_write_end(png, nullptr);
  });
  if (sink.outOfMemory) throw std::bad_alloc();
  if (!written) throw OutputError(showPath(name) + ": cannot encode PNG (" + message.text + ")");
  return std::move(sink.bytes);
}

}  // namespace omnicam::image_io
