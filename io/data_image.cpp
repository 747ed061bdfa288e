// The data images of image.h: EXR planes of floats (depth, normals, any named channels) and
// 16-bit single-channel PNGs (instance and class ids), read strictly by signature and channel.
#include "image.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "errors.h"
#include "exr_channels.h"
#include "oiio_support.h"

namespace omnicam {

using namespace image_io;  // OpenImageIO, quietly and in one-line messages

std::vector<unsigned char> encodeDataExr(const std::string& path, int width, int height, int channels,
                                         const float* values, ExrPrecision precision) {
  if (channels == 1) return encodeDataExr(path, width, height, std::vector<std::string>{"Z"}, values, precision);
  if (channels == 3) return encodeDataExr(path, width, height, {"X", "Y", "Z"}, values, precision);
  throw std::logic_error("encodeDataExr: 1 or 3 channels");
}

std::vector<unsigned char> encodeDataExr(const std::string& path, int width, int height,
                                         const std::vector<std::string>& names, const float* values,
                                         ExrPrecision precision) {
  std::vector<ExrChannelSource> channels;
  for (size_t c = 0; c < names.size(); ++c)
    channels.push_back({names[c], precision == ExrPrecision::Half ? ExrSampleType::Half : ExrSampleType::Float, values + c,
                        nullptr, names.size()});
  return encodeExrChannels(path, width, height, channels, {});
}

std::vector<unsigned char> encodeUint16Png(const std::string& path, int width, int height,
                                           const std::vector<uint16_t>& values) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput sink(bytes);
  void* proxy = &sink;
  auto out = OIIO::ImageOutput::create("memory.png");
  if (!out) throw OutputError(showPath(path) + ": no image writer (" + firstLine(OIIO::geterror()) + ")");
  OIIO::ImageSpec spec(width, height, 1, OIIO::TypeDesc::UINT16);
  spec.attribute("png:compressionLevel", 1);
  spec.attribute("png:filter", kPngFilterSub);
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  if (!out->open("memory.png", spec) || !out->write_image(OIIO::TypeDesc::UINT16, values.data()) || !out->close())
    throw OutputError(showPath(path) + ": cannot encode PNG (" + firstLine(out->geterror()) + ")");
  return bytes;
}

namespace {

// A data image opened from a file or from bytes in memory (which must outlive it); `name` is what
// messages call it.
struct DataInput {
  std::unique_ptr<OIIO::Filesystem::IOMemReader> memory;
  std::unique_ptr<OIIO::ImageInput> input;
  std::string name;
};

DataInput openDataImage(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(showPath(path) + ": cannot read image (no such file)");
  const QuietStderr quiet;
  DataInput in{nullptr, OIIO::ImageInput::open(path), showPath(path)};
  if (!in.input) throw InputError(in.name + ": cannot read image (" + firstLine(OIIO::geterror()) + ")");
  checkHeader(in.input->spec(), path);
  return in;
}

DataInput openDataImage(std::string_view bytes, const std::string& name) {
  // The format comes from the bytes' signature, never from a name the data chose.
  const char* format = nullptr;
  if (bytes.size() >= 8 && bytes.substr(0, 8) == std::string_view("\x89PNG\r\n\x1a\n", 8)) format = "memory.png";
  else if (bytes.size() >= 4 && bytes.substr(0, 4) == std::string_view("\x76\x2f\x31\x01", 4)) format = "memory.exr";
  if (!format) throw InputError(name + ": not a PNG or EXR image");
  DataInput in;
  in.name = name;
  in.memory = std::make_unique<OIIO::Filesystem::IOMemReader>(const_cast<char*>(bytes.data()), bytes.size());
  OIIO::ImageSpec config;
  void* proxy = in.memory.get();
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  const QuietStderr quiet;
  in.input = OIIO::ImageInput::open(format, &config);
  if (!in.input) throw InputError(name + ": cannot read image (" + firstLine(OIIO::geterror()) + ")");
  checkHeader(in.input->spec(), name);
  return in;
}

DataImage readExrChannels(DataInput in, const std::vector<std::string>& names) {
  const OIIO::ImageSpec& spec = in.input->spec();
  if (std::string(in.input->format_name()) != "openexr") throw InputError(in.name + ": not an OpenEXR image");
  std::vector<int> index;
  for (const std::string& name : names) {
    const auto at = std::find(spec.channelnames.begin(), spec.channelnames.end(), name);
    if (at == spec.channelnames.end()) throw InputError(in.name + ": no channel " + quote(name));
    index.push_back(static_cast<int>(at - spec.channelnames.begin()));
  }
  std::vector<float> all(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in.input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data()))
    throw InputError(in.name + ": cannot decode image (" + firstLine(in.input->geterror()) + ")");
  const int channels = static_cast<int>(names.size());
  DataImage image{spec.width, spec.height, channels, std::vector<float>(static_cast<size_t>(spec.width) * spec.height * channels)};
  for (size_t p = 0; p < static_cast<size_t>(spec.width) * spec.height; ++p)
    for (int c = 0; c < channels; ++c) image.values[p * channels + c] = all[p * spec.nchannels + index[c]];
  return image;
}

std::vector<uint16_t> readUint16(DataInput in, int& width, int& height) {
  const OIIO::ImageSpec& spec = in.input->spec();
  if (std::string(in.input->format_name()) != "png" || spec.nchannels != 1 || spec.format != OIIO::TypeDesc::UINT16)
    throw InputError(in.name + ": not a 16-bit single-channel PNG");
  width = spec.width, height = spec.height;
  std::vector<uint16_t> values(static_cast<size_t>(width) * height);
  if (!in.input->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT16, values.data()))
    throw InputError(in.name + ": cannot decode image (" + firstLine(in.input->geterror()) + ")");
  return values;
}

}  // namespace

DataImage readDataExr(const std::string& path) {
  DataInput in = openDataImage(path);
  const OIIO::ImageSpec& spec = in.input->spec();
  if (std::string(in.input->format_name()) != "openexr" || (spec.nchannels != 1 && spec.nchannels != 3))
    throw InputError(in.name + ": not a 1- or 3-channel OpenEXR data image");
  DataImage image{spec.width, spec.height, spec.nchannels, {}};
  image.values.resize(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in.input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.values.data()))
    throw InputError(in.name + ": cannot decode image (" + firstLine(in.input->geterror()) + ")");
  return image;
}

DataImage readDataExrChannels(const std::string& path, const std::vector<std::string>& names) {
  return readExrChannels(openDataImage(path), names);
}

DataImage readDataExrChannelsFromMemory(std::string_view bytes, const std::vector<std::string>& names, const std::string& name) {
  return readExrChannels(openDataImage(bytes, name), names);
}

std::vector<uint16_t> readUint16Png(const std::string& path, int& width, int& height) {
  return readUint16(openDataImage(path), width, height);
}

std::vector<uint16_t> readUint16PngFromMemory(std::string_view bytes, int& width, int& height, const std::string& name) {
  return readUint16(openDataImage(bytes, name), width, height);
}

}  // namespace omnicam
