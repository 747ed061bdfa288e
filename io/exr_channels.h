#pragma once
// OpenEXR images in memory whose channels each keep their own sample type (half, float32, uint32)
// and whose header carries text attributes: what one dataset frame's colour and AOVs need in
// one file (docs/dataset-format.md, "multilayer"), and what the single-purpose data EXRs are.
// Written with OpenEXR's core API and compressed here (exr_chunks.h), a batch of chunks at a time
// on TBB's threads (a large table alone would take a minute on one); read with OpenEXR's C++ API.
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace omnicam {

enum class ExrSampleType { Half, Float, Uint };
enum class ExrCompression { None, Rle, Zips, Zip };

// One channel to write, read in place: value of pixel p at base[p · pixelStride] (floats, stored
// as half or float32) or uints[p · pixelStride] (stored as uint32).
struct ExrChannelSource {
  std::string name;  // OpenEXR "layer.channel" names group channels into layers
  ExrSampleType stored = ExrSampleType::Float;
  const float* floats = nullptr;
  const uint32_t* uints = nullptr;
  size_t pixelStride = 1;
};

struct ExrWriteOptions {
  ExrCompression compression = ExrCompression::Zip;
  int zipLevel = 1;  // deflate level of Zip and Zips (1: speed over the last percent of size)
  std::map<std::string, std::string> text;  // string attributes of the header
  // Called on the encoding thread as lines are compressed (a 16384² image takes tens of seconds).
  std::function<void(int linesDone, int lines)> onLines;
};

// The file's bytes; OutputError naming `path` if OpenEXR refuses. No DateTime is written:
// identical values give identical bytes.
std::vector<unsigned char> encodeExrChannels(const std::string& path, int width, int height,
                                             const std::vector<ExrChannelSource>& channels, const ExrWriteOptions& options);

// A decoded image: every channel by name, float channels (half or float32 in the file) as floats,
// uint32 ones as uints; the header's string attributes.
struct ExrChannels {
  int width = 0, height = 0;
  std::map<std::string, ExrSampleType> types;
  std::map<std::string, std::vector<float>> floats;
  std::map<std::string, std::vector<uint32_t>> uints;
  std::map<std::string, std::string> text;
};

// Decodes `bytes` (an untrusted file: InputError naming `name` for anything but a readable
// single-part scanline or tiled OpenEXR within the image size limits, whose decoded channels
// hold at most kMaxDecodedExrSamples values). `channels`: only these are decoded (none: every
// channel); headerOnly: types, size and text only, no pixels.
inline constexpr int64_t kMaxDecodedExrSamples = int64_t{1} << 29;  // 2 GiB of 4-byte values
ExrChannels decodeExrChannels(std::string_view bytes, const std::string& name, bool headerOnly = false,
                              const std::set<std::string>* channels = nullptr);

// Whether an OpenEXR can hold the pixels its header claims, from its offset table and chunk
// leaders alone, before a pixel is allocated: every chunk lies within the file and is large
// enough to unpack to its lines. A forged header claiming 16384 x 8192 pixels in 64 KB is refused
// in microseconds, not after gigabytes are allocated. The file at `path`, or (`path` empty)
// `bytes`; InputError naming `name` otherwise.
void checkExrChunksPresent(std::string_view bytes, const std::string& path, const std::string& name);

}  // namespace omnicam
