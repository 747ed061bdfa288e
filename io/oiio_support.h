#pragma once
// What the image readers and writers (image.cpp, data_image.cpp) share about OpenImageIO: libpng
// kept off stderr, one-line messages, the checks of a header before any pixel is decoded.
#include <OpenImageIO/imageio.h>

#include <string>

namespace omnicam::image_io {

// libpng's PNG_FILTER_SUB: one cheap filter instead of trying all five per row (libpng's
// adaptive default), which costs more than the compression at level 1.
inline constexpr int kPngFilterSub = 0x10;

// libpng (under OpenImageIO) prints "libpng error: ..." straight to stderr before OpenImageIO
// reports the same error to us; our one-line messages carry it. While any image is being
// decoded, stderr points at /dev/null (reference-counted, so concurrent decodes nest safely).
class QuietStderr {
 public:
  QuietStderr();
  ~QuietStderr();
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;
};

// OpenImageIO's messages can span lines; ours are one line.
std::string firstLine(const std::string& text);

// InputError "<name>: ..." for an image without pixels, over the size limits, with more than 16
// channels or whose data window does not start at (0, 0).
void checkHeader(const OIIO::ImageSpec& spec, const std::string& name);

}  // namespace omnicam::image_io
