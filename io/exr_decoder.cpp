// OpenEXR through its C++ reader, a band of rows at a time (scanline and tiled files alike). The
// channels come in OpenImageIO's order: by layer, then R, G, B (or X, Y, Z in a layer that has
// X), Y, A, Z, ..., then by name; alpha is the first channel named A or Alpha.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <algorithm>
#include <cctype>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "errors.h"
#include "exr_channels.h"
#include "exr_memory_input.h"
#include "image_decoder.h"

namespace omnicam::image_io {

namespace {

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) { return std::tolower(x) == std::tolower(y); });
}

struct ExrChannel {
  std::string name, layer, suffix;  // layer keeps its dot: "depth." of "depth.Z"
  Imf::PixelType type = Imf::FLOAT;
  int special = 10000;
};

int specialIndex(std::string_view suffix, bool positionLayer) {
  static const char* const usual[] = {"R", "Red", "G", "Green", "B", "Blue", "Y", "real", "imag", "A", "Alpha",
                                      "AR", "RA", "AG", "GA", "AB", "BA", "Z", "Depth", "Zback"};
  static const char* const position[] = {"R", "Red", "G", "Green", "B", "Blue", "X", "Y", "Z", "real", "imag",
                                         "A", "Alpha", "AR", "RA", "AG", "GA", "AB", "BA", "Depth", "Zback"};
  const auto find = [&](const auto& names) {
    for (size_t i = 0; i < std::size(names); ++i)
      if (equalsIgnoringCase(suffix, names[i])) return static_cast<int>(i);
    return 10000;
  };
  return positionLayer ? find(position) : find(usual);
}

std::vector<ExrChannel> orderedChannels(const Imf::ChannelList& list) {
  std::vector<ExrChannel> channels;
  for (auto it = list.begin(); it != list.end(); ++it) {
    ExrChannel c{it.name(), "", it.name(), it.channel().type};
    const size_t dot = c.name.find_last_of('.');
    if (dot != std::string::npos) c.layer = c.name.substr(0, dot + 1), c.suffix = c.name.substr(dot + 1);
    channels.push_back(std::move(c));
  }
  const auto layerHas = [&](const std::string& layer, std::string_view suffix) {
    return std::any_of(channels.begin(), channels.end(),
                       [&](const ExrChannel& c) { return c.layer == layer && equalsIgnoringCase(c.suffix, suffix); });
  };
  for (ExrChannel& c : channels)
    c.special = specialIndex(c.suffix, layerHas(c.layer, "X") && (layerHas(c.layer, "Y") || layerHas(c.layer, "Z")));
  std::sort(channels.begin(), channels.end(), [](const ExrChannel& a, const ExrChannel& b) {
    return std::tie(a.layer, a.special, a.suffix) < std::tie(b.layer, b.special, b.suffix);
  });
  return channels;
}

class ExrDecoder final : public ImageDecoder {
 public:
  explicit ExrDecoder(const ImageSource& source) : ImageDecoder(source.name) {
    // The offset table against the file first: a forged chunk offset never reaches OpenEXR's reader.
    checkExrChunksPresent(source.bytes, source.path, name_);
    guarded("cannot read image", [&] {
      if (source.inMemory()) {
        stream_ = std::make_unique<MemoryExrInput>(source.bytes, name_);
        file_ = std::make_unique<Imf::InputFile>(*stream_, 0);
      } else {
        file_ = std::make_unique<Imf::InputFile>(source.path.c_str(), 0);
      }
    });
    const Imath::Box2i window = file_->header().dataWindow();
    header_.originX = window.min.x, header_.originY = window.min.y;
    header_.width = int64_t{window.max.x} - window.min.x + 1;
    header_.height = int64_t{window.max.y} - window.min.y + 1;
    channels_ = orderedChannels(file_->header().channels());
    header_.channels = static_cast<int>(channels_.size());
    for (const ExrChannel& c : channels_) header_.channelNames.push_back(c.name);
    header_.type = SampleType::Float;
    header_.colourSpace = "linear";
    for (size_t c = 0; c < channels_.size() && header_.alphaChannel < 0; ++c)
      if (equalsIgnoringCase(channels_[c].suffix, "A") || equalsIgnoringCase(channels_[c].suffix, "Alpha"))
        header_.alphaChannel = static_cast<int>(c);
  }

  std::string_view format() const override { return "openexr"; }

  void readNativeRows(int first, int count, void* samples) override {
    if (count <= 0) return;
    auto* out = static_cast<float*>(samples);
    const size_t channels = channels_.size(), width = static_cast<size_t>(header_.width);
    // uint32 channels are read as stored, then scaled as OpenImageIO scales them.
    const bool anyUint = std::any_of(channels_.begin(), channels_.end(), [](const ExrChannel& c) { return c.type == Imf::UINT; });
    std::vector<uint32_t> uints(anyUint ? width * static_cast<size_t>(count) * channels : 0);
    Imf::FrameBuffer frame;
    const Imath::V2i origin(static_cast<int>(header_.originX), static_cast<int>(header_.originY) + first);
    for (size_t c = 0; c < channels; ++c) {
      const bool uint = channels_[c].type == Imf::UINT;
      void* base = uint ? static_cast<void*>(uints.data() + c) : static_cast<void*>(out + c);
      frame.insert(channels_[c].name, Imf::Slice::Make(uint ? Imf::UINT : Imf::FLOAT, base, origin, static_cast<int64_t>(width), count,
                                                      channels * 4, channels * 4 * width));
    }
    guarded("cannot decode image", [&] {
      file_->setFrameBuffer(frame);
      file_->readPixels(static_cast<int>(header_.originY) + first, static_cast<int>(header_.originY) + first + count - 1);
    });
    constexpr float scale = 1.0f / 4294967295.0f;
    for (size_t c = 0; c < channels; ++c)
      if (channels_[c].type == Imf::UINT)
        for (size_t p = 0; p < width * static_cast<size_t>(count); ++p)
          out[p * channels + c] = static_cast<float>(uints[p * channels + c]) * scale;
  }

 private:
  template <typename Work>
  void guarded(const char* what, const Work& work) {
    try {
      work();
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& e) {
      throw InputError(name_ + ": " + what + " (" + oneLine(e.what()) + ")");
    }
  }

  std::unique_ptr<MemoryExrInput> stream_;
  std::unique_ptr<Imf::InputFile> file_;
  std::vector<ExrChannel> channels_;
};

}  // namespace

std::unique_ptr<ImageDecoder> openExrDecoder(const ImageSource& source) { return std::make_unique<ExrDecoder>(source); }

}  // namespace omnicam::image_io
