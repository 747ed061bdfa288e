#include "output_kinds.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <regex>
#include <stdexcept>
#include <string>

namespace omnicam {

namespace {

using P = OutputPlane;
using E = OutputEncoding;
using T = ExrSampleType;

// Frame order. The one table of output kinds.
const OutputKindRow kKinds[] = {
    {.kind = OutputKind::Rgb, .name = "rgb", .plane = P::Colour, .encoding = E::ColourImage, .extension = "png",
     .fileChannels = {"R", "G", "B", "A"}, .layerChannels = {"R", "G", "B", "A"}, .spec = InSpec::Always},
    {.kind = OutputKind::Depth, .name = "depth", .plane = P::Depth, .encoding = E::FloatExr, .extension = "exr",
     .fileChannels = {"Z"}, .layerChannels = {"depth.Z"}, .layerType = T::Float, .aovs = true},
    {.kind = OutputKind::Instance, .name = "instance", .plane = P::Instance, .encoding = E::Uint16Png, .extension = "png",
     .fileChannels = {"I"}, .layerChannels = {"instance.I"}, .layerType = T::Uint, .aovs = true, .instanceIds = true},
    {.kind = OutputKind::Semantic, .name = "semantic", .plane = P::Semantic, .encoding = E::Uint16Png, .extension = "png",
     .fileChannels = {"I"}, .layerChannels = {"semantic.I"}, .layerType = T::Uint, .aovs = true, .instanceIds = true},
    {.kind = OutputKind::Normal, .name = "normal", .plane = P::Normal, .encoding = E::HalfExr, .extension = "exr",
     .fileChannels = {"X", "Y", "Z"}, .layerChannels = {"normal.X", "normal.Y", "normal.Z"}, .aovs = true},
    {.kind = OutputKind::Landmarks, .name = "landmarks", .plane = P::Annotation, .encoding = E::Json, .extension = "json",
     .annotation = true, .gathered = Gathered::InMultilayer},
    {.kind = OutputKind::Coco, .name = "coco", .plane = P::Annotation, .encoding = E::Json, .extension = "json", .aovs = true,
     .annotation = true, .spec = InSpec::Off, .classFilter = true, .instanceIds = true, .gathered = Gathered::Always,
     .aovNote = "COCO annotations come from the instance AOV"},
    {.kind = OutputKind::Multilayer, .name = "multilayer", .plane = P::Frame, .encoding = E::MultilayerExr, .extension = "exr",
     .spec = InSpec::Never},
};

}  // namespace

const OutputKindRow& outputRow(OutputKind kind) {
  for (const OutputKindRow& r : kKinds)
    if (r.kind == kind) return r;
  throw std::logic_error("output kind " + std::to_string(static_cast<int>(kind)) + " has no row");
}

const char* outputName(OutputKind kind) { return outputRow(kind).name; }

std::optional<OutputKind> outputNamed(std::string_view name) {
  for (const OutputKindRow& r : kKinds)
    if (name == r.name) return r.kind;
  return std::nullopt;
}

const std::vector<OutputKind>& allOutputKinds() {
  static const std::vector<OutputKind> kinds = [] {
    std::vector<OutputKind> all;
    for (const OutputKindRow& r : kKinds) all.push_back(r.kind);
    return all;
  }();
  return kinds;
}

bool needsAovs(OutputKind kind) { return outputRow(kind).aovs; }

std::vector<OutputKind> switchableOutputs() {
  std::vector<OutputKind> kinds;
  for (const OutputKindRow& r : kKinds)
    if (r.spec == InSpec::On || r.spec == InSpec::Off) kinds.push_back(r.kind);
  return kinds;
}

std::set<OutputKind> defaultOutputs() {
  std::set<OutputKind> kinds;
  for (const OutputKindRow& r : kKinds)
    if (r.spec == InSpec::On) kinds.insert(r.kind);
  return kinds;
}
bool isAnnotation(OutputKind kind) { return outputRow(kind).annotation; }

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
    if (outputRow(kind).gathered == Gathered::Always ||
        (layout == DatasetLayout::Multilayer && outputRow(kind).gathered == Gathered::InMultilayer))
      kinds.push_back(kind);
  return kinds;
}

std::string FrameOutputPlan::frameFolder(const std::string& camera, OutputKind kind) const {
  return camera + "/" + (kind == kColourOutput && eurocIntervalS ? "data" : outputName(kind));
}

std::string FrameOutputPlan::framePath(const std::string& camera, OutputKind kind, int index) const {
  if (kind == kColourOutput && eurocIntervalS) return frameFolder(camera, kind) + "/" + eurocImageName(index, *eurocIntervalS);
  const char* extension = kind == kColourOutput && rgbFormat == "exr" ? "exr" : outputRow(kind).extension;
  char name[32];
  std::snprintf(name, sizeof name, "%06d.%s", index, extension);
  return frameFolder(camera, kind) + "/" + name;
}

bool isFramePath(const std::string& path, const std::string& camera, OutputKind kind, int index) {
  FrameOutputPlan plan;  // the files layout; a multilayer frame's file is its kind's
  for (const char* format : {"png", "exr"}) {
    plan.rgbFormat = format;
    if (path == plan.framePath(camera, kind, index)) return true;
  }
  const std::string euroc = camera + "/data/";
  return kind == kColourOutput && path.starts_with(euroc) && path.ends_with(".png") && path.size() > euroc.size() + 4 &&
         path.size() <= euroc.size() + 19 + 4 && path.find_first_not_of("0123456789", euroc.size()) == path.size() - 4;
}

namespace {

// The interval in whole nanoseconds, when it is the double nearest a whole number of them (the
// double nearest 0.05 s is 50 000 000 ns and a tiny fraction; 1/30 s is no whole number).
std::optional<int64_t> wholeNanoseconds(double intervalS) {
  const double whole = std::round(intervalS * 1e9);
  if (whole < 1.0 || whole / 1e9 != intervalS) return std::nullopt;
  return static_cast<int64_t>(whole);
}

// The double nearest `ns` nanoseconds in seconds, rounded once: from the decimal text, since
// ns / 1e9 in doubles rounds twice once ns exceeds 2^53.
double secondsOfNanoseconds(int64_t ns) {
  char text[40];
  const int length = std::snprintf(text, sizeof text, "%lld.%09lld", static_cast<long long>(ns / 1000000000),
                                   static_cast<long long>(ns % 1000000000));
  double seconds = 0.0;
  std::from_chars(text, text + length, seconds);
  return seconds;
}

}  // namespace

double frameTimestampSeconds(int frame, double intervalS) {
  if (const std::optional<int64_t> ns = wholeNanoseconds(intervalS)) return secondsOfNanoseconds(frame * *ns);
  return static_cast<double>(frame) * intervalS;
}

int64_t frameTimestampNs(int frame, double intervalS) {
  if (const std::optional<int64_t> ns = wholeNanoseconds(intervalS)) return frame * *ns;
  return std::llround(static_cast<double>(frame) * intervalS * 1e9);
}

std::string eurocImageName(int frame, double intervalS) { return std::to_string(frameTimestampNs(frame, intervalS)) + ".png"; }

std::string gatheredPath(const std::string& camera, OutputKind kind) { return camera + "/" + outputName(kind) + ".json"; }

std::vector<std::string> cameraFolderNames() {
  std::vector<std::string> names;
  for (const OutputKindRow& r : kKinds) names.push_back(r.name);
  names.push_back("intrinsics");
  names.push_back("data");         // EuRoC/ASL
  names.push_back("calibration");  // a calibration sequence's files
  return names;
}

bool isLayoutFile(const std::string& relative, const std::set<std::string>& cameras) {
  static const std::regex layout = [] {
    std::string kinds, annotations;
    for (const OutputKindRow& r : kKinds) {
      kinds += (kinds.empty() ? "" : "|") + std::string(r.name);
      if (r.annotation) annotations += (annotations.empty() ? "" : "|") + std::string(r.name);
    }
    return std::regex("([^/]+)/((" + kinds + R"()/\d{6}\.(png|exr|json)|()" + annotations +
                      R"()\.json|intrinsics/((opencv|kalibr|camodocal)\.yaml|rays\.exr)|poses\.tum|data/\d{1,19}\.png|data\.csv|sensor\.yaml|)"
                      R"(calibration/(target\.yaml|corners\.json|opencv_corners\.yml|images\.bag)))");
  }();
  std::smatch m;
  return std::regex_match(relative, m, layout) && cameras.count(m[1].str());
}

}  // namespace omnicam
