#include "multilayer_frame.h"

#include <stdexcept>

namespace omnicam {

std::string multilayerAttribute(OutputKind kind) { return std::string("omnicam:") + outputName(kind); }

std::vector<unsigned char> encodeMultilayerFrame(const std::string& path, const FramePlanes& frame,
                                                 const std::set<OutputKind>& outputs,
                                                 const std::map<OutputKind, std::string>& annotations,
                                                 FrameCompression compression) {
  std::set<OutputKind> kinds = outputs;
  kinds.insert(kColourOutput);
  std::vector<ExrChannelSource> channels;
  std::vector<std::vector<uint32_t>> idPlanes;  // alive until the file is encoded
  idPlanes.reserve(kinds.size());
  for (OutputKind kind : kinds) {  // frame order: colour first
    const OutputKindRow& row = outputRow(kind);
    const std::vector<std::string>& names = row.layerChannels;
    if (names.empty()) continue;  // annotations: in the header
    if (row.layerType == ExrSampleType::Uint) {
      const std::vector<uint16_t> ids = frame.ids(row.plane);
      idPlanes.emplace_back(ids.begin(), ids.end());
      channels.push_back({names[0], ExrSampleType::Uint, nullptr, idPlanes.back().data(), 1});
      continue;
    }
    const float* values = frame.floats(row.plane);
    for (size_t c = 0; c < names.size(); ++c) channels.push_back({names[c], row.layerType, values + c, nullptr, names.size()});
  }
  ExrWriteOptions options;
  // RLE: one scanline per chunk; zip: deflate level 1 over 16 scanlines.
  options.compression = compression == FrameCompression::Zip ? ExrCompression::Zip : ExrCompression::Rle;
  for (const auto& [kind, text] : annotations) options.text[multilayerAttribute(kind)] = text;
  return encodeExrChannels(path, frame.width(), frame.height(), channels, options);
}

}  // namespace omnicam
