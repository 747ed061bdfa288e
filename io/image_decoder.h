#pragma once
// The image file decoders behind image.h: PNG (libpng), JPEG (libjpeg), TIFF (libtiff), OpenEXR
// and Radiance HDR (its own, hdr_decoder.cpp). Each presents its file as OpenImageIO did before
// them (the same channels in the same order, the same colour-space names, integers scaled as it
// scales them), so decoded pixels are unchanged. Each library is small; OpenImageIO loaded 260
// shared libraries into every process that could read an image (docs/performance.md, "What an
// omnicam command pays before it renders").
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace omnicam::image_io {

// Where an image's bytes are: a file (`path`), or memory (`bytes`, which must outlive the decoder).
// `name` is what messages call it.
struct ImageSource {
  std::string path;
  std::string_view bytes;
  std::string name;
  bool inMemory() const { return path.empty(); }
  static ImageSource file(const std::string& path);  // named by showPath(path)
  static ImageSource memory(std::string_view bytes, const std::string& name) { return {"", bytes, name}; }
};

enum class SampleType { Uint8, Uint16, Uint32, Float };
size_t sampleBytes(SampleType type);

// What a file's header says, before any pixel is decoded.
struct ImageHeader {
  int64_t width = 0, height = 0;  // as the file states them, before checkHeader bounds them
  int channels = 0;
  int64_t originX = 0, originY = 0;  // where the pixels start (PNG oFFs, EXR data window)
  SampleType type = SampleType::Uint8;
  // How integer codes map to light, by OpenImageIO's names: "sRGB", "linear" or "Gamma<g>" (a
  // PNG's gAMA chunk). Float samples are linear whatever this says.
  std::string colourSpace = "sRGB";
  std::vector<std::string> channelNames;  // OpenEXR's, in the order the channels are presented
  int alphaChannel = -1;                   // -1: the file names none
  bool unassociatedAlpha = false;  // the file stores colour not multiplied by alpha
};

class ImageDecoder {
 public:
  virtual ~ImageDecoder() = default;
  const ImageHeader& header() const { return header_; }
  const std::string& name() const { return name_; }
  virtual std::string_view format() const = 0;  // "png", "jpeg", "tiff", "openexr", "hdr"

  // Rows [first, first + count) in the file's own samples (header().type), channels interleaved.
  // Rows are asked for top to bottom, each once. InputError naming the image if the data are bad.
  virtual void readNativeRows(int first, int count, void* samples) = 0;
  // The same as floats: integer samples scaled to [0, 1] by v · (1 / max), as OpenImageIO does.
  void readRows(int first, int count, float* values);
  // Every row, as readRows gives them.
  std::vector<float> readAllRows();
  // Memory the decoder holds beyond the rows asked for, from its first read on: the whole image
  // where the format cannot be read by rows (an interlaced PNG, tiled or planar TIFF, a
  // progressive JPEG's coefficients). It asks the memory budget for it before allocating.
  virtual int64_t wholeBytes() const { return 0; }

 protected:
  explicit ImageDecoder(std::string name) : name_(std::move(name)) {}
  ImageHeader header_;
  std::string name_;
};

// InputError "<name>: ..." for an image without pixels, over the size limits
// (limits::kMaxImageDimension, kMaxImagePixels), with more than 16 channels or whose pixels do
// not start at (0, 0): checked before any pixel is decoded.
void checkHeader(const ImageHeader& header, const std::string& name);

// The decoder for the source's format, told by its first bytes (never by a name), its header
// checked (checkHeader): InputError "<name>: cannot read image (...)" for a missing or irregular
// file or an unknown format.
std::unique_ptr<ImageDecoder> openImageDecoder(const ImageSource& source);

// One per format; the source's signature has been checked.
std::unique_ptr<ImageDecoder> openPngDecoder(const ImageSource& source);
std::unique_ptr<ImageDecoder> openJpegDecoder(const ImageSource& source);
std::unique_ptr<ImageDecoder> openTiffDecoder(const ImageSource& source);
std::unique_ptr<ImageDecoder> openExrDecoder(const ImageSource& source);
std::unique_ptr<ImageDecoder> openHdrDecoder(const ImageSource& source);

}  // namespace omnicam::image_io
