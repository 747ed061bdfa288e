#include "output_kinds.h"

#include <cmath>
#include <cstdio>
#include <regex>
#include <stdexcept>
#include <string>

namespace omnicam {

namespace {

// Whether a spec's `outputs` switches the kind on and off, and its default there.
enum class InSpec { Always, On, Off, Never };

struct KindRow {
  OutputKind kind;
  const char* name;
  bool aovs;        // from the engine's AOVs
  bool annotation;  // JSON
  InSpec spec;
};

// Frame order. The one table of output kinds.
constexpr KindRow kKinds[] = {
    {OutputKind::Rgb, "rgb", false, false, InSpec::Always},
    {OutputKind::Depth, "depth", true, false, InSpec::On},
    {OutputKind::Instance, "instance", true, false, InSpec::On},
    {OutputKind::Semantic, "semantic", true, false, InSpec::On},
    {OutputKind::Normal, "normal", true, false, InSpec::On},
    {OutputKind::Landmarks, "landmarks", false, true, InSpec::On},
    {OutputKind::Coco, "coco", true, true, InSpec::Off},
    {OutputKind::Multilayer, "multilayer", false, false, InSpec::Never},
};

const KindRow& row(OutputKind kind) {
  for (const KindRow& r : kKinds)
    if (r.kind == kind) return r;
  throw std::logic_error("output kind " + std::to_string(static_cast<int>(kind)) + " has no row");
}

}  // namespace

const char* outputName(OutputKind kind) { return row(kind).name; }

std::optional<OutputKind> outputNamed(std::string_view name) {
  for (const KindRow& r : kKinds)
    if (name == r.name) return r.kind;
  return std::nullopt;
}

const std::vector<OutputKind>& allOutputKinds() {
  static const std::vector<OutputKind> kinds = [] {
    std::vector<OutputKind> all;
    for (const KindRow& r : kKinds) all.push_back(r.kind);
    return all;
  }();
  return kinds;
}

bool needsAovs(OutputKind kind) { return row(kind).aovs; }

std::vector<OutputKind> switchableOutputs() {
  std::vector<OutputKind> kinds;
  for (const KindRow& r : kKinds)
    if (r.spec == InSpec::On || r.spec == InSpec::Off) kinds.push_back(r.kind);
  return kinds;
}

std::set<OutputKind> defaultOutputs() {
  std::set<OutputKind> kinds;
  for (const KindRow& r : kKinds)
    if (r.spec == InSpec::On) kinds.insert(r.kind);
  return kinds;
}
bool isAnnotation(OutputKind kind) { return row(kind).annotation; }

const char* layoutName(DatasetLayout layout) { return layout == DatasetLayout::Multilayer ? "multilayer" : "files"; }

std::optional<DatasetLayout> layoutNamed(std::string_view name) {
  if (name == "files") return DatasetLayout::Files;
  if (name == "multilayer") return DatasetLayout::Multilayer;
  return std::nullopt;
}

const char* compressionName(FrameCompression compression) { return compression == FrameCompression::Zip ? "zip" : "rle"; }

std::optional<FrameCompression> compressionNamed(std::string_view name) {
  if (name == "rle") return FrameCompression::Rle;
  if (name == "zip") return FrameCompression::Zip;
  return std::nullopt;
}

bool FrameOutputPlan::anyAov() const {
  for (OutputKind kind : outputs)
    if (needsAovs(kind)) return true;
  return false;
}

std::vector<OutputKind> FrameOutputPlan::outputList() const { return {outputs.begin(), outputs.end()}; }

std::vector<OutputKind> FrameOutputPlan::fileKinds() const {
  if (layout == DatasetLayout::Multilayer) return {OutputKind::Multilayer};
  return outputList();
}

std::vector<OutputKind> FrameOutputPlan::gatheredKinds() const {
  std::vector<OutputKind> kinds;
  for (OutputKind kind : outputs)
    if (kind == OutputKind::Coco || (layout == DatasetLayout::Multilayer && isAnnotation(kind))) kinds.push_back(kind);
  return kinds;
}

std::string FrameOutputPlan::frameFolder(const std::string& camera, OutputKind kind) const {
  return camera + "/" + (kind == OutputKind::Rgb && eurocIntervalS ? "data" : outputName(kind));
}

std::string FrameOutputPlan::framePath(const std::string& camera, OutputKind kind, int index) const {
  if (kind == OutputKind::Rgb && eurocIntervalS) return frameFolder(camera, kind) + "/" + eurocImageName(index, *eurocIntervalS);
  const char* extension = isAnnotation(kind) ? "json"
                          : kind == OutputKind::Rgb ? (rgbFormat == "exr" ? "exr" : "png")
                          : kind == OutputKind::Instance || kind == OutputKind::Semantic ? "png"
                                                                                         : "exr";
  char name[32];
  std::snprintf(name, sizeof name, "%06d.%s", index, extension);
  return frameFolder(camera, kind) + "/" + name;
}

int64_t eurocTimestampNs(int frame, double intervalS) {
  return std::llround(static_cast<double>(frame) * intervalS * 1e9);
}

std::string eurocImageName(int frame, double intervalS) { return std::to_string(eurocTimestampNs(frame, intervalS)) + ".png"; }

std::string gatheredPath(const std::string& camera, OutputKind kind) { return camera + "/" + outputName(kind) + ".json"; }

std::vector<std::string> cameraFolderNames() {
  std::vector<std::string> names;
  for (const KindRow& r : kKinds) names.push_back(r.name);
  names.push_back("intrinsics");
  names.push_back("data");  // EuRoC/ASL
  return names;
}

bool isLayoutFile(const std::string& relative, const std::set<std::string>& cameras) {
  static const std::regex layout = [] {
    std::string kinds, annotations;
    for (const KindRow& r : kKinds) {
      kinds += (kinds.empty() ? "" : "|") + std::string(r.name);
      if (r.annotation) annotations += (annotations.empty() ? "" : "|") + std::string(r.name);
    }
    return std::regex("([^/]+)/((" + kinds + R"()/\d{6}\.(png|exr|json)|()" + annotations +
                      R"()\.json|intrinsics/((opencv|kalibr|camodocal)\.yaml|rays\.exr)|poses\.tum|data/\d{1,19}\.png|data\.csv|sensor\.yaml))");
  }();
  std::smatch m;
  return std::regex_match(relative, m, layout) && cameras.count(m[1].str());
}

}  // namespace omnicam
