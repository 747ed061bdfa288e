#include "recording_camera_spec.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <random>
#include <set>

#include "closest_name.h"
#include "errors.h"
#include "json_fields.h"
#include "json_text.h"
#include "number_format.h"
#include "seed_mixing.h"

namespace omnicam {

namespace {

// ---- The parameters: name, stage, type, domain, neutral value, and where each lives. ----
enum class ValueType { Real, Integer, Word };

struct Parameter {
  const char* name;
  const char* stage;
  ValueType type;
  double lo, hi;
  bool openLow;                      // (lo, hi]
  std::vector<const char*> words;    // Word: the values, stored as their index
  double neutral;                    // the value at which the stage does nothing
  std::function<double(const RecordingCamera&)> get;
  std::function<void(RecordingCamera&, double)> set;
  std::string note = "";  // what a special value means, for messages
};

template <typename Enum>
Parameter wordParameter(const char* name, const char* stage, std::vector<const char*> words, Enum RecordingCamera::*member) {
  return {name, stage, ValueType::Word, 0, static_cast<double>(words.size() - 1), false, std::move(words), 0.0,
          [member](const RecordingCamera& c) { return static_cast<double>(static_cast<int>(c.*member)); },
          [member](RecordingCamera& c, double v) { c.*member = static_cast<Enum>(static_cast<int>(v)); }, ""};
}

Parameter realParameter(const char* name, const char* stage, double lo, double hi, double neutral,
                        double RecordingCamera::*member, const char* note = "") {
  return {name, stage, ValueType::Real, lo, hi, false, {}, neutral,
          [member](const RecordingCamera& c) { return c.*member; }, [member](RecordingCamera& c, double v) { c.*member = v; }, note};
}

Parameter whiteBalanceGain(int channel) {
  static const char* const names[] = {"white_balance[0]", "white_balance[1]", "white_balance[2]"};
  return {names[channel], "white_balance", ValueType::Real, 0.0, 10.0, true, {}, 1.0,
          [channel](const RecordingCamera& c) { return c.whiteBalance[static_cast<size_t>(channel)]; },
          [channel](RecordingCamera& c, double v) { c.whiteBalance[static_cast<size_t>(channel)] = v; }, ""};
}

const std::vector<Parameter>& parameters() {
  using C = RecordingCamera;
  static const std::vector<Parameter> table = {
      realParameter("blur_radius_px", "blur", 0, 20, 0, &C::blurRadiusPx),
      wordParameter("blur_kernel", "blur", {"gaussian", "disc"}, &C::blurKernel),
      realParameter("chromatic_aberration", "chromatic_aberration", -0.05, 0.05, 0, &C::chromaticAberration),
      realParameter("vignetting", "vignetting", 0, 1, 0, &C::vignetting),
      realParameter("exposure_ev", "exposure", -10, 10, 0, &C::exposureEv),
      whiteBalanceGain(0),
      whiteBalanceGain(1),
      whiteBalanceGain(2),
      wordParameter("bayer", "bayer", {"none", "rggb", "bggr", "grbg", "gbrg"}, &C::bayer),
      wordParameter("demosaic", "bayer", {"bilinear", "vng", "edge_aware"}, &C::demosaic),
      realParameter("full_well_electrons", "noise", 0, 1e7, 0, &C::fullWellElectrons, "0: no shot noise"),
      realParameter("read_noise", "noise", 0, 1, 0, &C::readNoise),
      realParameter("row_noise", "noise", 0, 1, 0, &C::rowNoise),
      wordParameter("tone_curve", "tone", {"srgb", "gamma", "filmic"}, &C::tone),
      realParameter("gamma", "tone", 1, 4, 2.2, &C::gamma),
      realParameter("contrast", "tone", 0.5, 4, 1.5, &C::contrast),
      {"jpeg_quality", "jpeg", ValueType::Integer, 0, 100, false, {}, 0,
       [](const C& c) { return static_cast<double>(c.jpegQuality); }, [](C& c, double v) { c.jpegQuality = static_cast<int>(v); },
       "0: no JPEG"},
  };
  return table;
}

// The presets, in the order a preset draw's values index them.
const std::vector<const char*> kPresets = {"webcam", "machine_vision", "phone"};

const Parameter* findParameter(const std::string& name) {
  for (const Parameter& p : parameters())
    if (name == p.name) return &p;
  return nullptr;
}

// ---- Presets: camera families, ranges chosen from their data sheets' typical values before
// any experiment's result was seen (docs/experiments.md gives the reasons). ----
const char* presetText(const std::string& name) {
  if (name == "webcam")  // USB webcams (1/4"–1/3" sensors, ~3 µm pixels, auto exposure, MJPEG)
    return R"({"blur_radius_px": {"uniform": [0, 1.2]}, "chromatic_aberration": {"uniform": [-0.003, 0.003]},
      "vignetting": {"uniform": [0.1, 0.5]}, "exposure_ev": {"uniform": [-0.7, 0.7]},
      "white_balance": [{"uniform": [0.8, 1.25]}, 1, {"uniform": [0.8, 1.25]}],
      "bayer": {"choice": ["rggb", "bggr", "grbg", "gbrg"]}, "demosaic": {"choice": ["bilinear", "edge_aware"]},
      "full_well_electrons": {"log_uniform": [1000, 8000]}, "read_noise": {"uniform": [0.002, 0.012]},
      "row_noise": {"uniform": [0, 0.003]}, "tone_curve": {"choice": ["srgb", "gamma"]}, "gamma": {"uniform": [1.8, 2.4]},
      "jpeg_quality": {"uniform": [60, 90]}})";
  if (name == "machine_vision")  // industrial cameras (2/3"–1" global-shutter sensors, raw or lightly compressed)
    return R"({"blur_radius_px": {"uniform": [0, 0.8]}, "chromatic_aberration": {"uniform": [-0.002, 0.002]},
      "vignetting": {"uniform": [0, 0.25]}, "exposure_ev": {"uniform": [-1, 1]},
      "white_balance": [{"uniform": [0.9, 1.1]}, 1, {"uniform": [0.9, 1.1]}],
      "bayer": {"choice": ["rggb", "bggr", "grbg", "gbrg"]}, "demosaic": {"choice": ["bilinear", "vng", "edge_aware"]},
      "full_well_electrons": {"log_uniform": [5000, 30000]}, "read_noise": {"uniform": [0.0005, 0.004]},
      "row_noise": {"uniform": [0, 0.001]}, "tone_curve": {"choice": ["gamma", "srgb"]}, "gamma": {"uniform": [1, 2.2]},
      "jpeg_quality": {"choice": [0, 95]}})";
  if (name == "phone")  // phone cameras (small pixels, strong processing: contrasty tone, sharpening lost to JPEG)
    return R"({"blur_radius_px": {"uniform": [0.3, 1.5]}, "blur_kernel": {"choice": ["gaussian", "disc"]},
      "chromatic_aberration": {"uniform": [-0.004, 0.004]}, "vignetting": {"uniform": [0, 0.3]},
      "exposure_ev": {"uniform": [-0.7, 0.7]}, "white_balance": [{"uniform": [0.85, 1.2]}, 1, {"uniform": [0.85, 1.2]}],
      "bayer": {"choice": ["rggb", "bggr", "grbg", "gbrg"]}, "demosaic": "edge_aware",
      "full_well_electrons": {"log_uniform": [1500, 8000]}, "read_noise": {"uniform": [0.001, 0.006]},
      "row_noise": {"uniform": [0, 0.002]}, "tone_curve": "filmic", "contrast": {"uniform": [1.1, 2.0]},
      "jpeg_quality": {"uniform": [80, 95]}})";
  return nullptr;
}

std::string wordList(const std::vector<const char*>& words) {
  std::string list;
  for (const char* w : words) list += (list.empty() ? "" : ", ") + std::string(w);
  return list;
}

std::string intervalText(const Parameter& p) {
  return (p.openLow ? "(" : "[") + shortNumber(p.lo) + ", " + shortNumber(p.hi) + "]";
}

std::string domainText(const Parameter& p) {
  if (p.type == ValueType::Word) return "one of " + wordList(p.words);
  return std::string(p.type == ValueType::Integer ? "an integer in " : "a number in ") + intervalText(p) +
         (p.note.empty() ? "" : " (" + p.note + ")");
}

bool inDomain(const Parameter& p, double v) {
  if (!std::isfinite(v) || v > p.hi || (p.openLow ? v <= p.lo : v < p.lo)) return false;
  return p.type == ValueType::Real || v == std::floor(v);
}

// A value as messages show it: a string quoted and escaped, anything else by jsonValueText.
std::string shown(const nlohmann::json& j) { return j.is_string() ? quote(j.get<std::string>()) : jsonValueText(j); }

// A single value of `p` from JSON (a number, or a word for a Word parameter).
double valueOf(const Parameter& p, const nlohmann::json& j, const JsonFields& f, const std::string& key) {
  if (p.type == ValueType::Word) {
    if (j.is_string())
      for (size_t k = 0; k < p.words.size(); ++k)
        if (j.get<std::string>() == p.words[k]) return static_cast<double>(k);
    f.fail(key, "must be " + domainText(p) + " (got " + shown(j) + ")" +
                    (j.is_string() ? didYouMean(j.get<std::string>(), std::vector<std::string>(p.words.begin(), p.words.end())) : ""));
  }
  if (!j.is_number() || !inDomain(p, j.get<double>())) f.fail(key, "must be " + domainText(p) + " (got " + shown(j) + ")");
  return j.get<double>();
}

// A parameter's draw: a value, or {"uniform": [lo, hi]}, {"log_uniform": [lo, hi]}, {"choice": [...]}.
ParameterDraw drawOf(const Parameter& p, const nlohmann::json& j, const JsonFields& f, const std::string& key) {
  ParameterDraw d;
  if (!j.is_object()) {
    d.values = {valueOf(p, j, f, key)};
    return d;
  }
  if (j.size() != 1)
    f.fail(key, "a distribution is one of {\"uniform\": [lo, hi]}, {\"log_uniform\": [lo, hi]}, {\"choice\": [...]} (got " +
                    std::to_string(j.size()) + " fields)");
  const std::string kind = j.begin().key();
  const nlohmann::json& arguments = j.begin().value();
  const std::string at = key + "." + keySegment(kind);
  if (kind == "choice") {
    if (!arguments.is_array() || arguments.empty() || arguments.size() > 64)
      f.fail(at, "must be a list of 1 to 64 values (got " + jsonShapeText(arguments) + ")");
    d.kind = ParameterDraw::Kind::Choice;
    for (size_t k = 0; k < arguments.size(); ++k) d.values.push_back(valueOf(p, arguments[k], f, at + "[" + std::to_string(k) + "]"));
    return d;
  }
  if (kind != "uniform" && kind != "log_uniform")
    f.fail(key, "unknown distribution " + quote(kind) + " (uniform, log_uniform, choice)");
  if (p.type == ValueType::Word) f.fail(at, "a word is drawn with {\"choice\": [...]}");
  // An integer's draw gives each integer of [lo, hi] the same chance: a log-uniform one has none.
  if (p.type == ValueType::Integer && kind == "log_uniform") f.fail(at, "an integer is drawn with {\"uniform\": [lo, hi]} or {\"choice\": [...]}");
  if (!arguments.is_array() || arguments.size() != 2) f.fail(at, "must be [lo, hi] (got " + jsonShapeText(arguments) + ")");
  d.kind = kind == "uniform" ? ParameterDraw::Kind::Uniform : ParameterDraw::Kind::LogUniform;
  for (int k = 0; k < 2; ++k) {
    const nlohmann::json& bound = arguments[static_cast<size_t>(k)];
    if (!bound.is_number() || !inDomain(p, bound.get<double>()))
      f.fail(at + "[" + std::to_string(k) + "]", std::string("must be ") + (p.type == ValueType::Integer ? "an integer" : "a number") +
                                                     " in " + intervalText(p) + " (got " + jsonValueText(bound) + ")");
  }
  d.lo = arguments[0].get<double>();
  d.hi = arguments[1].get<double>();
  if (d.lo > d.hi) f.fail(at, "lo > hi (" + shortNumber(d.lo) + " > " + shortNumber(d.hi) + ")");
  if (d.kind == ParameterDraw::Kind::LogUniform && d.lo <= 0) f.fail(at, "log_uniform needs lo > 0 (got " + roundTrip(d.lo) + ")");
  return d;
}

nlohmann::json valueJson(const Parameter& p, double v) {
  if (p.type == ValueType::Word) return p.words[static_cast<size_t>(v)];
  if (p.type == ValueType::Integer) return static_cast<int64_t>(v);
  return v;
}

nlohmann::json drawJson(const Parameter& p, const ParameterDraw& d) {
  switch (d.kind) {
    case ParameterDraw::Kind::Fixed: return valueJson(p, d.values.front());
    case ParameterDraw::Kind::Uniform: return {{"uniform", {d.lo, d.hi}}};
    case ParameterDraw::Kind::LogUniform: return {{"log_uniform", {d.lo, d.hi}}};
    case ParameterDraw::Kind::Choice: {
      nlohmann::json values = nlohmann::json::array();
      for (double v : d.values) values.push_back(valueJson(p, v));
      return {{"choice", values}};
    }
  }
  return nullptr;
}

std::string drawText(const Parameter& p, const ParameterDraw& d) {
  auto value = [&](double v) { return p.type == ValueType::Word ? std::string(p.words[static_cast<size_t>(v)]) : shortNumber(v); };
  switch (d.kind) {
    case ParameterDraw::Kind::Fixed: return value(d.values.front());
    case ParameterDraw::Kind::Uniform: return "uniform [" + shortNumber(d.lo) + ", " + shortNumber(d.hi) + "]";
    case ParameterDraw::Kind::LogUniform: return "log-uniform [" + shortNumber(d.lo) + ", " + shortNumber(d.hi) + "]";
    case ParameterDraw::Kind::Choice: {
      std::string text = "one of ";
      for (size_t k = 0; k < d.values.size(); ++k) text += (k ? ", " : "") + value(d.values[k]);
      return text;
    }
  }
  return "";
}

// One value from `d`, from its own stream (seed, index, the parameter's name): adding a parameter
// to a spec, or to the table, leaves the others' draws as they were. A draw stays within [lo, hi];
// an integer's uniform draw gives each integer in [lo, hi] the same chance.
double drawValue(const Parameter& p, const ParameterDraw& d, uint64_t seed, uint64_t index) {
  if (d.kind == ParameterDraw::Kind::Fixed) return d.values.front();
  std::mt19937_64 random(mixBits(mixBits(mixBits(seed ^ 0x5EEDCA3E7A5EC0DEull) + index) + nameHash(p.name)));
  const double u = static_cast<double>(random() >> 11) * 0x1.0p-53;  // [0, 1)
  if (d.kind == ParameterDraw::Kind::Choice)
    return d.values[std::min(d.values.size() - 1, static_cast<size_t>(u * static_cast<double>(d.values.size())))];
  if (p.type == ValueType::Integer) return std::min(d.hi, d.lo + std::floor((d.hi - d.lo + 1.0) * u));  // integer bounds
  const double v = d.kind == ParameterDraw::Kind::Uniform ? d.lo + (d.hi - d.lo) * u
                                                          : std::exp(std::log(d.lo) + (std::log(d.hi) - std::log(d.lo)) * u);
  return std::clamp(v, d.lo, d.hi);
}

// Reads the parameters of `f` into `draws` (the white balance as three), leaving other fields.
void readDraws(JsonFields& f, std::map<std::string, ParameterDraw>& draws) {
  for (const Parameter& p : parameters()) {
    const std::string name = p.name;
    if (name.rfind("white_balance[", 0) == 0) continue;
    if (f.has(name)) draws[name] = drawOf(p, f.raw(name), f, name);
  }
  if (f.has("white_balance")) {
    const nlohmann::json& gains = f.raw("white_balance");
    if (!gains.is_array() || gains.size() != 3)
      f.fail("white_balance", "must be [r, g, b], each a gain in (0, 10] or a distribution (got " + jsonShapeText(gains) + ")");
    for (int c = 0; c < 3; ++c) {
      const Parameter& p = *findParameter("white_balance[" + std::to_string(c) + "]");
      draws[p.name] = drawOf(p, gains[static_cast<size_t>(c)], f, "white_balance[" + std::to_string(c) + "]");
    }
  }
}

// The preset, read and written as a Word parameter of its own (not a camera's).
const Parameter& presetParameter() {
  static const Parameter preset{"preset", "", ValueType::Word, 0, static_cast<double>(kPresets.size() - 1), false, kPresets, 0, {}, {}, ""};
  return preset;
}

uint64_t seedOf(JsonFields& f) {
  const nlohmann::json& seed = f.raw("seed");
  if (!seed.is_number_unsigned()) f.fail("seed", "must be an integer in [0, 2^64 - 1] (got " + jsonValueText(seed) + ")");
  return seed.get<uint64_t>();
}

// The values `name` may take in a frame of `spec`: its own draw's, else each preset's that may be
// drawn, else its neutral value. For a word parameter (drawn by choice), the words; for a range,
// its ends (enough for the settings' conditions, each true on an end if on any value between).
std::set<double> possibleValues(const RecordingCameraSpec& spec, const std::string& name);

// A setting that changes nothing unless another takes a value (a gamma without a gamma tone
// curve) is refused: a spec that sets it believes it does something.
struct DependentSetting {
  const char* setting;
  const char* on;
  std::function<bool(double)> actsWhen;  // of a value of `on`: does `setting` act?
  const char* acts;                      // when it acts, in words
  const char* hint;
  // Its default, given where it does nothing, is kept: drawn cameras written before the setting
  // was refused so held it, and given back they read as they were.
  bool keepsItsDefault = false;
};

const std::vector<DependentSetting>& dependentSettings() {
  static const std::vector<DependentSetting> dependent = {
      {"blur_kernel", "blur_radius_px", [](double radius) { return radius > 0; }, "blur_radius_px > 0", "give a blur_radius_px",
       true},
      {"gamma", "tone_curve", [](double tone) { return tone == 1.0; }, "tone_curve is gamma", "give \"tone_curve\": \"gamma\""},
      {"contrast", "tone_curve", [](double tone) { return tone == 2.0; }, "tone_curve is filmic", "give \"tone_curve\": \"filmic\""},
      {"demosaic", "bayer", [](double pattern) { return pattern != 0.0; }, "bayer is a pattern", "give a bayer pattern"}};
  return dependent;
}

// True if `name` acts in `camera` (every setting but a dependent one whose switch is off).
bool actsIn(const RecordingCamera& camera, const std::string& name) {
  for (const DependentSetting& d : dependentSettings())
    if (name == d.setting) return d.actsWhen(findParameter(d.on)->get(camera));
  return true;
}

void refuseSettingsThatDoNothing(const RecordingCameraSpec& spec, const JsonFields& f) {
  for (const DependentSetting& d : dependentSettings()) {
    const auto given = spec.draws.find(d.setting);
    if (given == spec.draws.end()) continue;
    if (d.keepsItsDefault && given->second.kind == ParameterDraw::Kind::Fixed &&
        given->second.values.front() == findParameter(d.setting)->neutral)
      continue;
    const std::set<double> possible = possibleValues(spec, d.on);
    if (std::any_of(possible.begin(), possible.end(), d.actsWhen)) continue;
    const Parameter& on = *findParameter(d.on);
    std::string taken;
    for (double v : possible)
      taken += (taken.empty() ? "" : " or ") + (on.type == ValueType::Word ? std::string(on.words[static_cast<size_t>(v)]) : shortNumber(v));
    f.fail(d.setting, std::string("does nothing unless ") + d.acts + ", and it is " + taken +
                          (spec.draws.count(d.on)                   ? ""
                           : !spec.preset                           ? " (its default)"
                           : spec.preset->values.size() > 1 ? " (the presets')"
                                                                    : " (the preset's)") +
                          " here: " + d.hint +
                          ", or leave " + d.setting + " out");
  }
}

std::set<double> possibleValues(const RecordingCameraSpec& spec, const std::string& name) {
  if (const auto own = spec.draws.find(name); own != spec.draws.end()) {
    const ParameterDraw& draw = own->second;
    if (draw.kind == ParameterDraw::Kind::Uniform || draw.kind == ParameterDraw::Kind::LogUniform) return {draw.lo, draw.hi};
    return {draw.values.begin(), draw.values.end()};
  }
  if (!spec.preset) return {findParameter(name)->neutral};
  std::set<double> values;
  for (double preset : spec.preset->values) {
    const std::set<double> its = possibleValues(recordingPreset(recordingPresetNames()[static_cast<size_t>(preset)]), name);
    values.insert(its.begin(), its.end());
  }
  return values;
}

}  // namespace

const std::vector<std::string>& recordingPresetNames() {
  static const std::vector<std::string> names(kPresets.begin(), kPresets.end());
  return names;
}

RecordingCameraSpec recordingPreset(const std::string& name) {
  static const std::map<std::string, RecordingCameraSpec> presets = [] {
    std::map<std::string, RecordingCameraSpec> read;
    for (const std::string& preset : recordingPresetNames())
      read[preset] = recordingCameraSpecFromJson(nlohmann::json::parse(presetText(preset)), "the " + preset + " preset", "recording");
    return read;
  }();
  const auto found = presets.find(name);
  if (found == presets.end()) throw InputError("recording: unknown preset " + quote(name) + " (" + wordList(kPresets) + ")");
  return found->second;
}

const std::vector<std::string>& recordingStages() {
  static const std::vector<std::string> stages = {"blur",   "chromatic_aberration", "vignetting", "exposure", "white_balance",
                                                  "bayer",  "noise",                "tone",       "jpeg"};
  return stages;
}

std::string recordingStageOf(const std::string& parameter) {
  const Parameter* p = findParameter(parameter);
  return p ? p->stage : "";
}

RecordingCamera withStageNeutral(RecordingCamera camera, const std::string& stage) {
  for (const Parameter& p : parameters())
    if (stage == p.stage) p.set(camera, p.neutral);
  return camera;
}

namespace {

// A spec as written, each field checked on its own; `settingsMustAct` also refuses a setting that
// would act in no frame (a user's spec: not a manifest's drawn camera, which writes every value).
RecordingCameraSpec readRecordingCameraSpec(const nlohmann::json& j, const std::string& file, const std::string& where,
                                            bool settingsMustAct, const std::string& ownCamera = "an object of the stages' fields") {
  RecordingCameraSpec spec;
  if (j.is_string()) {
    if (!presetText(j.get<std::string>()))
      throw InputError(fieldLocation(file, where) + ": unknown preset " + quote(j.get<std::string>()) +
                       didYouMean(j.get<std::string>(), recordingPresetNames()) + " (" + wordList(kPresets) +
                       "; or a camera of its own: " + ownCamera + ", docs/experiments.md)");
    spec.preset = ParameterDraw{ParameterDraw::Kind::Fixed, 0, 0, {static_cast<double>(
        std::find(recordingPresetNames().begin(), recordingPresetNames().end(), j.get<std::string>()) - recordingPresetNames().begin())}};
    return spec;
  }
  JsonFields f(j, file, where);
  if (f.has("preset")) spec.preset = drawOf(presetParameter(), f.raw("preset"), f, "preset");
  readDraws(f, spec.draws);
  if (f.has("seed")) spec.seed = seedOf(f);
  if (f.has("drawn_from_preset")) {
    if (spec.preset) f.fail("drawn_from_preset", "says which preset a drawn camera came from: not beside preset, which draws one");
    spec.drawnFromPreset = recordingPresetNames()[static_cast<size_t>(valueOf(presetParameter(), f.raw("drawn_from_preset"), f, "drawn_from_preset"))];
  }
  f.finish();
  if (settingsMustAct) refuseSettingsThatDoNothing(spec, f);
  return spec;
}

}  // namespace

RecordingCameraSpec recordingCameraSpecFromJson(const nlohmann::json& j, const std::string& file, const std::string& where,
                                                const std::string& ownCamera) {
  return readRecordingCameraSpec(j, file, where, true, ownCamera);
}

nlohmann::json recordingCameraSpecToJson(const RecordingCameraSpec& spec) {
  nlohmann::json j = nlohmann::json::object();
  if (spec.preset) j["preset"] = drawJson(presetParameter(), *spec.preset);
  nlohmann::json gains = nlohmann::json::array({1.0, 1.0, 1.0});
  bool anyGain = false;
  for (const auto& [name, draw] : spec.draws) {
    const Parameter& p = *findParameter(name);
    if (name.rfind("white_balance[", 0) == 0) {
      gains[static_cast<size_t>(name[14] - '0')] = drawJson(p, draw);
      anyGain = true;
    } else {
      j[name] = drawJson(p, draw);
    }
  }
  if (anyGain) j["white_balance"] = gains;
  j["seed"] = spec.seed;
  if (!spec.drawnFromPreset.empty()) j["drawn_from_preset"] = spec.drawnFromPreset;
  return j;
}

RecordingCameraSpec fixedRecordingCameraSpec(const RecordingCamera& camera) {
  RecordingCameraSpec spec;
  for (const Parameter& p : parameters())  // the settings that act in the camera, as recordingCameraToJson writes them
    if (actsIn(camera, p.name)) spec.draws[p.name] = ParameterDraw{ParameterDraw::Kind::Fixed, 0, 0, {p.get(camera)}};
  spec.seed = camera.seed;
  spec.drawnFromPreset = camera.drawnFromPreset;
  return spec;
}

bool RecordingCameraSpec::randomised() const {
  auto drawn = [](const ParameterDraw& d) { return d.kind != ParameterDraw::Kind::Fixed; };
  if (preset && drawn(*preset)) return true;
  for (const auto& [name, draw] : draws)
    if (drawn(draw)) return true;
  if (!preset) return false;
  const RecordingCameraSpec family = recordingPreset(recordingPresetNames()[static_cast<size_t>(preset->values.front())]);
  for (const auto& [name, draw] : family.draws)
    if (drawn(draw) && !draws.count(name)) return true;
  return false;
}

RecordingCamera RecordingCameraSpec::draw(uint64_t index) const {
  RecordingCamera camera;
  std::optional<RecordingCameraSpec> family;
  camera.drawnFromPreset = drawnFromPreset;
  if (preset) {
    const double which = drawValue(presetParameter(), *preset, seed, index);
    camera.drawnFromPreset = recordingPresetNames()[static_cast<size_t>(which)];
    family = recordingPreset(camera.drawnFromPreset);
  }
  for (const Parameter& p : parameters()) {
    const ParameterDraw* d = nullptr;
    if (const auto own = draws.find(p.name); own != draws.end()) d = &own->second;
    else if (family)
      if (const auto inherited = family->draws.find(p.name); inherited != family->draws.end()) d = &inherited->second;
    p.set(camera, d ? drawValue(p, *d, seed, index) : p.neutral);
  }
  camera.seed = seed;
  return camera;
}

nlohmann::json recordingCameraToJson(const RecordingCamera& camera) {
  nlohmann::json j = nlohmann::json::object();
  for (const Parameter& p : parameters())  // a setting its stage does not use is left out: read back, it would be refused
    if (std::string(p.name).rfind("white_balance[", 0) != 0 && actsIn(camera, p.name)) j[p.name] = valueJson(p, p.get(camera));
  j["white_balance"] = camera.whiteBalance;
  j["seed"] = camera.seed;
  if (!camera.drawnFromPreset.empty()) j["drawn_from_preset"] = camera.drawnFromPreset;
  return j;
}

RecordingCamera recordingCameraFromJson(const nlohmann::json& j, const std::string& file, const std::string& where) {
  const RecordingCameraSpec spec = readRecordingCameraSpec(j, file, where, false);
  if (spec.randomised())
    throw InputError(fieldLocation(file, where) + ": a single camera is wanted here: fixed values, no distributions or preset ranges");
  return spec.draw(0);
}

std::vector<std::pair<std::string, std::string>> describeRanges(const RecordingCameraSpec& spec) {
  std::vector<RecordingCameraSpec> families;
  if (spec.preset)
    for (double which : spec.preset->values) families.push_back(recordingPreset(recordingPresetNames()[static_cast<size_t>(which)]));
  std::vector<std::pair<std::string, std::string>> ranges;
  for (const Parameter& p : parameters()) {
    std::string text;
    if (const auto own = spec.draws.find(p.name); own != spec.draws.end()) {
      text = drawText(p, own->second);
    } else if (families.empty()) {
      text = drawText(p, ParameterDraw{ParameterDraw::Kind::Fixed, 0, 0, {p.neutral}});
    } else {
      for (size_t k = 0; k < families.size(); ++k) {
        const auto inherited = families[k].draws.find(p.name);
        const std::string one = inherited != families[k].draws.end() ? drawText(p, inherited->second)
                                                                      : drawText(p, ParameterDraw{ParameterDraw::Kind::Fixed, 0, 0, {p.neutral}});
        text += (k ? "; " : "") + (families.size() > 1 ? recordingPresetNames()[static_cast<size_t>(spec.preset->values[k])] + ": " : "") + one;
      }
    }
    ranges.emplace_back(p.name, text);
  }
  return ranges;
}

std::vector<std::pair<std::string, std::string>> describeValues(const RecordingCamera& camera) {
  std::vector<std::pair<std::string, std::string>> values;
  for (const Parameter& p : parameters())
    values.emplace_back(p.name, drawText(p, ParameterDraw{ParameterDraw::Kind::Fixed, 0, 0, {p.get(camera)}}));
  return values;
}

namespace {

// Whether `d` can give `value`: a fixed value or a choice's candidate equal to it (to 1e-9 of its
// size: a value typed from a printed one), a range holding it.
bool canGive(const ParameterDraw& d, double value) {
  const double slack = 1e-9 * std::max(1.0, std::abs(value));
  switch (d.kind) {
    case ParameterDraw::Kind::Fixed:
    case ParameterDraw::Kind::Choice:
      return std::any_of(d.values.begin(), d.values.end(), [&](double v) { return std::abs(v - value) <= slack; });
    case ParameterDraw::Kind::Uniform:
    case ParameterDraw::Kind::LogUniform: return value >= d.lo - slack && value <= d.hi + slack;
  }
  return false;
}

}  // namespace

std::vector<std::string> parametersBeyond(const RecordingCameraSpec& spec, const RecordingCamera& camera) {
  std::vector<RecordingCameraSpec> families;
  if (spec.preset)
    for (double which : spec.preset->values) families.push_back(recordingPreset(recordingPresetNames()[static_cast<size_t>(which)]));
  std::vector<std::string> beyond;
  for (const Parameter& p : parameters()) {
    if (!actsIn(camera, p.name)) continue;
    const double value = p.get(camera);
    auto drawOf = [&](const RecordingCameraSpec& s) {
      const auto own = s.draws.find(p.name);
      return own != s.draws.end() ? own->second : ParameterDraw{ParameterDraw::Kind::Fixed, 0, 0, {p.neutral}};
    };
    bool given = false;
    if (spec.draws.count(p.name) || families.empty()) given = canGive(drawOf(spec), value);
    else
      for (const RecordingCameraSpec& family : families) given = given || canGive(drawOf(family), value);
    if (!given) beyond.push_back(p.name);
  }
  return beyond;
}

RecordingCameraSpec recordingCameraSpecFromFile(const std::string& path, const std::string& field) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(path, ec)) return recordingCameraSpecFromJson(readJsonFile(path), path, "");
  throw InputError(field + ": " + showPath(path) + (std::filesystem::exists(path, ec) ? ": not a file" : ": no such file") +
                   " (a preset's name or a JSON file)");
}

RecordingCameraSpec recordingCameraSpecFromNameOrFile(const std::string& text, const std::string& field) {
  if (text.empty()) throw InputError(field + ": give a preset's name or a JSON file (docs/experiments.md)");
  std::error_code ec;
  // What looks like a file (a '/', a .json name) is one: a folder named webcam does not hide the preset.
  if (std::filesystem::is_regular_file(text, ec) || text.find('/') != std::string::npos || text.ends_with(".json"))
    return recordingCameraSpecFromFile(text, field);
  return recordingCameraSpecFromJson(nlohmann::json(text), field, "", "a JSON file of the stages' fields");
}

}  // namespace omnicam
