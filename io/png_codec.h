#pragma once
// PNG files through libpng: the decoder of image_decoder.h and the one encoder omnicam writes
// PNGs with (8-bit sRGB RGBA frames, 16-bit single-channel ids).
#include <string>
#include <vector>

namespace omnicam::image_io {

// The bytes of a PNG of `channels` samples per pixel (1 to 4) of `bitDepth` bits (8 or 16;
// 16-bit samples are uint16_t in this machine's order), rows top to bottom. `srgb` writes an sRGB
// chunk (colour), without it the samples are data. Compressed for speed (zlib level 1, libpng's
// SUB filter on every row). OutputError naming `name` if libpng refuses.
std::vector<unsigned char> encodePng(const std::string& name, int width, int height, int channels, int bitDepth,
                                     const void* samples, bool srgb);

}  // namespace omnicam::image_io
