// The data images of image.h: EXR planes of floats (depth, normals, any named channels) and
// 16-bit single-channel PNGs (instance and class ids), read strictly by signature and channel.
#include "image.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>

#include "errors.h"
#include "exr_channels.h"
#include "file_confinement.h"
#include "image_decoder.h"
#include "png_codec.h"

namespace omnicam {

using namespace image_io;

std::vector<unsigned char> encodeDataExr(const std::string& path, int width, int height, int channels,
                                         const float* values, ExrPrecision precision) {
  if (channels == 1) return encodeDataExr(path, width, height, std::vector<std::string>{"Z"}, values, precision);
  if (channels == 3) return encodeDataExr(path, width, height, {"X", "Y", "Z"}, values, precision);
  throw std::logic_error("encodeDataExr: 1 or 3 channels");
}

std::vector<unsigned char> encodeDataExr(const std::string& path, int width, int height,
                                         const std::vector<std::string>& names, const float* values,
                                         ExrPrecision precision, const std::function<void(int linesDone, int lines)>& onLines) {
  std::vector<ExrChannelSource> channels;
  for (size_t c = 0; c < names.size(); ++c)
    channels.push_back({names[c], precision == ExrPrecision::Half ? ExrSampleType::Half : ExrSampleType::Float, values + c,
                        nullptr, names.size()});
  ExrWriteOptions options;
  options.onLines = onLines;
  return encodeExrChannels(path, width, height, channels, options);
}

std::vector<unsigned char> encodeUint16Png(const std::string& path, int width, int height,
                                           const std::vector<uint16_t>& values) {
  return encodePng(path, width, height, 1, 16, values.data(), false);
}

namespace {

// Every name in `names` must be a channel of `decoded`; InputError naming those it has otherwise.
void requireChannels(const ExrChannels& decoded, const std::vector<std::string>& names, const std::string& name) {
  for (const std::string& wanted : names) {
    if (decoded.types.count(wanted)) continue;
    std::string present;
    for (const auto& [channel, type] : decoded.types) present += (present.empty() ? "" : ", ") + channel;
    throw InputError(name + ": no channel " + quote(wanted) + " (it has " + (present.empty() ? "none" : present) + ")");
  }
}

ExrChannels decodeChannels(std::string_view bytes, const std::vector<std::string>& names, const std::string& name) {
  const std::set<std::string> wanted(names.begin(), names.end());
  ExrChannels decoded = decodeExrChannels(bytes, name, false, &wanted);
  requireChannels(decoded, names, name);
  return decoded;
}

DataImage floatChannels(std::string_view bytes, const std::vector<std::string>& names, const std::string& name) {
  const ExrChannels decoded = decodeChannels(bytes, names, name);
  const size_t channels = names.size(), pixels = static_cast<size_t>(decoded.width) * decoded.height;
  DataImage image{decoded.width, decoded.height, static_cast<int>(channels), std::vector<float>(pixels * channels)};
  for (size_t c = 0; c < channels; ++c) {
    const auto plane = decoded.floats.find(names[c]);
    if (plane == decoded.floats.end())  // read as floats, ids would come out scaled by 2^-32
      throw InputError(name + ": channel " + quote(names[c]) + " holds uint32 ids, not floats");
    for (size_t p = 0; p < pixels; ++p) image.values[p * channels + c] = plane->second[p];
  }
  return image;
}

std::string fileBytes(const std::string& path) {
  std::string why;
  std::optional<std::string> bytes = readWholeFile(path, why);
  if (!bytes) throw InputError(showPath(path) + ": " + why);
  return std::move(*bytes);
}

std::vector<uint16_t> readUint16(ImageDecoder& in, int& width, int& height) {
  const ImageHeader& header = in.header();
  if (in.format() != "png" || header.channels != 1 || header.type != SampleType::Uint16)
    throw InputError(in.name() + ": not a 16-bit single-channel PNG");
  width = static_cast<int>(header.width), height = static_cast<int>(header.height);
  std::vector<uint16_t> values(static_cast<size_t>(width) * height);
  in.readNativeRows(0, height, values.data());
  return values;
}

}  // namespace

DataImage readDataExr(const std::string& path) {
  const auto in = openImageDecoder(ImageSource::file(path));
  const ImageHeader& header = in->header();
  if (in->format() != "openexr" || (header.channels != 1 && header.channels != 3))
    throw InputError(in->name() + ": not a 1- or 3-channel OpenEXR data image");
  return DataImage{static_cast<int>(header.width), static_cast<int>(header.height), header.channels, in->readAllRows()};
}

DataImage readDataExrChannels(const std::string& path, const std::vector<std::string>& names) {
  return floatChannels(fileBytes(path), names, showPath(path));
}

DataImage readDataExrChannelsFromMemory(std::string_view bytes, const std::vector<std::string>& names, const std::string& name) {
  return floatChannels(bytes, names, name);
}

ExrChannels readExrChannelsExactly(const std::string& path, const std::vector<std::string>& names) {
  return decodeChannels(fileBytes(path), names, showPath(path));
}

std::vector<uint16_t> readUint16Png(const std::string& path, int& width, int& height) {
  return readUint16(*openImageDecoder(ImageSource::file(path)), width, height);
}

std::vector<uint16_t> readUint16PngFromMemory(std::string_view bytes, int& width, int& height, const std::string& name) {
  return readUint16(*openImageDecoder(ImageSource::memory(bytes, name)), width, height);
}

}  // namespace omnicam
