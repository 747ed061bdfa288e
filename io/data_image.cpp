// The data images of image.h: EXR planes of floats (depth, normals, any named channels) and
// 16-bit single-channel PNGs (instance and class ids), read strictly by signature and channel.
#include "image.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "errors.h"
#include "exr_channels.h"
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

DataImage readExrChannels(ImageDecoder& in, const std::vector<std::string>& names) {
  if (in.format() != "openexr") throw InputError(in.name() + ": not an OpenEXR image");
  const ImageHeader& header = in.header();
  std::vector<size_t> index;
  for (const std::string& name : names) {
    const auto at = std::find(header.channelNames.begin(), header.channelNames.end(), name);
    if (at == header.channelNames.end()) throw InputError(in.name() + ": no channel " + quote(name));
    index.push_back(static_cast<size_t>(at - header.channelNames.begin()));
  }
  const std::vector<float> all = in.readAllRows();
  const size_t channels = names.size(), pixels = static_cast<size_t>(header.width) * header.height;
  DataImage image{static_cast<int>(header.width), static_cast<int>(header.height), static_cast<int>(channels),
                  std::vector<float>(pixels * channels)};
  for (size_t p = 0; p < pixels; ++p)
    for (size_t c = 0; c < channels; ++c) image.values[p * channels + c] = all[p * header.channels + index[c]];
  return image;
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
  return readExrChannels(*openImageDecoder(ImageSource::file(path)), names);
}

DataImage readDataExrChannelsFromMemory(std::string_view bytes, const std::vector<std::string>& names, const std::string& name) {
  return readExrChannels(*openImageDecoder(ImageSource::memory(bytes, name)), names);
}

std::vector<uint16_t> readUint16Png(const std::string& path, int& width, int& height) {
  return readUint16(*openImageDecoder(ImageSource::file(path)), width, height);
}

std::vector<uint16_t> readUint16PngFromMemory(std::string_view bytes, int& width, int& height, const std::string& name) {
  return readUint16(*openImageDecoder(ImageSource::memory(bytes, name)), width, height);
}

}  // namespace omnicam
