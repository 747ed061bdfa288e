#pragma once
// A recording camera as a user writes it (a dataset's `recording`, Python's `recording=`, the
// experiment's --test-camera files): a preset and parameters, each a fixed value or a
// distribution drawn per frame and camera from the run's seed, so that training sees a range of
// cameras (domain randomisation of the image pipeline). The parameters, their stages, domains and
// neutral values are one table (recording_camera_spec.cpp); docs/experiments.md lists them.
//
//   "recording": {"preset": {"choice": ["webcam", "phone"]}, "exposure_ev": {"uniform": [-1, 1]},
//                 "full_well_electrons": {"log_uniform": [500, 20000]}, "bayer": "rggb", "seed": 7}
//
// Or just a preset's name: "recording": "webcam".
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "recording_camera.h"

namespace omnicam {

// One parameter's value: fixed, or drawn per frame.
struct ParameterDraw {
  enum class Kind { Fixed, Uniform, LogUniform, Choice };
  Kind kind = Kind::Fixed;
  double lo = 0.0, hi = 0.0;   // Uniform, LogUniform
  std::vector<double> values;  // Fixed: one; Choice: the candidates (a word as its index)
  bool operator==(const ParameterDraw&) const = default;
};

struct RecordingCameraSpec {
  std::optional<ParameterDraw> preset;         // index into recordingPresetNames()
  std::map<std::string, ParameterDraw> draws;  // by parameter name; white balance as white_balance[0..2]
  uint64_t seed = 1;
  // A drawn camera given back (its "drawn_from_preset"): the preset it came from, carried into
  // the camera it draws. Never beside `preset`.
  std::string drawnFromPreset;
  bool operator==(const RecordingCameraSpec&) const = default;

  // True if any value is drawn (then a dataset's manifest carries each frame's values).
  bool randomised() const;
  // The camera of one frame (and camera: a dataset passes frame × cameras + camera): the preset
  // drawn, then each parameter (this spec's draw, else the preset's, else its neutral value).
  // Deterministic in (seed, index): resume and shards draw the same values.
  RecordingCamera draw(uint64_t index) const;
};

// Throws InputError naming `file` and the field path (`where`.field) for an unknown field,
// preset, distribution or word, a wrong type, lo > hi, or a value outside the parameter's domain.
// An unknown preset's message says how a camera of its own is given there (`ownCamera`: in a
// spec an object, on a command line a JSON file).
RecordingCameraSpec recordingCameraSpecFromJson(const nlohmann::json& j, const std::string& file,
                                                const std::string& where = "recording",
                                                const std::string& ownCamera = "an object of the stages' fields");
// A preset's name, or a file holding one recording object, as a command line or a keyword gives
// it (`field`: "--recording", "recording"): what looks like a file (a '/', a .json name) and is
// none is said to be missing, not taken for a preset's name.
RecordingCameraSpec recordingCameraSpecFromNameOrFile(const std::string& text, const std::string& field);
// The same for what is a file whatever its name (a path object): missing or not a file is said so.
RecordingCameraSpec recordingCameraSpecFromFile(const std::string& path, const std::string& field);
nlohmann::json recordingCameraSpecToJson(const RecordingCameraSpec& spec);
// A spec that always gives `camera`.
RecordingCameraSpec fixedRecordingCameraSpec(const RecordingCamera& camera);

// One drawn camera's every value, by parameter name (the manifest's per-frame record), and back.
nlohmann::json recordingCameraToJson(const RecordingCamera& camera);
RecordingCamera recordingCameraFromJson(const nlohmann::json& j, const std::string& file,
                                        const std::string& where = "recording");

const std::vector<std::string>& recordingPresetNames();  // webcam, machine_vision, phone
RecordingCameraSpec recordingPreset(const std::string& name);
// The stages in the camera's order, as parameters name them (blur, chromatic_aberration, …).
const std::vector<std::string>& recordingStages();
// The stage a parameter belongs to ("white_balance[0]" → "white_balance"); "" for no parameter.
std::string recordingStageOf(const std::string& parameter);
// `camera` with every parameter of `stage` at its neutral value (the stage does nothing).
RecordingCamera withStageNeutral(RecordingCamera camera, const std::string& stage);
// What a spec lets a parameter take, in words ("uniform [0.8, 1.25]", "rggb", …), by parameter,
// for reports: the preset's draw where the spec has none.
std::vector<std::pair<std::string, std::string>> describeRanges(const RecordingCameraSpec& spec);
// A drawn camera's values in words, by parameter, in the same order.
std::vector<std::pair<std::string, std::string>> describeValues(const RecordingCamera& camera);
// The parameters of `camera` that no camera `spec` draws has: each unlike every value `spec` can
// give it (a range's ends included; for a preset mix, any preset's draw, else the parameter's
// neutral value), by name, in describeValues' order. A setting its stage does not use (a demosaic
// without a mosaic) is none of them. What tells a report which test camera lies beyond training.
std::vector<std::string> parametersBeyond(const RecordingCameraSpec& spec, const RecordingCamera& camera);

}  // namespace omnicam
