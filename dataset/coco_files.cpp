#include "coco_files.h"

#include <set>

#include "atomic_file.h"
#include "dataset_folder.h"
#include "errors.h"
#include "safe_files.h"
#include "scene_loader.h"
#include "sha256.h"

namespace omnicam {

namespace {

using json = nlohmann::json;

// A frame's COCO part: its bytes checked against the manifest, parsed.
json readPart(const std::string& dir, const FileRecord& file) {
  const std::string bytes = readFileInside(dir, file.path, kMaxDatasetFileBytes);
  if (sha256OfBytes(bytes) != file.sha256)
    throw InputError(showPath(dir) + ": " + quote(file.path) + ": changed since it was written (run omnicam dataset --verify)");
  return parseJsonText(bytes, showPath(dir) + "/" + file.path);
}

// The categories: the chosen classes, and the landmarks as one keypoint category after them.
json categories(const json& header, int landmarkCategory) {
  const json& outputs = header.at("outputs");
  const std::set<int> chosen = outputs.at("coco_classes").get<std::set<int>>();
  json list = json::array();
  for (const json& c : header.at("classes"))
    if (chosen.count(c.at("id").get<int>())) list.push_back({{"id", c.at("id")}, {"name", c.at("name")}, {"supercategory", "object"}});
  const json& keypoints = outputs.value("coco_keypoints", json::array());
  if (!keypoints.empty())
    list.push_back({{"id", landmarkCategory}, {"name", "landmark"}, {"supercategory", "landmark"},
                    {"keypoints", keypoints}, {"skeleton", json::array()}});
  return list;
}

json cocoFileOf(const std::string& dir, const DatasetManifest& manifest, const std::string& camera) {
  const json& header = manifest.header;
  const int landmarkCategory = static_cast<int>(header.at("classes").size());  // after the last class id
  json images = json::array(), annotations = json::array();
  int64_t nextId = 1;
  for (const auto& [index, frame] : manifest.frames) {
    const auto c = frame.cameras.find(camera);
    if (c == frame.cameras.end() || !c->second.files.count("coco")) continue;
    const json part = readPart(dir, c->second.files.at("coco"));
    const int imageId = index + 1;  // COCO tools treat id 0 as missing
    const std::string& rgb = c->second.files.at("rgb").path;
    images.push_back({{"id", imageId}, {"frame", index}, {"file_name", rgb.substr(camera.size() + 1)},
                      {"width", part.at("width")}, {"height", part.at("height")}, {"timestamp", frame.timestamp}});
    for (json a : part.at("annotations")) {
      a["id"] = nextId++;
      a["image_id"] = imageId;
      annotations.push_back(std::move(a));
    }
    if (part.contains("landmarks")) {
      json a = part.at("landmarks");
      a["id"] = nextId++;
      a["image_id"] = imageId;
      a["category_id"] = landmarkCategory;
      a["area"] = a.at("bbox").at(2).get<double>() * a.at("bbox").at(3).get<double>();
      annotations.push_back(std::move(a));
    }
  }
  return {{"info", {{"description", "omnicam dataset " + header.at("spec_file").get<std::string>() + ", camera " + camera},
                    {"version", "1"}}},
          {"licenses", json::array()},
          {"categories", categories(header, landmarkCategory)},
          {"images", images},
          {"annotations", annotations}};
}

}  // namespace

void writeCocoFiles(const std::string& dir, DatasetManifest& manifest) {
  if (!manifest.header.at("outputs").contains("coco_classes")) return;
  for (json& camera : manifest.header.at("cameras")) {
    const std::string name = camera.at("name").get<std::string>();
    const std::string text = cocoFileOf(dir, manifest, name).dump() + "\n";
    const std::string relative = name + "/coco.json";
    writeFileInside(dir, relative, text, Durability::Unsynced);
    camera["files"]["coco"] = {{"path", relative}, {"sha256", sha256OfBytes(text)}};
  }
}

}  // namespace omnicam
