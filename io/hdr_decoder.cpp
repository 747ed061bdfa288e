// Radiance HDR (RGBE, Greg Ward's format): linear float RGB, a scanline at a time from the file or
// memory, flat or with the per-channel run-length coding. Written here because stb_image's reader
// loops forever on a truncated run-length scanline; every loop below advances or fails. The header
// is read as OpenImageIO reads it (FORMAT=32-bit_rle_rgbe required); only the standard orientation
// "-Y height +X width" is accepted.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "errors.h"
#include "image_decoder.h"

namespace omnicam::image_io {

namespace {

constexpr int kMaxHeaderLines = 100;
constexpr size_t kMaxHeaderLine = 4096;

class HdrDecoder final : public ImageDecoder {
 public:
  explicit HdrDecoder(const ImageSource& source) : ImageDecoder(source.name) {
    if (source.inMemory()) {
      bytes_ = source.bytes;
    } else {
      file_.open(source.path, std::ios::binary);
      if (!file_) throw InputError(name_ + ": cannot read image (cannot open the file)");
    }
    readHeader();
    header_.channels = 3;
    header_.type = SampleType::Float;
    header_.colourSpace = "linear";
  }

  std::string_view format() const override { return "hdr"; }

  void readNativeRows(int first, int count, void* samples) override {
    if (first != next_) throw std::logic_error(name_ + ": HDR rows asked for out of order");
    auto* out = static_cast<float*>(samples);
    const size_t width = static_cast<size_t>(header_.width);
    std::vector<unsigned char> rgbe(width * 4);  // channel-major: all R, all G, all B, all E
    for (int r = 0; r < count; ++r) {
      readScanline(first + r, rgbe);
      float* row = out + static_cast<size_t>(r) * width * 3;
      for (size_t i = 0; i < width; ++i) {
        const unsigned char e = rgbe[3 * width + i];
        const float scale = e ? std::ldexp(1.0f, static_cast<int>(e) - (128 + 8)) : 0.0f;
        for (size_t c = 0; c < 3; ++c) row[3 * i + c] = e ? static_cast<float>(rgbe[c * width + i]) * scale : 0.0f;
      }
    }
    next_ = first + count;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw InputError(name_ + ": " + what); }

  // The next byte, or -1 at the end.
  int next() {
    if (file_.is_open()) {
      const auto c = file_.rdbuf()->sbumpc();  // the buffer directly: get() builds a sentry per byte
      return c == std::char_traits<char>::eof() ? -1 : static_cast<unsigned char>(c);
    }
    return at_ < bytes_.size() ? static_cast<unsigned char>(bytes_[at_++]) : -1;
  }

  std::string nextLine() {
    std::string line;
    for (int c = next(); c != '\n'; c = next()) {
      if (c < 0) fail("cannot read image (HDR header ends without its resolution line)");
      if (line.size() == kMaxHeaderLine) fail("cannot read image (HDR header line of more than " + std::to_string(kMaxHeaderLine) + " bytes)");
      line.push_back(static_cast<char>(c));
    }
    return line;
  }

  void readHeader() {
    nextLine();  // "#?RADIANCE": the program that wrote it
    bool rgbeFormat = false;
    for (int n = 0;; ++n) {
      if (n == kMaxHeaderLines) fail("cannot read image (HDR header of more than " + std::to_string(kMaxHeaderLines) + " lines)");
      const std::string line = nextLine();
      if (line.empty()) break;
      if (line == "FORMAT=32-bit_rle_rgbe") rgbeFormat = true;
    }
    if (!rgbeFormat) fail("cannot read image (HDR header without FORMAT=32-bit_rle_rgbe)");
    const std::string resolution = nextLine();
    int height = 0, width = 0, used = 0;
    if (std::sscanf(resolution.c_str(), "-Y %d +X %d%n", &height, &width, &used) != 2 || used != static_cast<int>(resolution.size()))
      fail("cannot read image (HDR resolution " + quote(resolution) + " is not \"-Y <height> +X <width>\")");
    header_.width = width, header_.height = height;
  }

  unsigned char byte(int row) {
    const int c = next();
    if (c < 0) fail("cannot decode image (HDR data ends in scanline " + std::to_string(row) + ")");
    return static_cast<unsigned char>(c);
  }

  // One scanline into `rgbe`, channel-major.
  void readScanline(int row, std::vector<unsigned char>& rgbe) {
    const size_t width = static_cast<size_t>(header_.width);
    unsigned char first[4];
    for (unsigned char& b : first) b = byte(row);
    const bool runLength = width >= 8 && width <= 0x7fff && first[0] == 2 && first[1] == 2 && !(first[2] & 0x80);
    if (!runLength) {
      // Flat: four bytes a pixel, the first already read.
      for (size_t i = 0; i < width; ++i)
        for (size_t c = 0; c < 4; ++c) rgbe[c * width + i] = i == 0 ? first[c] : byte(row);
      return;
    }
    if ((static_cast<size_t>(first[2]) << 8 | first[3]) != width)
      fail("cannot decode image (HDR scanline " + std::to_string(row) + " has the wrong width)");
    for (size_t c = 0; c < 4; ++c) {
      unsigned char* channel = rgbe.data() + c * width;
      for (size_t i = 0; i < width;) {
        const unsigned char code = byte(row);
        const bool run = code > 128;
        const size_t count = run ? code - 128u : code;
        if (count == 0 || count > width - i) fail("cannot decode image (HDR scanline " + std::to_string(row) + " has bad runs)");
        if (run) {
          std::memset(channel + i, byte(row), count);
        } else {
          for (size_t k = 0; k < count; ++k) channel[i + k] = byte(row);
        }
        i += count;
      }
    }
  }

  std::ifstream file_;
  std::string_view bytes_;
  size_t at_ = 0;
  int next_ = 0;
};

}  // namespace

std::unique_ptr<ImageDecoder> openHdrDecoder(const ImageSource& source) { return std::make_unique<HdrDecoder>(source); }

}  // namespace omnicam::image_io
