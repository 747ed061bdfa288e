#pragma once
// Reading a dataset folder (docs/dataset-format.md) for use, as untrusted input: the manifest
// strictly (readDatasetManifest), files only inside the folder with no link followed, hashes
// checked on request, and each output decoded from the bytes that were checked.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "image.h"
#include "manifest.h"
#include "safe_files.h"
#include "output_kinds.h"

namespace omnicam {

// One decoded output of a frame: an image (rgb), data (depth: 1 channel; normal: 3), ids
// (instance, semantic) or JSON (landmarks, coco), from its own file or its frame's OpenEXR.
struct DecodedOutput {
  std::optional<ImageRGBA> image;
  std::optional<DataImage> data;
  std::vector<uint16_t> ids;
  int width = 0, height = 0;
  nlohmann::json json;
};

// The colour of a multilayer frame file (its R, G, B, A channels), decoded by the reader every
// consumer of a dataset uses (this one, `omnicam compare`, Python): one reader, one rule.
ImageRGBA multilayerFrameColour(std::string_view bytes, const std::string& name);

class DatasetReader {
 public:
  // InputError naming the file and field for a missing, linked or malformed manifest.
  explicit DatasetReader(std::string dir);

  const std::string& dir() const { return dir_; }
  const DatasetManifest& manifest() const { return manifest_; }
  std::vector<std::string> cameras() const;
  // Finished frames' indices, ascending.
  const std::vector<int>& frames() const { return frames_; }
  const FrameRecord& frame(int index) const;

  // The bytes of frame `index`'s file `kind` of `camera`, or of the camera's own file `kind`
  // (intrinsics_opencv, poses_tum, …) when index is nullopt. With checkHash, InputError unless
  // they hash to the manifest's SHA-256.
  std::string fileBytes(std::optional<int> index, const std::string& camera, const std::string& kind, bool checkHash) const;
  // Frame `index`'s outputs `kinds` of `camera`, whichever the layout: each file read (and
  // checked) once. InputError naming the file for an output the frame lacks or cannot decode.
  std::map<OutputKind, DecodedOutput> readOutputs(int index, const std::string& camera, const std::vector<OutputKind>& kinds,
                                                  bool checkHash) const;
  DecodedOutput readOutput(int index, const std::string& camera, OutputKind kind, bool checkHash) const;
  // The rig `camera` rendered frame `index` with: the frame's own (a vibrating robot's), else the
  // camera's of the header. InputError naming the manifest's field when it is not a rig.
  RigSpec cameraRig(int index, const std::string& camera) const;

 private:
  FileRecord record(std::optional<int> index, const std::string& camera, const std::string& kind) const;
  std::string dir_;
  SafeFolder folder_;  // the folder, opened once: every file is read through its descriptor
  DatasetManifest manifest_;
  std::vector<int> frames_;
};

// Where an image file lies in a dataset: `frame` of `camera` in the dataset folder `dir`, when
// the file is DIR/<camera>/<folder>/<name> and DIR's manifest lists it there (a frame copied
// elsewhere, a folder that only looks like a dataset's, or another tool's manifest.json is
// none). InputError for omnicam's manifest that cannot be read. `rig` is the camera's for that
// frame (DatasetReader::cameraRig), from the same read of the manifest.
struct DatasetImageLocation {
  std::string dir, camera;
  int frame = 0;
  RigSpec rig;
};
std::optional<DatasetImageLocation> locateInDataset(const std::string& image);

}  // namespace omnicam
