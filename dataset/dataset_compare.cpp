#include "dataset_compare.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "atomic_file.h"
#include "dataset_reader.h"
#include "dataset_runner.h"
#include "dataset_shards.h"
#include "errors.h"
#include "json_text.h"
#include "manifest.h"
#include "markup.h"
#include "memory_budget.h"
#include "number_format.h"
#include "output_kinds.h"
#include "render_records.h"
#include "safe_files.h"
#include "sidecar.h"

namespace omnicam {

namespace fs = std::filesystem;

namespace {

// B's image for A's `relative` path when B has no manifest: the same path, .png or .exr (a
// link there is not followed: it is reported when the image is read).
std::optional<std::string> layoutFileIfAny(const std::string& dirB, const std::string& relative) {
  for (const char* ext : {".png", ".exr"}) {
    const std::string candidate = fs::path(relative).replace_extension(ext).string();
    if (entryInside(dirB, candidate) != EntryKind::Missing) return candidate;
  }
  return std::nullopt;
}

// layoutFileIfAny, or InputError naming both names it looked for.
std::string layoutFile(const std::string& dirB, const std::string& relative) {
  if (std::optional<std::string> file = layoutFileIfAny(dirB, relative)) return *file;
  const std::string stem = fs::path(relative).replace_extension("").string();
  throw InputError(showPath(dirB) + ": has neither " + showPath(stem + ".png") + " nor " + showPath(stem + ".exr") +
                   ", the image to compare with the first dataset's " + showPath(relative) +
                   " (a folder without manifest.json must follow the dataset layout)");
}

// The file holding a camera frame's colour: its rgb image (files layout) or its frame OpenEXR
// (multilayer layout, whose R, G, B, A channels image readers take as the colour).
const FileRecord* colourFile(const CameraFrame& frame) {
  const FileRecord* rgb = frame.file(kColourOutput);
  return rgb ? rgb : frame.file(OutputKind::Multilayer);
}

// An image of a dataset folder: read without following links, a regular file of bounded size; a
// multilayer frame by the dataset reader's own decoder (which keeps a NaN as it is: the
// comparison counts it), an image file by the image decoder (which reads it as 0 and counts it).
struct DatasetImage {
  ImageRGBA image;
  long nonFinitePixels = 0;
  bool holdsAlpha = true;  // a multilayer frame always has A
};
DatasetImage readDatasetImage(const std::string& dir, const std::string& relative, bool layered) {
  const std::string bytes = readFileInside(dir, relative, kMaxDatasetFileBytes);
  const std::string name = showPath((fs::path(dir) / relative).string());
  if (layered) return {multilayerFrameColour(bytes, name)};
  ImageRowReader reader = ImageRowReader::openMemory(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), name);
  reader.requireColour();
  DatasetImage read{reader.readRemaining()};
  read.nonFinitePixels = reader.nonFinitePixels();
  read.holdsAlpha = reader.holdsAlpha();
  return read;
}

struct FrameFilesComparison {
  CompareResult result;
  int64_t bytes = 0;  // the memory the comparison held at once
};

// One frame of A against B's: each image file read whole (bounded by kMaxDatasetFileBytes), its
// pixels decoded a band of rows at a time (compareImageRows) — a multilayer frame whole, by the
// dataset reader's own decoder.
FrameFilesComparison compareFrameFiles(const std::string& dirA, const std::string& dirB, const FrameComparison& f,
                                       const CompareOptions& options) {
  if (f.layeredA || f.layeredB) {
    DatasetImage a = readDatasetImage(dirA, f.fileA, f.layeredA), b = readDatasetImage(dirB, f.fileB, f.layeredB);
    if (a.image.width != b.image.width || a.image.height != b.image.height)
      throw InputError(showPath((fs::path(dirB) / f.fileB).string()) + ": frame " + std::to_string(f.index) + " of camera " +
                       quote(f.camera) + " is " + std::to_string(b.image.width) + "x" + std::to_string(b.image.height) + ", A's is " +
                       std::to_string(a.image.width) + "x" + std::to_string(a.image.height));
    // Both images as floats, and their decoding (the larger of the multilayer reader's planes plus
    // interleaved copy and the decoder's raw channels).
    const int64_t bytes = (static_cast<int64_t>(a.image.width) * a.image.height + static_cast<int64_t>(b.image.width) * b.image.height) * 16 * 3;
    const ColourImagePair pair{std::move(a.image), std::move(b.image), a.nonFinitePixels, b.nonFinitePixels, a.holdsAlpha, b.holdsAlpha};
    return {compareImagePair(pair, options), bytes};
  }
  const std::string bytesA = readFileInside(dirA, f.fileA, kMaxDatasetFileBytes);
  const std::string bytesB = readFileInside(dirB, f.fileB, kMaxDatasetFileBytes);
  ImageRowReader a = ImageRowReader::openMemory(reinterpret_cast<const unsigned char*>(bytesA.data()), bytesA.size(),
                                                showPath((fs::path(dirA) / f.fileA).string()));
  ImageRowReader b = ImageRowReader::openMemory(reinterpret_cast<const unsigned char*>(bytesB.data()), bytesB.size(),
                                                showPath((fs::path(dirB) / f.fileB).string()));
  if (a.width() != b.width() || a.height() != b.height())
    throw InputError(showPath((fs::path(dirB) / f.fileB).string()) + ": frame " + std::to_string(f.index) + " of camera " +
                     quote(f.camera) + " is " + std::to_string(b.width()) + "x" + std::to_string(b.height()) + ", A's is " +
                     std::to_string(a.width()) + "x" + std::to_string(a.height()));
  requireMemory(imageRowsCompareBytes(a, b), "comparing two frames");
  return {compareImageRows(a, b, options), static_cast<int64_t>(bytesA.size() + bytesB.size()) + imageRowsCompareBytes(a, b)};
}

std::string frameLabel(const FrameComparison& f) {
  char text[96];
  std::snprintf(text, sizeof text, "frame %06d %s", f.index, f.camera.c_str());
  return text;
}

std::string psnrText(double psnr) {
  if (std::isinf(psnr)) return "inf";
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", psnr);
  return text;
}

}  // namespace

namespace {

// Every camera any finished frame of the manifest has, sorted.
std::set<std::string> camerasOf(const DatasetManifest& m) {
  std::set<std::string> names;
  for (const auto& [index, frame] : m.frames)
    for (const auto& [camera, files] : frame.cameras) names.insert(camera);
  return names;
}

std::string cameraList(const std::set<std::string>& names) {
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "" : ", ") + showPath(name);
  return list.empty() ? "none" : list;
}

// "3 only in A (first 7), 0 only in B (first -)".
std::string onlyInText(const std::vector<int>& onlyA, const std::vector<int>& onlyB) {
  return std::to_string(onlyA.size()) + " only in A (first " + (onlyA.empty() ? "-" : std::to_string(onlyA[0])) + "), " +
         std::to_string(onlyB.size()) + " only in B (first " + (onlyB.empty() ? "-" : std::to_string(onlyB[0])) + ")";
}

// B's manifest lists A's frames, of the same cameras: the cameras first, since datasets of other
// rigs differ in their frames too. Every frame (exit 2 otherwise), or with `commonOnly` the ones
// both hold: A's others are dropped here and said in a note.
void matchFrames(DatasetManifest& a, const DatasetManifest& b, const std::string& dirA, const std::string& dirB, bool commonOnly,
                 std::vector<std::string>& notes) {
  const std::set<std::string> camerasA = camerasOf(a), camerasB = camerasOf(b);
  if (camerasA != camerasB)
    throw InputError(showPath(dirB) + ": cameras do not match " + showPath(dirA) + ": A has " + cameraList(camerasA) + ", B has " +
                     cameraList(camerasB));
  std::vector<int> onlyA, onlyB;
  for (const auto& [index, frame] : a.frames)
    if (!b.frames.count(index)) onlyA.push_back(index);
  for (const auto& [index, frame] : b.frames)
    if (!a.frames.count(index)) onlyB.push_back(index);
  if (onlyA.empty() && onlyB.empty()) return;
  if (!commonOnly)
    throw InputError(showPath(dirB) + ": frames do not match " + showPath(dirA) + ": " + onlyInText(onlyA, onlyB) +
                     " (--common-frames compares the frames both hold)");
  if (onlyA.size() == a.frames.size())
    throw InputError(showPath(dirB) + ": holds none of " + showPath(dirA) + "'s frames: " + onlyInText(onlyA, onlyB));
  for (int index : onlyA) a.frames.erase(index);
  notes.push_back("compared the " + countOf(static_cast<long long>(a.frames.size()), "frame") + " both hold; left out: " +
                  onlyInText(onlyA, onlyB));
}

// With `commonOnly`, A's frames of which a folder without manifest has no image are dropped
// (said in a note); else each must be there.
void matchFolderFrames(DatasetManifest& a, const std::string& dirA, const std::string& dirB, bool commonOnly,
                       std::vector<std::string>& notes) {
  if (!commonOnly) return;
  std::vector<int> onlyA;
  for (const auto& [index, frame] : a.frames)
    for (const auto& [camera, files] : frame.cameras) {
      const FileRecord* rgb = colourFile(files);
      if (rgb && !layoutFileIfAny(dirB, rgb->path)) {
        onlyA.push_back(index);
        break;
      }
    }
  if (onlyA.empty()) return;
  if (onlyA.size() == a.frames.size()) throw InputError(showPath(dirB) + ": holds no image of " + showPath(dirA) + "'s frames");
  for (int index : onlyA) a.frames.erase(index);
  notes.push_back("compared the " + countOf(static_cast<long long>(a.frames.size()), "frame") + " with images in both; left out: " +
                  std::to_string(onlyA.size()) + " only in A (first " + std::to_string(onlyA[0]) + ")");
}

// Each frame's colour file of each camera in A beside B's: from B's manifest when it has one
// (same frames, cameras and poses), else at the same place in B's folder.
std::vector<FrameComparison> pairFrames(const DatasetManifest& a, const std::optional<DatasetManifest>& b,
                                        const std::string& dirA, const std::string& dirB) {
  std::vector<FrameComparison> pairs;
  for (const auto& [index, frame] : a.frames) {
    for (const auto& [camera, files] : frame.cameras) {
      FrameComparison f;
      f.index = index;
      f.camera = camera;
      const FileRecord* rgb = colourFile(files);
      // A camera name is a folder of the dataset: messages show it as they show paths.
      if (!rgb) throw InputError(showPath(dirA) + ": frame " + std::to_string(index) + " " + showPath(camera) + ": no rgb file");
      f.fileA = rgb->path;
      f.layeredA = rgb == files.file(OutputKind::Multilayer);
      if (b) {
        const FrameRecord& other = b->frames.at(index);
        const auto cam = other.cameras.find(camera);
        if (cam == other.cameras.end())
          throw InputError(showPath(dirB) + ": frame " + std::to_string(index) + " has no camera " + quote(camera) + " (A has it)");
        if (!samePose(cam->second.pose, files.pose))
          throw InputError(showPath(dirB) + ": frame " + std::to_string(index) + " camera " + showPath(camera) + ": pose " +
                           poseText(cam->second.pose) + " differs from A's " + poseText(files.pose));
        const FileRecord* rgbB = colourFile(cam->second);
        if (!rgbB) throw InputError(showPath(dirB) + ": frame " + std::to_string(index) + " " + showPath(camera) + ": no rgb file");
        f.fileB = rgbB->path;
        f.layeredB = rgbB == cam->second.file(OutputKind::Multilayer);
      } else {
        f.fileB = layoutFile(dirB, f.fileA);
      }
      pairs.push_back(f);
    }
    if (b && b->frames.at(index).cameras.size() != frame.cameras.size())
      throw InputError(showPath(dirB) + ": frame " + std::to_string(index) + " has " + std::to_string(b->frames.at(index).cameras.size()) +
                       " cameras, A has " + std::to_string(frame.cameras.size()));
  }
  return pairs;
}

// Each camera's rig in a manifest's header, by name.
std::map<std::string, nlohmann::json> headerRigs(const DatasetManifest& m) {
  std::map<std::string, nlohmann::json> rigs;
  for (const nlohmann::json& camera : m.header.value("cameras", nlohmann::json::array()))
    if (camera.is_object() && camera.contains("name") && camera["name"].is_string()) rigs[camera["name"]] = camera.value("rig", nlohmann::json());
  return rigs;
}

// Where the two datasets' cameras differ: each camera's rig of the header, then the rigs frames
// hold of their own (a vibrating robot's), counted when the headers agree.
std::vector<std::string> rigNotes(const DatasetManifest& a, const DatasetManifest& b) {
  std::vector<std::string> notes;
  const std::map<std::string, nlohmann::json> rigsA = headerRigs(a), rigsB = headerRigs(b);
  std::set<std::string> differing;
  for (const auto& [name, rig] : rigsA) {
    const auto other = rigsB.find(name);
    if (other == rigsB.end() || other->second == rig) continue;
    differing.insert(name);
    notes.push_back("camera " + quote(name) + ": the datasets' rigs differ (" + jsonDifferenceList(rig, other->second, "the whole rig") +
                    "): A and B are images of different cameras");
  }
  int frames = 0;
  std::string first;
  for (const auto& [index, frame] : a.frames) {
    const auto other = b.frames.find(index);
    if (other == b.frames.end()) continue;
    bool differs = false;
    for (const auto& [camera, files] : frame.cameras) {
      const auto cam = other->second.cameras.find(camera);
      if (differing.count(camera) || cam == other->second.cameras.end() || !rigsA.count(camera) || !rigsB.count(camera)) continue;
      const nlohmann::json rigA = files.rig ? rigToJson(*files.rig) : rigsA.at(camera);
      const nlohmann::json rigB = cam->second.rig ? rigToJson(*cam->second.rig) : rigsB.at(camera);
      if (rigA == rigB) continue;
      if (first.empty())
        first = "frame " + std::to_string(index) + " camera " + quote(camera) + ": " + jsonDifferenceList(rigA, rigB, "the whole rig");
      differs = true;
    }
    frames += differs;
  }
  if (frames)
    notes.push_back(std::to_string(frames) + " of " + std::to_string(a.frames.size()) +
                    " frames were rendered with rigs that differ between A and B (a vibrating robot's; first: " + first + ")");
  // The robot's own tilt (a rocking robot's, or its vibration's) tilts every camera it carries.
  int tilted = 0;
  std::string firstTilt;
  for (const auto& [index, frame] : a.frames) {
    const auto other = b.frames.find(index);
    if (other == b.frames.end() || other->second.robotTiltDeg == frame.robotTiltDeg) continue;
    if (!tilted++)
      firstTilt = "frame " + std::to_string(index) + ": A (" + roundTrip(frame.robotTiltDeg[0]) + ", " + roundTrip(frame.robotTiltDeg[1]) +
                  ")°, B (" + roundTrip(other->second.robotTiltDeg[0]) + ", " + roundTrip(other->second.robotTiltDeg[1]) + ")°";
  }
  if (tilted)
    notes.push_back(std::to_string(tilted) + " of " + std::to_string(a.frames.size()) +
                    " frames have the robot tilted otherwise in A and B (robot_tilt_deg, roll and pitch; first: " + firstTilt + ")");
  return notes;
}

// Compares every pair, as many at once as memory holds.
void compareAll(std::vector<FrameComparison>& frames, const std::string& dirA, const std::string& dirB,
                const DatasetCompareOptions& options) {
  // Each camera's first pair, one at a time, sizes the rest: as many comparisons run at once as
  // memory holds for the largest (a dataset's frames share a size per camera; each decode checks
  // its own need again).
  std::vector<int64_t> bytes(frames.size(), 0);
  const auto compareFrame = [&](size_t k) {
    FrameComparison& f = frames[k];
    const FrameFilesComparison compared = compareFrameFiles(dirA, dirB, f, options.image);
    f.result = compared.result;
    bytes[k] = compared.bytes;
    f.failed = !options.thresholds.failures(f.result).empty();
  };
  std::set<std::string> sized;
  std::vector<size_t> rest;
  for (size_t k = 0; k < frames.size(); ++k) {
    if (sized.insert(frames[k].camera).second) compareFrame(k);
    else rest.push_back(k);
  }
  const int64_t bytesEach = *std::max_element(bytes.begin(), bytes.end());
  const int concurrency = concurrencyWithin(bytesEach, tbb::this_task_arena::max_concurrency(), "comparing two frames");
  tbb::task_arena arena(concurrency);
  arena.execute([&] { tbb::parallel_for(size_t{0}, rest.size(), [&](size_t r) { compareFrame(rest[r]); }); });
}

}  // namespace

DatasetCompareResult compareDatasets(const std::string& dirA, const std::string& dirB,
                                     const DatasetCompareOptions& options) {
  DatasetManifest a = readMergedDatasetManifest(SafeFolder(dirA));
  std::error_code ec;
  if (!fs::is_directory(dirB, ec)) throw InputError(showPath(dirB) + ": not a folder");
  std::optional<DatasetManifest> b;
  // A folder of unmerged shards is a dataset in the making, not a folder of images.
  if (entryInside(dirB, kManifestName) != EntryKind::Missing || !shardCountsIn(dirB).empty())
    b = readMergedDatasetManifest(SafeFolder(dirB));
  DatasetCompareResult result;
  if (b)
    matchFrames(a, *b, dirA, dirB, options.commonFramesOnly, result.notes);
  else
    matchFolderFrames(a, dirA, dirB, options.commonFramesOnly, result.notes);
  result.frames = pairFrames(a, b, dirA, dirB);
  if (b) {
    const std::vector<std::string> settings = recordedSettingNotes(a.header, b->header, manifestSettings());
    result.notes.insert(result.notes.end(), settings.begin(), settings.end());
    const std::vector<std::string> rigs = rigNotes(a, *b);
    result.notes.insert(result.notes.end(), rigs.begin(), rigs.end());
  }
  if (result.frames.empty()) throw InputError(showPath(dirA) + ": no finished frames to compare");
  compareAll(result.frames, dirA, dirB, options);
  result.minPsnrDb = std::numeric_limits<double>::infinity();
  double finiteSum = 0.0;
  int finite = 0;
  for (const FrameComparison& f : result.frames) {
    result.failures += f.failed;
    result.minPsnrDb = std::min(result.minPsnrDb, f.result.psnrDb);
    result.meanSsim += f.result.ssim / result.frames.size();
    result.maxAbs = std::max(result.maxAbs, f.result.maxAbs);
    result.maxAbsAlpha = std::max(result.maxAbsAlpha, f.result.maxAbsAlpha);
    result.alphaCompared += f.result.alphaCompared;
    if (std::isfinite(f.result.psnrDb)) finiteSum += f.result.psnrDb, ++finite;
    else ++result.identical;
  }
  result.meanPsnrDb = finite ? finiteSum / finite : std::numeric_limits<double>::infinity();
  return result;
}

std::string datasetAlphaText(const DatasetCompareResult& result) {
  if (!result.alphaCompared) return "not compared (no image pair has an alpha channel in both)";
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", result.maxAbsAlpha);
  return text;
}

namespace {

// A report's image link as its page writes it (percent-encoded, then escaped for HTML).
std::string imageLink(const std::string& assetsName, const std::string& name) {
  return "<img src=\"" + escapeMarkup(urlPath(assetsName + "/" + name)) + "\">";
}

// How a dataset comparison report omnicam writes begins (a page saved by a browser has the same
// NAME.html beside NAME_files/ layout, but not this opening); reports written before the
// generator mark began without it.
constexpr const char* kReportGenerator = "<meta name=\"generator\" content=\"omnicam dataset compare\">";
const std::string kReportOpening =
    std::string("<!doctype html><html><head><meta charset=\"utf-8\">") + kReportGenerator + "<title>omnicam dataset comparison</title>";
const std::string kReportOpeningBeforeMark = "<!doctype html><html><head><meta charset=\"utf-8\"><title>omnicam dataset comparison</title>";

bool isOmnicamReport(const std::string& page) {
  return page.rfind(kReportOpening, 0) == 0 || page.rfind(kReportOpeningBeforeMark, 0) == 0;
}

// The name of one of a report's images: frame, camera, then a, b or diff (000012_cam0_diff.png).
bool isReportImageName(const std::string& name) {
  static const std::regex form(R"(\d{6}_.+_(a|b|diff)\.png)");
  return std::regex_match(name, form);
}

// The page `name` in `folder` if it is a report omnicam wrote, else "".
std::string omnicamReportAt(const SafeFolder& folder, const std::string& name) {
  if (folder.entry(name) != EntryKind::File) return "";
  try {
    const std::string page = folder.readFile(name, 64 << 20);
    return isOmnicamReport(page) ? page : "";
  } catch (const InputError&) {
    return "";  // larger than any report, or gone
  }
}

// The images an earlier report at the same path showed that the new one does not (frames no
// longer among the worst): each a regular file in the images' folder, named as a report names
// its images, that the earlier page — one omnicam wrote — links to, and that no other report
// sharing the folder (r.htm beside r.html: one stem, one r_files/) links to. Anything else stays.
std::vector<std::string> imagesOnlyTheEarlierReportShowed(const SafeFolder& folder, const std::string& pageName,
                                                          const std::string& assetsName, const std::set<std::string>& shown) {
  if (folder.entry(assetsName) != EntryKind::Folder) return {};
  const std::string earlierPage = omnicamReportAt(folder, pageName);
  if (earlierPage.empty()) return {};
  std::vector<std::string> otherPages;
  std::error_code ec;
  const std::string stem = fs::path(pageName).stem().string();
  for (fs::directory_iterator it(folder.path(), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name != pageName && fs::path(name).stem().string() == stem)
      if (std::string page = omnicamReportAt(folder, name); !page.empty()) otherPages.push_back(std::move(page));
  }
  std::vector<std::string> stale;
  for (fs::directory_iterator it(fs::path(folder.path()) / assetsName, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const std::string link = imageLink(assetsName, name);
    if (shown.count(name) || !isReportImageName(name) || earlierPage.find(link) == std::string::npos) continue;
    if (std::none_of(otherPages.begin(), otherPages.end(), [&](const std::string& page) { return page.find(link) != std::string::npos; }))
      stale.push_back(name);
  }
  return stale;
}

}  // namespace

std::string reportAssetsFolder(const std::string& reportPath) {
  const fs::path report(reportPath);
  return (report.parent_path() / (report.stem().string() + "_files")).string();
}

void writeDatasetCompareReport(const std::string& reportPath, const std::string& dirA, const std::string& dirB,
                               const DatasetCompareResult& result, const DatasetCompareOptions& options) {
  const fs::path report(reportPath);
  const std::string assetsName = fs::path(reportAssetsFolder(reportPath)).filename().string();
  // The images' folder is omnicam's, beside the report: a link there (someone's, in a shared
  // folder) is refused, not followed.
  const SafeFolder reportFolder(report.parent_path().empty() ? "." : report.parent_path().string());
  // The images are encoded first, then written with the page through one group: a report that
  // cannot be finished leaves neither its images nor its page (nor replaces an earlier one's).
  std::vector<FileBytes> images;
  const auto addPng = [&](const std::string& name, const ImageRGBA& image) {
    images.push_back({assetsName + "/" + name, encodeImage(name, image)});
  };
  {
    std::vector<const FrameComparison*> order;
    for (const FrameComparison& f : result.frames) order.push_back(&f);
    std::stable_sort(order.begin(), order.end(), [](auto* x, auto* y) { return x->result.psnrDb < y->result.psnrDb; });

    std::ostringstream html;
    html << kReportOpening << "<style>"
            "body{font-family:sans-serif;margin:2em}td,th{padding:2px 8px;text-align:right}"
            "td:first-child,th:first-child{text-align:left}.fail{color:#b00;font-weight:bold}"
            "figure{display:inline-block;margin:4px}img{width:240px;image-rendering:pixelated}</style></head><body>"
         << "<h1>Dataset comparison</h1><p>A: <code>" << escapeMarkup(dirA) << "</code><br>B: <code>" << escapeMarkup(dirB)
         << "</code></p><p>" << result.frames.size() << " images compared; mean PSNR " << psnrText(result.meanPsnrDb)
         << " dB" << (result.identical ? " (of the " + std::to_string(result.frames.size() - static_cast<size_t>(result.identical)) + " whose colour differs)" : "")
         << ", worst " << psnrText(result.minPsnrDb) << " dB, mean SSIM " << result.meanSsim << ", max abs " << result.maxAbs
         << ", max abs of alpha " << datasetAlphaText(result) << "; " << (options.image.discOnly ? "inside the mirror disc" : "every pixel")
         << ", tolerance " << options.image.tolerance;
    const CompareThresholds& t = options.thresholds;
    if (t.any()) {
      html << "; thresholds:";
      if (t.minPsnrDb) html << " PSNR " << *t.minPsnrDb << " dB";
      if (t.maxAbs) html << " max abs " << *t.maxAbs;
      html << ": <span class=\"" << (result.failures ? "fail" : "") << "\">" << result.failures << " failing</span>";
    } else {
      html << "; no threshold given: nothing checked";
    }
    html << "</p>";
    for (const std::string& note : result.notes) html << "<p><b>Note:</b> " << escapeMarkup(note) << "</p>";
    html << "<h2>Worst frames</h2><p>Heat map: |A − B| (max over channels), black 0 → white at " << options.diffScale
         << ".</p>";
    const size_t worst = std::min<size_t>(order.size(), static_cast<size_t>(std::max(0, options.worstFrames)));
    for (size_t k = 0; k < worst; ++k) {
      const FrameComparison& f = *order[k];
      const ImageRGBA imageA = readDatasetImage(dirA, f.fileA, f.layeredA).image;
      const ImageRGBA imageB = readDatasetImage(dirB, f.fileB, f.layeredB).image;
      char stem[96];
      std::snprintf(stem, sizeof stem, "%06d_%s", f.index, f.camera.c_str());
      const std::string names[3] = {std::string(stem) + "_a.png", std::string(stem) + "_b.png", std::string(stem) + "_diff.png"};
      addPng(names[0], imageA);
      addPng(names[1], imageB);
      addPng(names[2], differenceHeatmap(imageA, imageB, options.diffScale));
      html << "<h3>" << escapeMarkup(frameLabel(f)) << ": " << psnrText(f.result.psnrDb) << " dB</h3>";
      const char* captions[3] = {"A", "B", "|A − B|"};
      for (int i = 0; i < 3; ++i)
        html << "<figure>" << imageLink(assetsName, names[i]) << "<figcaption>" << captions[i] << "</figcaption></figure>";
    }
    html << "<h2>All frames</h2><table><tr><th>frame</th><th>camera</th><th>PSNR (dB)</th><th>SSIM</th><th>RMSE</th>"
            "<th>max abs</th></tr>";
    for (const FrameComparison& f : result.frames)
      html << "<tr" << (f.failed ? " class=\"fail\"" : "") << "><td>" << f.index << "</td><td>" << escapeMarkup(f.camera)
           << "</td><td>" << psnrText(f.result.psnrDb) << "</td><td>" << f.result.ssim << "</td><td>" << f.result.rmse
           << "</td><td>" << f.result.maxAbs << "</td></tr>";
    html << "</table></body></html>\n";
    const std::string page = html.str();
    std::set<std::string> shown;
    for (const FileBytes& image : images) shown.insert(fs::path(image.path).filename().string());
    const std::vector<std::string> stale =
        imagesOnlyTheEarlierReportShowed(reportFolder, report.filename().string(), assetsName, shown);
    AtomicFileGroup group;
    for (const FileBytes& image : images)
      reportFolder.stageFile(group, image.path, std::string_view(reinterpret_cast<const char*>(image.bytes.data()), image.bytes.size()));
    group.stage(reportPath, page);
    group.commit();
    for (const std::string& name : stale) reportFolder.removeFile(assetsName + "/" + name);
  }
}

std::string datasetCompareJUnit(const std::string& dirA, const std::string& dirB, const DatasetCompareResult& result,
                                const DatasetCompareOptions& options) {
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n<testsuite name=\"omnicam compare "
      << escapeMarkup(dirA) << " vs " << escapeMarkup(dirB) << "\" tests=\"" << result.frames.size() << "\" failures=\""
      << result.failures << "\" errors=\"0\" skipped=\"" << (options.thresholds.any() ? 0 : result.frames.size()) << "\">\n";
  for (const FrameComparison& f : result.frames) {
    xml << "  <testcase classname=\"" << escapeMarkup(f.camera) << "\" name=\"" << escapeMarkup(frameLabel(f)) << "\">";
    if (!options.thresholds.any()) {
      xml << "\n    <skipped message=\"no threshold given (--fail-psnr, --fail-max): nothing checked\"/>\n  ";
    } else if (f.failed) {
      std::string failed;
      for (const std::string& why : options.thresholds.failures(f.result)) failed += (failed.empty() ? "" : ", ") + why;
      xml << "\n    <failure message=\"" << escapeMarkup(failed) << "\">" << escapeMarkup(f.fileA + " vs " + f.fileB) << "</failure>\n  ";
    }
    xml << "<system-out>psnr_db=" << psnrText(f.result.psnrDb) << " ssim=" << f.result.ssim << " rmse=" << f.result.rmse
        << " max_abs=" << f.result.maxAbs << " max_abs_alpha=" << alphaText(f.result) << "</system-out></testcase>\n";
  }
  xml << "</testsuite>\n</testsuites>\n";
  return xml.str();
}

}  // namespace omnicam
