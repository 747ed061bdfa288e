#include "multilayer_frame.h"

#include <stdexcept>

#include "scene_ids.h"

namespace omnicam {

const std::vector<std::string>& multilayerChannels(OutputKind kind) {
  static const std::vector<std::string> rgb{"R", "G", "B", "A"}, depth{"depth.Z"}, normal{"normal.X", "normal.Y", "normal.Z"},
      instance{"instance.I"}, semantic{"semantic.I"}, none;
  switch (kind) {
    case OutputKind::Rgb: return rgb;
    case OutputKind::Depth: return depth;
    case OutputKind::Normal: return normal;
    case OutputKind::Instance: return instance;
    case OutputKind::Semantic: return semantic;
    case OutputKind::Landmarks:
    case OutputKind::Coco:
    case OutputKind::Multilayer: return none;  // in the header, or the file itself
  }
  return none;
}

std::string multilayerAttribute(OutputKind kind) { return std::string("omnicam:") + outputName(kind); }

std::vector<unsigned char> encodeMultilayerFrame(const std::string& path, const ImageRGBA& rgb, const AovFrame* aovs,
                                                 const std::set<OutputKind>& outputs,
                                                 const std::vector<uint16_t>& classOfInstance,
                                                 const std::map<OutputKind, std::string>& annotations,
                                                 FrameCompression compression) {
  std::vector<ExrChannelSource> channels;
  auto add = [&](OutputKind kind, ExrSampleType type, const float* values) {
    const std::vector<std::string>& names = multilayerChannels(kind);
    for (size_t c = 0; c < names.size(); ++c) channels.push_back({names[c], type, values + c, nullptr, names.size()});
  };
  add(OutputKind::Rgb, ExrSampleType::Half, rgb.pixels.data());
  std::vector<uint32_t> instance, semantic;
  for (OutputKind kind : outputs) {
    if (!needsAovs(kind) || isAnnotation(kind)) continue;
    if (!aovs) throw std::logic_error("encodeMultilayerFrame: AOVs asked for but not rendered");
    if (kind == OutputKind::Depth) add(kind, ExrSampleType::Float, aovs->depth.data());
    if (kind == OutputKind::Normal) add(kind, ExrSampleType::Half, aovs->normal.data());
    if (kind == OutputKind::Instance) {
      instance.assign(aovs->instance.begin(), aovs->instance.end());
      channels.push_back({multilayerChannels(kind)[0], ExrSampleType::Uint, nullptr, instance.data(), 1});
    }
    if (kind == OutputKind::Semantic) {
      const std::vector<uint16_t> classes = classIdsOf(aovs->instance, classOfInstance);
      semantic.assign(classes.begin(), classes.end());
      channels.push_back({multilayerChannels(kind)[0], ExrSampleType::Uint, nullptr, semantic.data(), 1});
    }
  }
  ExrWriteOptions options;
  // RLE: one scanline per chunk; zip: deflate level 1 over 16 scanlines.
  options.compression = compression == FrameCompression::Zip ? ExrCompression::Zip : ExrCompression::Rle;
  for (const auto& [kind, text] : annotations) options.text[multilayerAttribute(kind)] = text;
  return encodeExrChannels(path, rgb.width, rgb.height, channels, options);
}

}  // namespace omnicam
