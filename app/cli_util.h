#pragma once
// Small helpers shared by the CLI verbs: strict number parsing, progress display, data paths.
#include <CLI/CLI.hpp>
#include <chrono>
#include <functional>
#include <map>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>
#include <string>

#include "geometry.h"
#include "input_limits.h"
#include "render_request.h"
#include "render_settings.h"
#include "rig.h"
#include "scene_loader.h"

namespace omnicam::cli {

// "X,Y,Z" → three finite doubles (locale-independent); throws InputError naming `flag` and the
// expected `form` ("VX,VY,YAW_RATE").
Vec3 parseTriple(const std::string& text, const std::string& flag, const std::string& form = "X,Y,Z");
// "X,Y,YAW" → a robot pose within the documented bounds; InputError naming `flag`.
RobotPose parsePose(const std::string& text, const std::string& flag);
// Messages about render settings name the flags that set them.
inline const SettingNames kSettingFlags{"--spp", "--size", "--velocity"};
// Validators for numeric flags, read exactly as the spec reader reads JSON numbers: a decimal
// integer (an optional '-', then digits without a leading zero: no '+', blanks, hex, octal or
// exponent) in [lo, hi], or
// a finite decimal number in [lo, hi] (`openLow`: lo itself excluded). Anything else is
// "<flag>: must be an integer in [lo, hi] (got "text")": never wrapped, clamped or rounded.
CLI::Validator integerIn(int64_t lo, uint64_t hi);
CLI::Validator numberIn(double lo, double hi, bool openLow = false);
// Any such integer in [lo, hi] (what the option's variable holds), its rule (`rule`, as the docs
// state it) checked by the reader that owns it; "must be an integer, <rule> (got "text")"
// otherwise. Its help shows no range: the option's type name states the rule.
CLI::Validator integerRuled(const std::string& rule, int64_t lo = INT64_MIN, int64_t hi = INT64_MAX);
// --spp of a verb that renders with its own default (demo, rings, study): the render's rule and
// help; the request (or checkSpp) checks the rule.
void addSppOption(CLI::App& cmd, int& spp, const std::string& help);
// "<text>" as an integer in [lo, hi], or nullopt (the rule integerIn checks).
std::optional<int64_t> parseIntegerIn(std::string_view text, int64_t lo, int64_t hi);
// The render request's flags (request_fields.h's rows) as given: each flag's text, or a switch.
struct RequestFlags {
  std::map<RequestField, std::string> text;
  std::map<RequestField, bool> on;
};
// Registers the request's flags in the groups `which` (RequestFlagGroup) on `cmd`, as their rows
// say; their help states RenderRequest's defaults.
void addRequestFlags(CLI::App& cmd, RequestFlags& flags, unsigned which);
// The request those flags give (readRenderRequest, naming the flags): a flag not given keeps
// the request's default.
RenderRequest readRequestFlags(const CLI::App& cmd, const RequestFlags& flags);
// Registers --allow-outside-files (scene files may pull in files outside the scene's folder).
void addSceneLoadFlags(CLI::App& cmd, SceneLoadOptions& options);
// The rig a --rig file holds (a scene's "rig" object, checked as a scene's is); a whole scene
// given there is refused, naming how the verb takes a scene (`sceneGiven`).
RigSpec readRigFlag(const std::string& path, const std::string& sceneGiven = "the scene argument");
// InputError unless exactly one of a scene file and --rig is given.
void checkSceneOrRigFlag(const std::string& scenePath, const std::string& rigPath);
// The rig of exactly one of `scenePath` (a scene file, loaded with `load`) or `rigPath` (readRigFlag):
// for verbs that need a camera and nothing else of the scene. `images` (named by `flag`), and
// their sidecars, must not be a file it read (checkOutputsSpareScene).
RigSpec rigOfSceneOrRigFlag(const std::string& scenePath, const std::string& rigPath, const SceneLoadOptions& load,
                            const std::vector<std::string>& images = {}, const std::string& flag = "-o");
// InputError("<flag>: … is the scene file; writing it would destroy what is read") if an image
// in `images`, or its sidecar, is a file the scene was read from (Scene::inputFiles: the scene,
// its textures, environment and glTF files).
void checkOutputsSpareScene(const Scene& scene, const std::vector<std::string>& images, const std::string& flag);

// Runs `check`, a check of what a scene file holds (an engine's capabilities against its rig),
// naming the file in the InputError it throws: "SCENE: rig.lens.model: …".
void checkScene(const std::string& sceneFile, const std::function<void()>& check);

// InputError("<flag>: only with <when>") if `flag` was given on `cmd`: flags that would do
// nothing in the chosen mode are refused, not silently ignored.
void refuseUnless(const CLI::App& cmd, const std::string& flag, bool allowed, const std::string& when);

// Folder with the bundled scenes: dataFile("scenes") (base/data_files.h); OMNICAM_SCENES overrides.
std::string scenesDir();
// Creates `dir` (and parents) if missing; throws InputError if it exists as a non-folder.
// Returns the folders it made, deepest first.
std::vector<std::string> ensureDirectory(const std::string& dir, const std::string& flag);
// Removes folders ensureDirectory made, if they are still empty: a refusal after them leaves
// nothing behind, and nothing else is touched.
void removeMadeFolders(const std::vector<std::string>& made);

// A one-line progress bar on stderr for long sequences: steps/s and time left, each step one of
// `unit` (frames, renders, rows). `alreadyDone` steps (kept from an earlier run) count toward the
// bar but not toward the rate. A bar left unfinished (an error thrown through it) ends its line when
// destroyed, so the error starts a line of its own.
class Progress {
 public:
  using Clock = std::function<std::chrono::steady_clock::time_point()>;
  // `now` is the clock rates and the log's pace are read from (a test's own; default the steady clock).
  Progress(std::string label, int total, int alreadyDone = 0, std::string unit = "frames", Clock now = {});
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  void step();
  // Jumps to `done` steps, printing once.
  void advanceTo(int done);
  void finish();

 private:
  std::string label_, unit_;
  int total_, done_ = 0, alreadyDone_ = 0;
  bool tty_, lineOpen_ = false;
  Clock now_;
  std::chrono::steady_clock::time_point start_, lastLine_;
};

}  // namespace omnicam::cli
