#pragma once
// JPEG through libjpeg(-turbo): the decoder of image_decoder.h and an encoder with libjpeg's
// defaults (baseline, 4:2:0 chroma, the IJG tables scaled to a quality), as OpenCV's imencode
// writes them.
#include <string>
#include <vector>

namespace omnicam::image_io {

// The bytes of a JPEG of 8-bit codes, `channels` per pixel (1: grey, 3: RGB), rows top to bottom,
// at `quality` (1 to 100). OutputError naming `name` if libjpeg refuses.
std::vector<unsigned char> encodeJpeg(const std::string& name, int width, int height, int channels,
                                      const unsigned char* codes, int quality);

}  // namespace omnicam::image_io
