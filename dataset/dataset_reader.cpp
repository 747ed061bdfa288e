#include "dataset_reader.h"

#include "dataset_folder.h"
#include "errors.h"
#include "safe_files.h"
#include "scene_loader.h"
#include "sha256.h"

namespace omnicam {

DatasetReader::DatasetReader(std::string dir) : dir_(std::move(dir)), manifest_(readDatasetManifest(dir_)) {
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
    // readManifest checked every record of the header.
    return {files.at(kind).at("path").get<std::string>(), files.at(kind).at("sha256").get<std::string>()};
  }
  throw InputError(where + ": not in the manifest");
}

std::string DatasetReader::fileBytes(std::optional<int> index, const std::string& camera, const std::string& kind,
                                     bool checkHash) const {
  const FileRecord file = record(index, camera, kind);
  std::string bytes = readFileInside(dir_, file.path, kMaxDatasetFileBytes);
  if (checkHash && sha256OfBytes(bytes) != file.sha256)
    throw InputError(showPath(dir_) + ": " + quote(file.path) + ": changed since it was written (SHA-256 differs from the manifest's)");
  return bytes;
}

DecodedOutput DatasetReader::readOutput(int index, const std::string& camera, const std::string& kind, bool checkHash) const {
  const std::string bytes = fileBytes(index, camera, kind, checkHash);
  const std::string name = showPath(dir_) + ": " + quote(record(index, camera, kind).path);
  DecodedOutput out;
  if (kind == "rgb") {
    out.image = readImageFromMemory(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), name);
    out.width = out.image->width, out.height = out.image->height;
  } else if (kind == "depth" || kind == "normal") {
    out.data = readDataExrChannelsFromMemory(bytes, kind == "depth" ? std::vector<std::string>{"Z"} : std::vector<std::string>{"X", "Y", "Z"}, name);
    out.width = out.data->width, out.height = out.data->height;
  } else if (kind == "instance" || kind == "semantic") {
    out.ids = readUint16PngFromMemory(bytes, out.width, out.height, name);
  } else if (kind == "landmarks" || kind == "coco") {
    out.json = parseJsonText(bytes, name);
  } else {
    throw InputError(name + ": no decoder for outputs of kind " + quote(kind));
  }
  return out;
}

}  // namespace omnicam
