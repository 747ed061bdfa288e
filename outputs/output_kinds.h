#pragma once
// The outputs a dataset frame can have, and the two layouts that store them
// (docs/dataset-format.md): every place that names, files, checks or decodes an output asks
// here, so a new output is one new row of the table in output_kinds.cpp.
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "exr_channels.h"

namespace omnicam {

// What one camera's frame records. Multilayer is that layout's one file per frame holding the others.
enum class OutputKind { Rgb, Depth, Instance, Semantic, Normal, Landmarks, Coco, Multilayer };

// files: one file per output and frame (<camera>/<kind>/NNNNNN.<ext>); multilayer: one OpenEXR per
// frame holding colour and every AOV as named channels, its annotations in the file's header and
// gathered into one file per camera (<camera>/<kind>.json) when the dataset is complete.
enum class DatasetLayout { Files, Multilayer };
// How the multilayer layout's frame files are compressed (both lossless).
enum class FrameCompression { Rle, Zip };

// Where a kind's values come from in a rendered frame, and how its own file stores them.
enum class OutputPlane { Colour, Depth, Normal, Instance, Semantic, Annotation, Frame };
enum class OutputEncoding { ColourImage, FloatExr, HalfExr, Uint16Png, Json, MultilayerExr };
// Whether a spec's `outputs` switches the kind on and off, and its default there.
enum class InSpec { Always, On, Off, Never };
// When an annotation is gathered into one file per camera once the dataset is complete.
enum class Gathered { Never, Always, InMultilayer };

// One kind, declared once: every encoder, decoder, the multilayer writer, the plan, `compare` and
// Python iterate over these rows.
struct OutputKindRow {
  OutputKind kind;
  const char* name;                        // the manifest's key, the folder, Python's key
  OutputPlane plane;
  OutputEncoding encoding;                 // its own file (files layout)
  const char* extension;                   // of that file (colour: the plan's rgb format)
  std::vector<std::string> fileChannels = {};   // that file's OpenEXR channels, or the image's RGBA
  std::vector<std::string> layerChannels = {};  // its channels in a multilayer frame (none: in the header)
  ExrSampleType layerType = ExrSampleType::Half;
  bool aovs = false;                       // rendered from the engine's AOVs, or derived from them
  bool annotation = false;                 // JSON
  InSpec spec = InSpec::On;
  bool classFilter = false;                // a spec may give {"classes": [names]} (COCO)
  bool instanceIds = false;                // made of 16-bit instance ids
  Gathered gathered = Gathered::Never;
  const char* aovNote = "";                // why it needs AOVs, where that is not obvious
  // Values per pixel when decoded (the reader and Python): the channels it has.
  size_t valuesPerPixel() const { return fileChannels.size(); }
};
const OutputKindRow& outputRow(OutputKind kind);
// The kind that holds a frame's colour (every frame has it).
inline constexpr OutputKind kColourOutput = OutputKind::Rgb;

// The kind's name: the manifest's key for its files and the folder they are in.
const char* outputName(OutputKind kind);
std::optional<OutputKind> outputNamed(std::string_view name);
// Every kind, in the order frames list them.
const std::vector<OutputKind>& allOutputKinds();
// Rendered by the engine beside the colour (its AOVs), or derived from them.
bool needsAovs(OutputKind kind);
// Annotations (JSON): in the multilayer layout, gathered per camera instead of stored per frame.
bool isAnnotation(OutputKind kind);
// The outputs a spec switches on or off by name (`"depth": true`; colour is always written), and
// those on unless switched off.
std::vector<OutputKind> switchableOutputs();
std::set<OutputKind> defaultOutputs();

const char* layoutName(DatasetLayout layout);
std::optional<DatasetLayout> layoutNamed(std::string_view name);
const char* compressionName(FrameCompression compression);
std::optional<FrameCompression> compressionNamed(std::string_view name);

// What each camera's frames record, and how.
struct FrameOutputPlan {
  DatasetLayout layout = DatasetLayout::Files;
  FrameCompression compression = FrameCompression::Rle;  // multilayer frame files
  std::string rgbFormat = "png";      // the files layout's colour file: "png" or "exr"
  std::set<OutputKind> outputs{OutputKind::Rgb};  // never Multilayer
  std::set<uint16_t> cocoClasses;     // class ids the COCO annotations cover
  // The EuRoC/ASL layout's frame interval (euroc_files.h): colour frames are then
  // <camera>/data/<t_ns>.png. Absent: <camera>/rgb/NNNNNN.png.
  std::optional<double> eurocIntervalS;

  bool wants(OutputKind kind) const { return outputs.count(kind) > 0; }
  bool anyAov() const;
  // Whether frames need their landmarks annotated: for the landmarks output, or COCO's keypoints
  // when the scene has landmarks.
  bool needsLandmarkAnnotations(bool sceneHasLandmarks) const {
    return wants(OutputKind::Landmarks) || (wants(OutputKind::Coco) && sceneHasLandmarks);
  }
  // The outputs, in frame order.
  std::vector<OutputKind> outputList() const;  // the enum is declared in frame order
  // The files each camera's frame has: each output (files), or Multilayer.
  std::vector<OutputKind> fileKinds() const;
  // The annotation files gathered per camera once the dataset is complete: coco (both layouts),
  // landmarks (multilayer).
  std::vector<OutputKind> gatheredKinds() const;
  // "<camera>/<kind>/NNNNNN.<ext>": frame `index`'s file of `kind` (one of fileKinds()).
  std::string framePath(const std::string& camera, OutputKind kind, int index) const;
  // "<camera>/<folder>": the folder of every frame's file of `kind`.
  std::string frameFolder(const std::string& camera, OutputKind kind) const;
};

// Frame `frame`'s timestamp, frame · interval, in seconds (the manifest, COCO, poses.tum) and in
// nanoseconds (EuRoC, bags). An interval of whole nanoseconds (0.05 s, not 1/30 s) is multiplied
// as an integer, so that the seconds are the double nearest the decimal product and print as it:
// 0.15 for frame 3 at 0.05 s, where 3 · 0.05 in doubles is 0.15000000000000002.
double frameTimestampSeconds(int frame, double intervalS);
int64_t frameTimestampNs(int frame, double intervalS);
// The EuRoC/ASL layout's image name (euroc_files.h): "<frameTimestampNs>.png" in <camera>/data/.
std::string eurocImageName(int frame, double intervalS);

// Whether `path` is where some dataset of omnicam's names frame `index`'s file of `kind` for
// `camera` (framePath, with colour in PNG or EXR; a EuRoC colour frame's "<camera>/data/<ns>.png",
// its interval unknown here, by its digits): what a manifest's frame records must be.
bool isFramePath(const std::string& path, const std::string& camera, OutputKind kind, int index);

// "<camera>/<kind>.json": a camera's gathered annotation file.
std::string gatheredPath(const std::string& camera, OutputKind kind);

// The folders a camera may have: one per kind of frame file, and "intrinsics".
std::vector<std::string> cameraFolderNames();

// Whether `relative` is a file some plan's dataset layout has for one of `cameras` (frame files,
// gathered annotations, intrinsics and poses, calibration files): all that replacing a dataset may
// remove.
bool isLayoutFile(const std::string& relative, const std::set<std::string>& cameras);

}  // namespace omnicam
