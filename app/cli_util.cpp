#include "cli_util.h"

#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "atomic_file.h"
#include "errors.h"
#include "number_format.h"
#include "render_settings.h"

namespace omnicam::cli {

Vec3 parseTriple(const std::string& text, const std::string& flag) {
  Vec3 out;
  size_t start = 0;
  for (int k = 0; k < 3; ++k) {
    const size_t end = k < 2 ? text.find(',', start) : text.size();
    if (end == std::string::npos)
      throw InputError(flag + ": expected three comma-separated numbers X,Y,Z (got " + quote(text) + ")");
    const char* first = text.data() + start;
    const char* last = text.data() + end;
    double v = 0.0;
    auto [ptr, ec] = std::from_chars(first, last, v);
    if (ec != std::errc() || ptr != last || !std::isfinite(v))
      throw InputError(flag + ": " + quote(std::string_view(first, static_cast<size_t>(last - first))) + " is not a number");
    out[k] = v;
    start = end + 1;
  }
  return out;
}

RobotPose parsePose(const std::string& text, const std::string& flag) {
  const Vec3 p = parseTriple(text, flag);
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

std::string rangeText(const std::string& lo, const std::string& hi, bool openLow) {
  return std::string(openLow ? "(" : "[") + lo + ", " + hi + "]";
}

}  // namespace

CLI::Validator integerIn(int64_t lo, uint64_t hi) {
  const std::string range = rangeText(std::to_string(lo), std::to_string(hi), false);
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        bool ok = plainInteger(text);
        if (ok && text[0] == '-') {
          int64_t v = 0;
          const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
          ok = ec == std::errc() && end == text.data() + text.size() && v >= lo;
        } else if (ok) {
          uint64_t v = 0;
          const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
          ok = ec == std::errc() && end == text.data() + text.size() && v <= hi && (lo <= 0 || v >= static_cast<uint64_t>(lo));
        }
        return ok ? std::string() : "must be an integer in " + range + " (got " + quote(text) + ")";
      },
      "INT in " + range);
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
  const RenderRequest defaults;
  const auto integer = integerIn(0, INT32_MAX);  // the syntax; readRenderRequest checks the range
  if (which & kEngineFlag) cmd.add_option("--engine", flags.engine, "fast (default), povray or blender (ground truth)");
  if (which & kTimeoutFlag)
    cmd.add_option("--timeout", flags.timeout,
                   "Seconds allowed per external render (default " + shortNumber(defaults.timeoutSeconds) + ")")
        ->check(numberIn(0, limits::kMaxTimeoutSeconds, true));
  if (which & kSppFlag)
    cmd.add_option("--spp", flags.spp, "Samples per pixel, n*n on a regular grid (default " + std::to_string(defaults.spp) + ")")
        ->check(integer);
  if (which & kShadingFlag) {
    cmd.add_option("--shading", flags.shading,
                   "unlit (default), lit (the thesis' model) or path (physically based, docs/conventions.md §3)");
    cmd.add_option("--bounces", flags.bounces,
                   "path: diffuse bounces per path, as Cycles' diffuse_bounces (default " + std::to_string(defaults.bounces) +
                       ", as Blender's export)")
        ->check(integerIn(0, kMaxBounces));
    cmd.add_option("--seed", flags.seed, "path and blender: the random stream's seed (default 0)")->check(integerIn(0, INT64_MAX));
    cmd.add_flag("--denoise", flags.denoise,
                 "Path-traced frames: filter the indirect light, guided by albedo, normal and depth (a small bias)");
  }
  if (which & kModeFlags) {
    cmd.add_option("--mode", flags.mode, "exact (default), cubemap (thesis' cube faces) or thesis-mesh (thesis' mirror mesh)");
    cmd.add_option("--faces", flags.faces,
                   "cubemap/thesis-mesh: 5 (the thesis) or 6 cube faces (default " + std::to_string(defaults.modeOptions.faces) + ")")
        ->check(integer);
    cmd.add_option("--face-size", flags.faceSize,
                   "cubemap/thesis-mesh: texels per face edge (default " + std::to_string(defaults.modeOptions.faceSize) + ")")
        ->check(integer);
    cmd.add_option("--polygons", flags.polygons,
                   "thesis-mesh: 16, 64, 256 or 1024 mirror polygons (default " +
                       std::to_string(defaults.modeOptions.polygons) + ")")
        ->check(integer);
  }
}

RenderRequest readRequestFlags(const CLI::App& cmd, const RequestFlags& flags) {
  // A flag the verb did not register (addRequestFlags' `which`) was not given.
  const auto given = [&](const char* flag) {
    const CLI::Option* option = cmd.get_option_no_throw(flag);
    return option && option->count() > 0;
  };
  RequestFields f;
  if (given("--engine")) f.engine = flags.engine;
  if (given("--mode")) f.mode = flags.mode;
  if (given("--shading")) f.shading = flags.shading;
  if (given("--faces")) f.faces = flags.faces;
  if (given("--face-size")) f.faceSize = flags.faceSize;
  if (given("--polygons")) f.polygons = flags.polygons;
  if (given("--spp")) f.spp = flags.spp;
  if (given("--timeout")) f.timeoutSeconds = flags.timeout;
  if (given("--bounces")) f.bounces = flags.bounces;
  if (given("--seed")) f.seed = flags.seed;
  if (given("--denoise")) f.denoise = flags.denoise;
  return readRenderRequest(f, RequestFieldNames::cli());
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
  return OMNICAM_SCENES_DIR;
}

std::vector<std::string> ensureDirectory(const std::string& dir, const std::string& flag) {
  namespace fs = std::filesystem;
  checkOutputFolder(dir, flag);
  std::error_code ec;
  std::vector<std::string> made;
  for (fs::path at = dir; !at.empty() && !fs::exists(at, ec) && at != at.parent_path(); at = at.parent_path())
    made.push_back(at.string());
  fs::create_directories(dir, ec);
  if (ec) throw InputError(flag + ": cannot create folder " + showPath(dir) + " (" + ec.message() + ")");
  return made;
}

void removeMadeFolders(const std::vector<std::string>& made) {
  std::error_code ec;
  for (const std::string& folder : made) std::filesystem::remove(folder, ec);  // an empty folder only
}

Progress::Progress(std::string label, int total, int alreadyDone)
    : label_(std::move(label)), total_(total), done_(alreadyDone), alreadyDone_(alreadyDone),
      tty_(::isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()) {}

void Progress::step() {
  ++done_;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = seconds > 0.0 ? (done_ - alreadyDone_) / seconds : 0.0;
  const int width = 30, filled = total_ > 0 ? width * done_ / total_ : width;
  const double left = rate > 0.0 ? (total_ - done_) / rate : 0.0;
  char eta[32];
  std::snprintf(eta, sizeof eta, "ETA %d:%02d", static_cast<int>(left) / 60, static_cast<int>(left) % 60);
  if (tty_) {
    std::fprintf(stderr, "\r%s [%s%s] %d/%d  %.1f frames/s  %s ", label_.c_str(), std::string(filled, '#').c_str(),
                 std::string(width - filled, ' ').c_str(), done_, total_, rate, eta);
  } else if (done_ == total_ || (total_ >= 10 && done_ % (total_ / 10) == 0)) {
    std::fprintf(stderr, "%s %d/%d  %.1f frames/s  %s\n", label_.c_str(), done_, total_, rate, eta);
  }
  std::fflush(stderr);
}

void Progress::finish() {
  if (tty_) std::fprintf(stderr, "\n");
}

}  // namespace omnicam::cli
