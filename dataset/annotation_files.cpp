#include "annotation_files.h"

#include <map>
#include <set>

#include "atomic_file.h"
#include "dataset_folder.h"
#include "json_text.h"
#include "errors.h"
#include "exr_channels.h"
#include "multilayer_frame.h"
#include "output_kinds.h"
#include "safe_files.h"
#include "scene_loader.h"
#include "sha256.h"

namespace omnicam {

namespace {

using json = nlohmann::json;

// What the header says is gathered, and from where.
struct Gathering {
  DatasetLayout layout = DatasetLayout::Files;
  std::vector<OutputKind> kinds;
};

Gathering gatheringOf(const json& header) {
  const json outputs = header.value("outputs", json::object());
  FrameOutputPlan plan;  // checked by the manifest reader: a known layout and known outputs
  plan.layout = layoutNamed(outputs.value("layout", "files")).value_or(DatasetLayout::Files);
  for (const json& name : outputs.value("written", json::array()))
    if (const auto kind = outputNamed(name.get<std::string>())) plan.outputs.insert(*kind);
  return {plan.layout, plan.gatheredKinds()};
}

}  // namespace

std::string checkedBytes(const SafeFolder& dir, const FileRecord& file) {
  std::string bytes = dir.readFile(file.path, kMaxDatasetFileBytes);
  if (sha256OfBytes(bytes) != file.sha256)
    throw InputError(showPath(dir.path()) + ": " + quote(file.path) + ": changed since it was written (run omnicam dataset --verify)");
  return bytes;
}

namespace {

// One camera's frame: its part of each gathered kind, the image file the COCO file names, and
// what messages call the frame.
struct FrameParts {
  std::map<OutputKind, json> parts;
  std::string image, name;
};

// The record of `kind` every frame of a complete dataset has: InputError when a (forged) manifest
// lacks it.
const FileRecord& requiredRecord(const SafeFolder& dir, const CameraFrame& frame, OutputKind kind, const std::string& where) {
  const FileRecord* file = frame.file(kind);
  if (!file) throw InputError(showPath(dir.path()) + ": " + where + " has no " + quote(outputName(kind)) + " file");
  return *file;
}

FrameParts framePartsOf(const SafeFolder& dir, const CameraFrame& frame, const Gathering& gathering, const std::string& where) {
  FrameParts out;
  if (gathering.layout == DatasetLayout::Multilayer) {
    const FileRecord& file = requiredRecord(dir, frame, OutputKind::Multilayer, where);
    out.image = file.path;
    out.name = showPath(dir.path()) + "/" + file.path;
    const std::string& name = out.name;
    const ExrChannels header = decodeExrChannels(checkedBytes(dir, file), name, /*headerOnly=*/true);
    for (OutputKind kind : gathering.kinds) {
      const auto text = header.text.find(multilayerAttribute(kind));
      if (text == header.text.end()) throw InputError(name + ": no attribute " + quote(multilayerAttribute(kind)));
      out.parts[kind] = parseJsonText(text->second, name + ": " + multilayerAttribute(kind));
    }
    return out;
  }
  out.image = requiredRecord(dir, frame, kColourOutput, where).path;
  for (OutputKind kind : gathering.kinds) {
    const FileRecord& file = requiredRecord(dir, frame, kind, where);
    out.name = showPath(dir.path()) + "/" + file.path;
    out.parts[kind] = parseJsonText(checkedBytes(dir, file), out.name);
  }
  return out;
}

// The categories: the chosen classes, and the landmarks as one keypoint category after them.
json cocoCategories(const json& header, int landmarkCategory) {
  const json& outputs = header.at("outputs");
  const std::set<int> chosen = outputs.value("coco_classes", json::array()).get<std::set<int>>();
  json list = json::array();
  for (const json& c : header.value("classes", json::array()))
    if (chosen.count(c.at("id").get<int>())) list.push_back({{"id", c.at("id")}, {"name", c.at("name")}, {"supercategory", "object"}});
  const json& keypoints = outputs.value("coco_keypoints", json::array());
  if (!keypoints.empty())
    list.push_back({{"id", landmarkCategory}, {"name", "landmark"}, {"supercategory", "landmark"},
                    {"keypoints", keypoints}, {"skeleton", json::array()}});
  return list;
}

// The COCO file of one camera, built frame by frame.
class CocoFile {
 public:
  CocoFile(const json& header, const std::string& camera)
      : header_(header), camera_(camera), landmarkCategory_(static_cast<int>(header.value("classes", json::array()).size())) {}

  void add(int index, const FrameRecord& frame, const std::string& image, const json& part) {
    const int imageId = index + 1;  // COCO tools treat id 0 as missing
    images_.push_back({{"id", imageId}, {"frame", index}, {"file_name", image.substr(camera_.size() + 1)},
                       {"width", part.at("width")}, {"height", part.at("height")}, {"timestamp", frame.timestamp}});
    for (json a : part.at("annotations")) {
      a["id"] = nextId_++;
      a["image_id"] = imageId;
      annotations_.push_back(std::move(a));
    }
    if (part.contains("landmarks")) {
      json a = part.at("landmarks");
      a["id"] = nextId_++;
      a["image_id"] = imageId;
      a["category_id"] = landmarkCategory_;  // after the last class id
      a["area"] = a.at("bbox").at(2).get<double>() * a.at("bbox").at(3).get<double>();
      annotations_.push_back(std::move(a));
    }
  }

  json document() const {
    return {{"info", {{"description", "omnicam dataset " + (header_.contains("spec_file") && header_["spec_file"].is_string() ? header_["spec_file"].get<std::string>() : std::string("?")) + ", camera " + camera_},
                      {"version", "1"}}},
            {"licenses", json::array()},
            {"categories", cocoCategories(header_, landmarkCategory_)},
            {"images", images_},
            {"annotations", annotations_}};
  }

 private:
  const json& header_;
  std::string camera_;
  int landmarkCategory_;
  json images_ = json::array(), annotations_ = json::array();
  int64_t nextId_ = 1;
};

// Every frame's landmark annotations of one camera, in frame order.
json landmarksFile(const std::string& camera, const json& frames) { return {{"camera", camera}, {"frames", frames}}; }

void writeCameraFiles(const SafeFolder& dir, DatasetManifest& manifest, json& camera, const Gathering& gathering) {
  const std::string name = camera.at("name").get<std::string>();
  CocoFile coco(manifest.header, name);
  json landmarkFrames = json::array();
  for (const auto& [index, frame] : manifest.frames) {
    const std::string where = "frame " + std::to_string(index) + " camera " + quote(name);
    const auto c = frame.cameras.find(name);
    if (c == frame.cameras.end()) throw InputError(showPath(dir.path()) + ": " + where + " is not in the manifest");
    const FrameParts parts = framePartsOf(dir, c->second, gathering, where);
    try {  // a part's fields are untrusted: a missing or mistyped one is the part's fault
      if (const auto part = parts.parts.find(OutputKind::Coco); part != parts.parts.end())
        coco.add(index, frame, parts.image, part->second);
      if (const auto part = parts.parts.find(OutputKind::Landmarks); part != parts.parts.end())
        landmarkFrames.push_back(part->second);
    } catch (const json::exception& e) {
      throw InputError(parts.name + ": not an annotation part omnicam wrote (" + jsonErrorText(oneLine(e.what())) + ")");
    }
  }
  for (OutputKind kind : gathering.kinds) {
    const std::string text = (kind == OutputKind::Coco ? coco.document() : landmarksFile(name, landmarkFrames)).dump() + "\n";
    const std::string relative = gatheredPath(name, kind);
    dir.writeFile(relative, text, Durability::Unsynced);
    camera["files"][outputName(kind)] = {{"path", relative}, {"sha256", sha256OfBytes(text)}};
  }
}

}  // namespace

void writeAnnotationFiles(const SafeFolder& dir, DatasetManifest& manifest) {
  const Gathering gathering = gatheringOf(manifest.header);
  if (gathering.kinds.empty()) return;
  for (json& camera : manifest.header.at("cameras")) writeCameraFiles(dir, manifest, camera, gathering);
}

}  // namespace omnicam
