#include "cli_util.h"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "atomic_file.h"
#include "data_files.h"
#include "errors.h"
#include "file_formats.h"
#include "json_text.h"
#include "number_format.h"
#include "render_settings.h"
#include "sidecar.h"

namespace omnicam::cli {

Vec3 parseTriple(const std::string& text, const std::string& flag, const std::string& form) {
  if (std::count(text.begin(), text.end(), ',') != 2)
    throw InputError(flag + ": expected three comma-separated numbers " + form + " (got " + quote(text) + ")");
  Vec3 out;
  size_t start = 0;
  for (int k = 0; k < 3; ++k) {
    const size_t end = k < 2 ? text.find(',', start) : text.size();
    const char* first = text.data() + start;
    const char* last = text.data() + end;
    // Spaces around a number, as JSON's "[1, 0, 90]" copied in: "1, 0, 90" reads as "1,0,90".
    while (first != last && *first == ' ') ++first;
    while (last != first && last[-1] == ' ') --last;
    const std::string_view written(first, static_cast<size_t>(last - first));
    // A sign as people write it: from_chars takes "-" only.
    const char* digits = first != last && *first == '+' && last - first > 1 && first[1] != '-' ? first + 1 : first;
    double v = 0.0;
    auto [ptr, ec] = std::from_chars(digits, last, v);
    if (ec == std::errc::result_out_of_range && ptr == last)
      throw InputError(flag + ": " + quote(written) + " is out of a double's range (magnitudes from about 1e-308 to 1e308, or 0)");
    if (ec != std::errc() || ptr != last) throw InputError(flag + ": " + quote(written) + " is not a number");
    if (!std::isfinite(v)) throw InputError(flag + ": " + quote(written) + " is not a finite number");
    out[k] = v;
    start = end + 1;
  }
  return out;
}

RobotPose parsePose(const std::string& text, const std::string& flag) {
  const Vec3 p = parseTriple(text, flag, "X,Y,YAW");
  const RobotPose pose{p.x(), p.y(), p.z()};
  checkPose(pose, flag);
  return pose;
}

namespace {

// Digits only after an optional '-', no leading zero: what CLI11's own conversion then reads
// exactly (it takes "0x10" as hex, "010" as octal 8, and wraps "-1" into an unsigned flag).
bool plainInteger(std::string_view text) {
  const size_t digits = !text.empty() && text[0] == '-' ? 1 : 0;
  if (text.size() == digits) return false;
  if (text[digits] == '0' && text.size() > digits + 1) return false;
  for (size_t k = digits; k < text.size(); ++k)
    if (text[k] < '0' || text[k] > '9') return false;
  return true;
}

// "04": digits a leading zero makes ambiguous (CLI11 would read octal), which the rule's words
// alone would not explain.
bool leadingZero(std::string_view text) {
  const size_t digits = !text.empty() && text[0] == '-' ? 1 : 0;
  if (text.size() <= digits + 1 || text[digits] != '0') return false;
  return text.find_first_not_of("0123456789", digits) == std::string_view::npos;
}

std::string rangeText(const std::string& lo, const std::string& hi, bool openLow) {
  return std::string(openLow ? "(" : "[") + lo + ", " + hi + "]";
}

}  // namespace

namespace {

// A plain integer (plainInteger) in [lo, hi].
bool integerTextIn(const std::string& text, int64_t lo, uint64_t hi) {
  if (!plainInteger(text)) return false;
  if (text[0] == '-') {
    int64_t v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    return ec == std::errc() && end == text.data() + text.size() && v >= lo;
  }
  uint64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  return ec == std::errc() && end == text.data() + text.size() && v <= hi && (lo <= 0 || v >= static_cast<uint64_t>(lo));
}

// A rule as the docs write it, in ASCII for the help's columns (CLI11 counts bytes, not letters).
std::string asciiRule(std::string rule) {
  for (const auto& [from, to] : {std::pair{"²", "^2"}, std::pair{"–", "-"}, std::pair{"·", "*"}})
    for (size_t at = rule.find(from); at != std::string::npos; at = rule.find(from, at)) rule.replace(at, std::strlen(from), to);
  return rule;
}

}  // namespace

CLI::Validator integerIn(int64_t lo, uint64_t hi) {
  const std::string range = rangeText(std::to_string(lo), std::to_string(hi), false);
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        if (integerTextIn(text, lo, hi)) return std::string();
        if (leadingZero(text)) return "must be written without a leading zero (got " + quote(text) + ")";
        return "must be an integer in " + range + " (got " + quote(text) + ")";
      },
      "INT in " + range);
}

CLI::Validator integerRuled(const std::string& rule, int64_t lo, int64_t hi) {
  return CLI::Validator(
      [rule, lo, hi](std::string& text) -> std::string {
        if (integerTextIn(text, lo, static_cast<uint64_t>(hi))) return std::string();
        if (leadingZero(text)) return "must be written without a leading zero (got " + quote(text) + ")";
        return "must be an integer, " + rule + " (got " + quote(text) + ")";
      },
      "");
}

void addSppOption(CLI::App& cmd, int& spp, const std::string& help) {
  const std::string& rule = requestFieldRow(RequestField::Spp).range;
  cmd.add_option("--spp", spp, help)->type_name("INT (" + asciiRule(rule) + ")")->check(integerRuled(rule, INT32_MIN, INT32_MAX));
}

CLI::Validator numberIn(double lo, double hi, bool openLow) {
  const std::string range = rangeText(shortNumber(lo), shortNumber(hi), openLow);
  return CLI::Validator(
      [lo, hi, openLow, range](std::string& text) -> std::string {
        double v = 0.0;
        const char* first = text.data();
        const char* last = first + text.size();
        const auto [end, ec] = std::from_chars(first, last, v, std::chars_format::general);
        const bool ok = !text.empty() && text[0] != '+' && ec == std::errc() && end == last && std::isfinite(v) &&
                        (openLow ? v > lo : v >= lo) && v <= hi;
        return ok ? std::string() : "must be a number in " + range + " (got " + quote(text) + ")";
      },
      "NUMBER in " + range);
}

std::optional<int64_t> parseIntegerIn(std::string_view text, int64_t lo, int64_t hi) {
  if (!plainInteger(text)) return std::nullopt;
  int64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v < lo || v > hi) return std::nullopt;
  return v;
}

void addRequestFlags(CLI::App& cmd, RequestFlags& flags, unsigned which) {
  for (const RequestFieldRow& row : requestFieldRows()) {
    if (!row.cli || !(row.cliGroup & which)) continue;
    const std::string help = row.help + " (default " + row.defaultText() + ")";
    switch (row.type) {
      case RequestFieldType::Switch: cmd.add_flag(row.cli, flags.on[row.field], help); break;
      case RequestFieldType::Text: cmd.add_option(row.cli, flags.text[row.field], help); break;
      case RequestFieldType::Integer:
        // Any integer passes here: the request states the rule, in the words a spec and Python get too.
        cmd.add_option(row.cli, flags.text[row.field], help)->type_name("INT (" + asciiRule(row.range) + ")")->check(integerRuled(row.range));
        break;
      case RequestFieldType::Number:
        cmd.add_option(row.cli, flags.text[row.field], help)->type_name("FLOAT")->check(numberIn(0, row.cliNumberMax, true));
        break;
    }
  }
}

RenderRequest readRequestFlags(const CLI::App& cmd, const RequestFlags& flags) {
  RequestFields fields;
  for (const RequestFieldRow& row : requestFieldRows()) {
    // A flag the verb did not register (addRequestFlags' `which`) was not given.
    const CLI::Option* option = row.cli ? cmd.get_option_no_throw(row.cli) : nullptr;
    if (!option || option->count() == 0) continue;
    switch (row.type) {
      case RequestFieldType::Switch: fields.set(row.field, flags.on.at(row.field)); break;
      case RequestFieldType::Text: fields.set(row.field, flags.text.at(row.field)); break;
      case RequestFieldType::Integer:  // its validator took it: a plain integer of 64 bits
        fields.set(row.field, *parseIntegerIn(flags.text.at(row.field), INT64_MIN, INT64_MAX));
        break;
      case RequestFieldType::Number: {  // its validator took it: a finite number in range
        const std::string& text = flags.text.at(row.field);
        double value = 0.0;
        std::from_chars(text.data(), text.data() + text.size(), value, std::chars_format::general);
        fields.set(row.field, value);
        break;
      }
    }
  }
  return readRenderRequest(fields, RequestFieldNames::cli());
}

RigSpec readRigFlag(const std::string& path, const std::string& sceneGiven) {
  const nlohmann::json file = readJsonFile(path);
  if (file.is_object() && file.contains("format") && file["format"] == kSceneFormat)
    throw InputError("--rig: " + showPath(path) + " is a scene file: give it as " + sceneGiven +
                     " (--rig takes a scene's \"rig\" object)");
  // A rig has no "format": another of omnicam's files (a dataset's manifest, a spec) is named as such.
  if (file.is_object() && file.contains("format") && file["format"].is_string())
    throw InputError("--rig: " + showPath(path) + " is not a rig but a file of format " + quote(file["format"].get<std::string>()) +
                     " (--rig takes a scene's \"rig\" object" +
                     (file["format"] == kManifestFormat ? "; a dataset's frames need none: their manifest gives each camera's" : "") + ")");
  return rigFromJson(file, path, "rig");
}

void checkSceneOrRigFlag(const std::string& scenePath, const std::string& rigPath) {
  if (scenePath.empty() == rigPath.empty())
    throw InputError(scenePath.empty() ? "give a scene file or --rig RIG.json (the camera's rig)"
                                       : "--rig: give a scene file or --rig, not both");
}

RigSpec rigOfSceneOrRigFlag(const std::string& scenePath, const std::string& rigPath, const SceneLoadOptions& load,
                            const std::vector<std::string>& images, const std::string& flag) {
  checkSceneOrRigFlag(scenePath, rigPath);
  if (!rigPath.empty()) {
    for (const std::string& image : images) {
      checkOutputIsNotInput(image, flag, rigPath, "the --rig file");
      checkOutputIsNotInput(sidecarPath(image), flag + " (its sidecar)", rigPath, "the --rig file");
    }
    return readRigFlag(rigPath);
  }
  const Scene scene = loadScene(scenePath, load);
  checkOutputsSpareScene(scene, images, flag);
  return scene.rig;
}

void addSceneLoadFlags(CLI::App& cmd, SceneLoadOptions& options) {
  cmd.add_flag("--allow-outside-files", options.allowOutsideFolder,
               "Let the scene pull in textures, glTF files, buffers and images from outside its own folder");
}

void refuseUnless(const CLI::App& cmd, const std::string& flag, bool allowed, const std::string& when) {
  if (!allowed && cmd.count(flag) > 0) throw InputError(flag + ": only with " + when + " (it would do nothing here)");
}

std::string scenesDir() {
  if (const char* env = std::getenv("OMNICAM_SCENES")) return env;
  return dataFile("scenes").string();
}

std::vector<std::string> ensureDirectory(const std::string& dir, const std::string& flag) {
  namespace fs = std::filesystem;
  checkOutputFolder(dir, flag);
  std::error_code ec;
  std::vector<std::string> made;
  for (fs::path at = dir; !at.empty() && !fs::exists(at, ec) && at != at.parent_path(); at = at.parent_path())
    made.push_back(at.string());
  fs::create_directories(dir, ec);
  // The name passed checkOutputFolder: what fails now is the file system (read-only, full, no
  // permission), an output that cannot be written (exit 5), not bad input.
  if (ec) throw OutputError(flag + ": cannot create folder " + showPath(dir) + " (" + ec.message() + ")");
  return made;
}

void removeMadeFolders(const std::vector<std::string>& made) {
  std::error_code ec;
  for (const std::string& folder : made) std::filesystem::remove(folder, ec);  // an empty folder only
}

void checkOutputsSpareScene(const Scene& scene, const std::vector<std::string>& images, const std::string& flag) {
  for (const std::string& image : images)
    for (const auto& [output, which] : {std::pair{image, flag}, std::pair{sidecarPath(image), flag + " (its sidecar)"}})
      for (const std::string& input : scene.inputFiles)
        checkOutputIsNotInput(output, which, input, input == scene.path ? "the scene file" : "a file the scene reads");
}

void checkScene(const std::string& sceneFile, const std::function<void()>& check) {
  try {
    check();
  } catch (const InputError& e) {
    throw InputError(showPath(sceneFile) + ": " + e.what());
  }
}

Progress::Progress(std::string label, int total, int alreadyDone, std::string unit, Clock now)
    : label_(std::move(label)), unit_(std::move(unit)), total_(total), done_(alreadyDone), alreadyDone_(alreadyDone),
      tty_(::isatty(STDERR_FILENO)), now_(now ? std::move(now) : Clock([] { return std::chrono::steady_clock::now(); })), start_(now_()),
      lastLine_(start_) {}

Progress::~Progress() { finish(); }

void Progress::step() { advanceTo(done_ + 1); }

void Progress::advanceTo(int done) {
  const int before = done_;
  done_ = done;
  const auto at = now_();
  const double seconds = std::chrono::duration<double>(at - start_).count();
  // No rate before a step was timed here: a bar made when its first step was already done would
  // divide that step by no time at all.
  const bool timed = done_ > alreadyDone_ && seconds > 0.0;
  const double rate = timed ? (done_ - alreadyDone_) / seconds : 0.0;
  const int width = 30, filled = total_ > 0 ? width * done_ / total_ : width;
  const double left = timed ? (total_ - done_) / rate : 0.0;
  char rateText[48], eta[32];
  if (timed) {
    std::snprintf(rateText, sizeof rateText, "%.1f", rate);
    std::snprintf(eta, sizeof eta, "ETA %d:%02d", static_cast<int>(left) / 60, static_cast<int>(left) % 60);
  } else {
    std::snprintf(rateText, sizeof rateText, "-");
    std::snprintf(eta, sizeof eta, "ETA -");
  }
  // Without a terminal (a log): a line at each tenth crossed (every step when there are fewer than
  // ten), and at the first step 30 s or more after the last line, so a long run's log moves.
  const auto tenth = [&](int n) { return total_ >= 10 ? static_cast<int>(int64_t{n} * 10 / total_) : n; };
  if (tty_) {
    std::fprintf(stderr, "\r%s [%s%s] %d/%d  %s %s/s  %s ", label_.c_str(), std::string(filled, '#').c_str(),
                 std::string(width - filled, ' ').c_str(), done_, total_, rateText, unit_.c_str(), eta);
    lineOpen_ = true;
  } else if (done_ == total_ || tenth(done_) > tenth(before) || at - lastLine_ >= std::chrono::seconds(30)) {
    lastLine_ = at;
    std::fprintf(stderr, "%s %d/%d  %s %s/s  %s\n", label_.c_str(), done_, total_, rateText, unit_.c_str(), eta);
  }
  std::fflush(stderr);
}

void Progress::finish() {
  if (lineOpen_) std::fprintf(stderr, "\n");
  lineOpen_ = false;
}

}  // namespace omnicam::cli
