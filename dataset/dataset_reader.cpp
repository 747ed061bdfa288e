#include "dataset_reader.h"

#include <filesystem>
#include <set>

#include "dataset_folder.h"
#include "dataset_shards.h"
#include "errors.h"
#include "exr_channels.h"
#include "memory_budget.h"
#include "multilayer_frame.h"
#include "safe_files.h"
#include "scene_loader.h"
#include "sha256.h"

namespace omnicam {

DatasetReader::DatasetReader(std::string dir) : dir_(std::move(dir)), folder_(dir_), manifest_(readMergedDatasetManifest(folder_)) {
  for (const auto& [index, frame] : manifest_.frames) frames_.push_back(index);
}

std::vector<std::string> DatasetReader::cameras() const {
  std::vector<std::string> names;
  for (const auto& camera : manifest_.header.at("cameras")) names.push_back(camera.at("name").get<std::string>());
  return names;
}

const FrameRecord& DatasetReader::frame(int index) const {
  const auto at = manifest_.frames.find(index);
  if (at == manifest_.frames.end()) throw InputError(showPath(dir_) + ": frame " + std::to_string(index) + " is not in the manifest");
  return at->second;
}

FileRecord DatasetReader::record(std::optional<int> index, const std::string& camera, const std::string& kind) const {
  const std::string where = showPath(dir_) + ": camera " + quote(camera);
  if (index) {
    const FrameRecord& f = frame(*index);
    const auto c = f.cameras.find(camera);
    if (c == f.cameras.end()) throw InputError(where + ": not in frame " + std::to_string(*index));
    const auto file = c->second.files.find(kind);
    if (file == c->second.files.end()) throw InputError(where + ": frame " + std::to_string(*index) + " has no " + quote(kind));
    return file->second;
  }
  for (const auto& entry : manifest_.header.at("cameras")) {
    if (entry.at("name") != camera) continue;
    const auto& files = entry.at("files");
    if (!files.contains(kind)) throw InputError(where + ": has no file " + quote(kind));
    // readDatasetManifest checked every record of the header.
    return {files.at(kind).at("path").get<std::string>(), files.at(kind).at("sha256").get<std::string>()};
  }
  throw InputError(where + ": not in the manifest");
}

RigSpec DatasetReader::cameraRig(int index, const std::string& camera) const {
  const FrameRecord& f = frame(index);
  const auto c = f.cameras.find(camera);
  if (c == f.cameras.end()) throw InputError(showPath(dir_) + ": camera " + quote(camera) + ": not in frame " + std::to_string(index));
  if (c->second.rig) return *c->second.rig;
  const nlohmann::json& cameras = manifest_.header.at("cameras");
  for (size_t k = 0; k < cameras.size(); ++k) {
    if (cameras[k].at("name") != camera) continue;
    const std::string where = "cameras[" + std::to_string(k) + "].rig";
    if (!cameras[k].contains("rig")) throw InputError(showPath(dir_ + "/" + kManifestName) + ": " + where + ": missing");
    return rigFromJson(cameras[k].at("rig"), dir_ + "/" + kManifestName, where);
  }
  throw InputError(showPath(dir_) + ": camera " + quote(camera) + ": not in the manifest");
}

namespace {

// Whether DIR/manifest.json states omnicam's manifest format, however broken the rest: a file of
// that name from another tool is no dataset's.
bool statesManifestFormat(const std::string& dir) {
  try {
    const nlohmann::json top = nlohmann::json::parse(readFileInside(dir, kManifestName, kMaxManifestBytes), nullptr, false);
    return top.is_object() && top.contains("format") && top["format"] == kManifestFormat;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

std::optional<DatasetImageLocation> locateInDataset(const std::string& image) {
  namespace fs = std::filesystem;
  const fs::path path = fs::absolute(image).lexically_normal();
  const fs::path kindFolder = path.parent_path(), cameraFolder = kindFolder.parent_path(), dir = cameraFolder.parent_path();
  if (!path.has_filename() || kindFolder == cameraFolder || cameraFolder == dir || entryInside(dir.string(), kManifestName) != EntryKind::File)
    return std::nullopt;
  std::optional<DatasetReader> reader;
  try {
    reader.emplace(dir.string());
  } catch (const InputError&) {
    if (!statesManifestFormat(dir.string())) return std::nullopt;
    throw;
  }
  // By the path the manifest lists (<camera>/rgb/000001.png, <camera>/data/<t_ns>.png, …), not
  // by a number read from the name.
  const std::string camera = cameraFolder.filename().string();
  const std::string listed = camera + "/" + kindFolder.filename().string() + "/" + path.filename().string();
  for (const auto& [index, frame] : reader->manifest().frames) {
    const auto cameraFrame = frame.cameras.find(camera);
    if (cameraFrame == frame.cameras.end()) continue;
    for (const auto& [kind, file] : cameraFrame->second.files)
      if (file.path == listed) return DatasetImageLocation{dir.string(), camera, index, reader->cameraRig(index, camera)};
  }
  return std::nullopt;
}

std::string DatasetReader::fileBytes(std::optional<int> index, const std::string& camera, const std::string& kind,
                                     bool checkHash) const {
  const FileRecord file = record(index, camera, kind);
  std::string bytes = folder_.readFile(file.path, kMaxDatasetFileBytes);
  if (checkHash && sha256OfBytes(bytes) != file.sha256)
    throw InputError(showPath(dir_) + ": " + quote(file.path) + ": changed since it was written (SHA-256 differs from the manifest's)");
  return bytes;
}

namespace {

// An output from its own file (files layout).
DecodedOutput decodeOutputFile(const std::string& bytes, OutputKind kind, const std::string& name) {
  DecodedOutput out;
  const OutputKindRow& row = outputRow(kind);
  switch (row.encoding) {
    case OutputEncoding::ColourImage:
      out.image = readImageFromMemory(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), name);
      out.width = out.image->width, out.height = out.image->height;
      return out;
    case OutputEncoding::FloatExr:
    case OutputEncoding::HalfExr:
      out.data = readDataExrChannelsFromMemory(bytes, row.fileChannels, name);
      out.width = out.data->width, out.height = out.data->height;
      return out;
    case OutputEncoding::Uint16Png: out.ids = readUint16PngFromMemory(bytes, out.width, out.height, name); return out;
    case OutputEncoding::Json: out.json = parseJsonText(bytes, name); return out;
    case OutputEncoding::MultilayerExr: break;
  }
  throw InputError(name + ": no decoder for outputs of kind " + quote(outputName(kind)));
}

// An output from its frame's decoded OpenEXR (multilayer layout, multilayer_frame.h).
DecodedOutput outputOfFrame(const ExrChannels& frame, OutputKind kind, const std::string& name) {
  DecodedOutput out;
  out.width = frame.width, out.height = frame.height;
  const size_t pixels = static_cast<size_t>(frame.width) * static_cast<size_t>(frame.height);
  if (isAnnotation(kind)) {
    const auto text = frame.text.find(multilayerAttribute(kind));
    if (text == frame.text.end()) throw InputError(name + ": no attribute " + quote(multilayerAttribute(kind)));
    out.json = parseJsonText(text->second, name + ": " + multilayerAttribute(kind));
    return out;
  }
  const OutputKindRow& row = outputRow(kind);
  const std::vector<std::string>& channels = row.layerChannels;
  const bool ids = row.layerType == ExrSampleType::Uint;
  for (const std::string& channel : channels)
    if (!(ids ? frame.uints.count(channel) : frame.floats.count(channel)))
      throw InputError(name + ": no " + (ids ? "uint" : "half or float") + " channel " + quote(channel));
  if (ids) {
    const std::vector<uint32_t>& values = frame.uints.at(channels[0]);
    out.ids.resize(pixels);
    for (size_t p = 0; p < pixels; ++p) {
      if (values[p] > 0xffff) throw InputError(name + ": " + channels[0] + ": id " + std::to_string(values[p]) + " is not 16-bit");
      out.ids[p] = static_cast<uint16_t>(values[p]);
    }
    return out;
  }
  requireMemory(static_cast<int64_t>(pixels * channels.size() * sizeof(float)),
                name + ": " + std::to_string(frame.width) + "x" + std::to_string(frame.height) + " pixels of " + outputName(kind));
  std::vector<float> interleaved(pixels * channels.size());
  for (size_t c = 0; c < channels.size(); ++c) {
    const std::vector<float>& plane = frame.floats.at(channels[c]);
    for (size_t p = 0; p < pixels; ++p) interleaved[p * channels.size() + c] = plane[p];
  }
  if (row.plane == OutputPlane::Colour) {
    out.image = ImageRGBA(frame.width, frame.height);
    out.image->pixels = std::move(interleaved);
  } else {
    out.data = DataImage{frame.width, frame.height, static_cast<int>(channels.size()), std::move(interleaved)};
  }
  return out;
}

}  // namespace

ImageRGBA multilayerFrameColour(std::string_view bytes, const std::string& name) {
  const std::vector<std::string>& names = outputRow(kColourOutput).layerChannels;
  const std::set<std::string> channels(names.begin(), names.end());
  return std::move(*outputOfFrame(decodeExrChannels(bytes, name, false, &channels), kColourOutput, name).image);
}

std::map<OutputKind, DecodedOutput> DatasetReader::readOutputs(int index, const std::string& camera,
                                                               const std::vector<OutputKind>& kinds, bool checkHash) const {
  std::map<OutputKind, DecodedOutput> outputs;
  const std::string multilayer = outputName(OutputKind::Multilayer);
  const FrameRecord& f = frame(index);
  const auto c = f.cameras.find(camera);
  const bool layered = c != f.cameras.end() && c->second.file(OutputKind::Multilayer);
  if (!layered) {
    for (OutputKind kind : kinds) {
      const std::string name = showPath(dir_) + ": " + quote(record(index, camera, outputName(kind)).path);
      outputs[kind] = decodeOutputFile(fileBytes(index, camera, outputName(kind), checkHash), kind, name);
    }
    return outputs;
  }
  const std::string name = showPath(dir_) + ": " + quote(record(index, camera, multilayer).path);
  std::set<std::string> channels;  // only what was asked for is decoded
  for (OutputKind kind : kinds) channels.insert(outputRow(kind).layerChannels.begin(), outputRow(kind).layerChannels.end());
  const ExrChannels decoded = decodeExrChannels(fileBytes(index, camera, multilayer, checkHash), name, channels.empty(), &channels);
  for (OutputKind kind : kinds) {
    if (kind == OutputKind::Multilayer) throw InputError(name + ": the frame file itself is not an output");
    outputs[kind] = outputOfFrame(decoded, kind, name);
  }
  return outputs;
}

DecodedOutput DatasetReader::readOutput(int index, const std::string& camera, OutputKind kind, bool checkHash) const {
  return std::move(readOutputs(index, camera, {kind}, checkHash).at(kind));
}

}  // namespace omnicam
