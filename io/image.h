#pragma once
// Linear RGBA float images with associated (premultiplied) alpha, and their files.
// PNG/JPEG are sRGB-encoded 8-bit on disk; EXR is linear half/float (docs/conventions.md §2).
#include <functional>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace omnicam {

struct ExrChannels;  // exr_channels.h

struct ImageRGBA {
  int width = 0, height = 0;
  std::vector<float> pixels;  // row-major, 4 floats per pixel, v down

  ImageRGBA() = default;
  ImageRGBA(int w, int h) : width(w), height(h), pixels(static_cast<size_t>(w) * h * 4, 0.0f) {}
  float* at(int i, int j) { return &pixels[(static_cast<size_t>(j) * width + i) * 4]; }
  const float* at(int i, int j) const { return &pixels[(static_cast<size_t>(j) * width + i) * 4]; }
};

float srgbToLinear(float encoded);
float linearToSrgb(float linear);

// Rec. 709 luminance of linear RGB, in T's arithmetic: float for the filters' per-pixel weights,
// double for statistics over a frame.
template <class T = float>
T luminance(const float* rgb) {
  return T(0.2126) * rgb[0] + T(0.7152) * rgb[1] + T(0.0722) * rgb[2];
}

// Reads a PNG, JPEG, TIFF, OpenEXR or Radiance HDR file (told by its first bytes, not its name) as
// linear premultiplied RGBA; missing alpha becomes 1.
// Integer images are decoded by the colour space they declare (sRGB unless tagged linear or
// with a gamma), whatever their bit depth; float images are linear. The header is checked
// against limits::kMaxImageDimension / kMaxImagePixels before any pixel is read. Throws
// InputError naming the file.
ImageRGBA readImage(const std::string& path);
// What readImage needs to decode `path`, from its header alone (checked as readImage checks it).
int64_t imageDecodeBytes(const std::string& path);
// The same for an image held in memory (any of the formats readImage reads, told by its
// signature); `name` is used in errors.
ImageRGBA readImageFromMemory(const unsigned char* data, size_t size, const std::string& name);
// readImageFromMemory for an image whose values are data (a scene's texture, its environment's
// light), where a NaN or ±∞ read as 0 would pass unnoticed: InputError "<name>: N pixels hold a
// value that is not finite (NaN or ±∞)" instead.
ImageRGBA readFiniteImageFromMemory(const unsigned char* data, size_t size, const std::string& name);

// An image read a band of rows at a time, decoded as readImage decodes it whole (the same colour
// space and alpha, the same floats): for work that needs only a few rows at once, in memory that
// does not grow with the height, except where the format cannot be read by rows (an interlaced
// PNG, a tiled or planar TIFF, a progressive JPEG: wholeBytes()).
// The header is checked as readImage checks it; InputError naming the file.
class ImageRowReader {
 public:
  static ImageRowReader openFile(const std::string& path);
  // An image in memory (told by its signature); `data` must outlive the reader.
  static ImageRowReader openMemory(const unsigned char* data, size_t size, const std::string& name);
  ImageRowReader(ImageRowReader&&) noexcept;
  ImageRowReader& operator=(ImageRowReader&&) noexcept;
  ~ImageRowReader();

  int width() const;
  int height() const;
  // Memory one row takes while it is decoded: the floats of every channel and the RGBA.
  int64_t rowBytes() const;
  // Memory held whatever the band: the whole image, for files that cannot be read by rows.
  int64_t wholeBytes() const;
  // Rows [first, first + count) as readImage's pixels (linear premultiplied RGBA), into `rgba`
  // (width × count × 4 floats). Rows are read top to bottom: `first` is where the last read ended.
  void readRows(int first, int count, float* rgba);
  // The rows not read yet, into an image of the whole size (rows already read stay 0).
  ImageRGBA readRemaining();
  // Pixels read so far with a colour or alpha value that is not finite (NaN, ±∞): readImage
  // decodes such a value as 0, so whoever judges the pixels asks here.
  long nonFinitePixels() const;
  // OpenEXR's channel names in the order they are read (empty for other formats).
  const std::vector<std::string>& channelNames() const;
  // Whether what is read as colour is an image's colour: always for PNG, JPEG, TIFF and HDR; for
  // OpenEXR when the channels read as colour (the first three in OpenImageIO's order, or the first
  // of one or two) are named R, G, B (Red, Green, Blue, in any case and layer), or for one channel
  // Y or a colour. A table of data (rays' origin.X …, normals' X, Y, Z, a depth map's Z) is not,
  // though it reads.
  bool holdsColour() const;
  // Whether a channel is read as alpha (one the file names so, or the last of two or four);
  // without one, alpha reads as 1 everywhere.
  bool holdsAlpha() const;
  // InputError "<file>: not a colour image: its channels are …" unless holdsColour().
  void requireColour() const;

 private:
  struct State;
  explicit ImageRowReader(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

// The image as a PNG holds it: sRGB 8-bit codes with straight alpha, RGBA, row by row. The same
// codes reach a live sensor's rgb8 messages (ros/live_sensor.h).
std::vector<unsigned char> srgb8Codes(const ImageRGBA& image);

// The 8-bit codes of an 8-bit image in memory (PNG, JPEG, TIFF) as RGB, as stored: no colour
// conversion, alpha dropped, grey repeated; rows top to bottom. InputError "<name>: not an 8-bit
// image" for deeper ones.
std::vector<unsigned char> readRgb8Codes(std::string_view bytes, const std::string& name, int& width, int& height);

// 8-bit RGB codes (width × height × 3, rows top to bottom) as a JPEG of `quality` (1 to 100)
// decodes them: what a camera's compression leaves. libjpeg's defaults, which OpenCV's
// imencode / imdecode use too (tested against them).
std::vector<unsigned char> jpegCompressed(const std::vector<unsigned char>& rgb, int width, int height, int quality);

// The bytes of .png (sRGB 8-bit, straight alpha) or .exr (linear float, associated alpha,
// byte-identical for identical pixels). Throws InputError for another extension.
std::vector<unsigned char> encodeImage(const std::string& path, const ImageRGBA& image);
// encodeImage, then writeBytesAtomically (atomic_file.h): OutputError if it cannot be written.
void writeImageAtomic(const std::string& path, const ImageRGBA& image);
bool isSupportedImageOutput(const std::string& path);

// Images whose pixels are data, not colour (depth, normals, ids): no colour space, no alpha,
// values stored exactly.
struct DataImage {
  int width = 0, height = 0, channels = 1;
  std::vector<float> values;  // row-major, `channels` per pixel
};
// A float32 OpenEXR (zip, no DateTime: identical values give identical bytes). Channel names:
// "Z" for one channel, "X", "Y", "Z" for three.
// `values`: width × height × channels floats, row-major. Half stores 16-bit floats (relative
// error ≤ 2⁻¹¹), float 32-bit ones exactly.
enum class ExrPrecision { Float, Half };
std::vector<unsigned char> encodeDataExr(const std::string& path, int width, int height, int channels,
                                         const float* values, ExrPrecision precision = ExrPrecision::Float);
// The same with the channels named (OpenEXR's "layer.channel" names allowed), one per value;
// `onLines(done, total)` as lines are encoded.
std::vector<unsigned char> encodeDataExr(const std::string& path, int width, int height,
                                         const std::vector<std::string>& channelNames, const float* values,
                                         ExrPrecision precision = ExrPrecision::Float,
                                         const std::function<void(int linesDone, int lines)>& onLines = {});
// A 16-bit single-channel PNG holding `values` exactly.
std::vector<unsigned char> encodeUint16Png(const std::string& path, int width, int height,
                                           const std::vector<uint16_t>& values);
// Readers for the two; InputError naming the file for anything else (wrong channel count or type).
DataImage readDataExr(const std::string& path);
// The named float channels of any OpenEXR, in the order asked for (OpenEXR stores them sorted by
// name), exactly; InputError naming the channels the file has for one it lacks, and for a uint32
// channel (ids: readExrChannelsExactly).
DataImage readDataExrChannels(const std::string& path, const std::vector<std::string>& names);
// The named channels of any OpenEXR, each as its own sample type stored it (uint32 ids as uints).
ExrChannels readExrChannelsExactly(const std::string& path, const std::vector<std::string>& names);
std::vector<uint16_t> readUint16Png(const std::string& path, int& width, int& height);
// The same from bytes in memory (told by their signature, never by a name); `name` is used in errors.
DataImage readDataExrChannelsFromMemory(std::string_view bytes, const std::vector<std::string>& names, const std::string& name);
std::vector<uint16_t> readUint16PngFromMemory(std::string_view bytes, int& width, int& height, const std::string& name);

}  // namespace omnicam
