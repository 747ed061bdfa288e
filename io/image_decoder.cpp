#include "image_decoder.h"

#include <cstring>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <limits>
#include <vector>

#include "errors.h"
#include "input_limits.h"

namespace omnicam::image_io {

size_t sampleBytes(SampleType type) {
  switch (type) {
    case SampleType::Uint8: return 1;
    case SampleType::Uint16: return 2;
    default: return 4;
  }
}

namespace {

template <typename T>
void scaleToFloats(const T* codes, size_t n, float* values) {
  // OpenImageIO's conversion: the code times the reciprocal of the largest code, in float.
  constexpr float scale = 1.0f / static_cast<float>(std::numeric_limits<T>::max());
  for (size_t i = 0; i < n; ++i) values[i] = static_cast<float>(codes[i]) * scale;
}

}  // namespace

ImageSource ImageSource::file(const std::string& path) { return {path, {}, showPath(path)}; }

std::vector<float> ImageDecoder::readAllRows() {
  std::vector<float> values(static_cast<size_t>(header_.width * header_.height) * static_cast<size_t>(header_.channels));
  readRows(0, static_cast<int>(header_.height), values.data());
  return values;
}

void ImageDecoder::readRows(int first, int count, float* values) {
  const size_t n = static_cast<size_t>(header_.width) * static_cast<size_t>(count) * static_cast<size_t>(header_.channels);
  if (header_.type == SampleType::Float) {
    readNativeRows(first, count, values);
    return;
  }
  std::vector<unsigned char> native(n * sampleBytes(header_.type));
  readNativeRows(first, count, native.data());
  switch (header_.type) {
    case SampleType::Uint8: scaleToFloats(native.data(), n, values); break;
    case SampleType::Uint16: scaleToFloats(reinterpret_cast<const uint16_t*>(native.data()), n, values); break;
    default: scaleToFloats(reinterpret_cast<const uint32_t*>(native.data()), n, values); break;
  }
}

void checkHeader(const ImageHeader& header, const std::string& name) {
  if (header.width < 1 || header.height < 1)
    throw InputError(name + ": image has no pixels (" + std::to_string(header.width) + "x" + std::to_string(header.height) + ")");
  if (header.width > limits::kMaxImageDimension || header.height > limits::kMaxImageDimension ||
      static_cast<int64_t>(header.width) * header.height > limits::kMaxImagePixels)
    throw InputError(name + ": image is " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                     " pixels; the limit is " + std::to_string(limits::kMaxImageDimension) + " per side and " +
                     std::to_string(limits::kMaxImagePixels) + " in all");
  if (header.channels < 1 || header.channels > 16)
    throw InputError(name + ": image has " + std::to_string(header.channels) + " channels (1 to 16 are read)");
  // One rule with the frame-file reader (exr_channels.h): pixels start at (0, 0).
  if (header.originX != 0 || header.originY != 0)
    throw InputError(name + ": the image's data window does not start at pixel (0, 0)");
}

namespace {

// The first bytes of the source: all a format is told by.
std::string signatureOf(const ImageSource& source) {
  constexpr size_t kSignatureBytes = 16;
  if (source.inMemory()) return std::string(source.bytes.substr(0, kSignatureBytes));
  // Only regular files: a FIFO or a device (/dev/zero) would be read forever.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(source.path, ec))
    throw InputError(source.name + ": cannot read image (" +
                     (std::filesystem::exists(source.path, ec) ? "not a regular file" : "no such file") + ")");
  std::ifstream in(source.path, std::ios::binary);
  if (!in) throw InputError(source.name + ": cannot read image (cannot open the file)");
  std::string head(kSignatureBytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return head;
}

// Why an image omnicam does not read is refused: formats users meet (POV-Ray's +FP and +FB
// outputs, web images) named by their first bytes, so the message says what the file is.
std::string unreadFormatOf(std::string_view head) {
  using namespace std::string_view_literals;
  if (head.empty()) return "the file is empty";
  std::string format;
  bool povrayWrites = false;  // +FB, +FP: POV-Ray can write PNG instead
  if (head.starts_with("GIF87a"sv) || head.starts_with("GIF89a"sv)) format = "a GIF file";
  else if (head.starts_with("BM"sv) && head.size() >= 14) format = "a BMP file", povrayWrites = true;
  else if (head.size() >= 3 && head[0] == 'P' && head[1] >= '1' && head[1] <= '7' && std::isspace(static_cast<unsigned char>(head[2])))
    format = "a Netpbm (PBM, PGM, PPM or PAM) file", povrayWrites = true;
  else if (head.starts_with("RIFF"sv) && head.size() >= 12 && head.substr(8, 4) == "WEBP"sv) format = "a WebP file";
  else if (head.starts_with("8BPS"sv)) format = "a Photoshop file";
  else if (head.starts_with("SDPX"sv) || head.starts_with("XPDS"sv)) format = "a DPX file";
  const std::string read = "omnicam reads PNG, JPEG, TIFF, OpenEXR and Radiance HDR";
  return format.empty() ? "not a PNG, JPEG, TIFF, OpenEXR or Radiance HDR file"
                        : format + "; " + read + ": convert it (oiiotool, ImageMagick)" +
                              (povrayWrites ? ", or have POV-Ray write PNG (+FN)" : "");
}

std::unique_ptr<ImageDecoder> openByFormat(const ImageSource& source) {
  using namespace std::string_view_literals;
  const std::string bytes = signatureOf(source);
  const std::string_view head = bytes;
  if (head.starts_with("\x89PNG\r\n\x1a\n"sv)) return openPngDecoder(source);
  if (head.starts_with("\xFF\xD8\xFF"sv)) return openJpegDecoder(source);
  if (head.starts_with("\x76\x2f\x31\x01"sv)) return openExrDecoder(source);
  if (head.starts_with("II*\0"sv) || head.starts_with("MM\0*"sv) || head.starts_with("II+\0"sv) || head.starts_with("MM\0+"sv))
    return openTiffDecoder(source);
  if (head.starts_with("#?RADIANCE"sv) || head.starts_with("#?RGBE"sv)) return openHdrDecoder(source);
  throw InputError(source.name + ": cannot read image (" + unreadFormatOf(head) + ")");
}

}  // namespace

std::unique_ptr<ImageDecoder> openImageDecoder(const ImageSource& source) {
  auto decoder = openByFormat(source);
  checkHeader(decoder->header(), decoder->name());
  return decoder;
}

}  // namespace omnicam::image_io
