#include "render_request.h"

#include <algorithm>

#include "engine_capabilities.h"
#include "errors.h"
#include "input_limits.h"
#include "number_format.h"

namespace omnicam {

namespace {

class Reader {
 public:
  explicit Reader(const RequestFieldNames& names) : names_(names) {}
  [[noreturn]] void fail(RequestField field, const std::string& rule) const {
    throw InputError(qualified(field) + ": " + rule);
  }
  std::string name(RequestField field) const { return names_(field); }
  std::string qualified(RequestField field) const { return names_.prefix + names_(field); }
  const RequestFieldNames& names() const { return names_; }
  int integerIn(const std::optional<int64_t>& given, int fallback, RequestField field, int64_t lo, int64_t hi,
                const std::string& unit = "") const {
    if (!given) return fallback;
    if (*given < lo || *given > hi)
      fail(field, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]" + unit + " (got " +
                      std::to_string(*given) + ")");
    return static_cast<int>(*given);
  }

 private:
  const RequestFieldNames& names_;
};

}  // namespace

namespace {

// The rule of one mode option, on the value as given (any 64-bit integer, never narrowed first).
void checkModeOption(RequestField field, int64_t value, const Reader& r) {
  switch (field) {
    case RequestField::Faces:
      if (value != 5 && value != 6) r.fail(field, "must be 5 or 6 (got " + std::to_string(value) + ")");
      break;
    case RequestField::FaceSize: r.integerIn(value, 0, field, 8, 8192, " texels"); break;
    case RequestField::Polygons:
      if (value != 16 && value != 64 && value != 256 && value != 1024)
        r.fail(field, "must be 16, 64, 256 or 1024 (got " + std::to_string(value) + ")");
      break;
    default: break;
  }
}

}  // namespace

std::optional<EngineKind> RenderRequest::engineKind() const {
  const std::optional<CubeMapOptions> cube = cubeMap();
  return engineKindNamed(engine, cube ? cube->mode : OmniMode::Exact);
}

void checkModeOptions(const CubeMapOptions& o, const RequestFieldNames& names) {
  const Reader r(names);
  checkModeOption(RequestField::Faces, o.faces, r);
  checkModeOption(RequestField::FaceSize, o.faceSize, r);
  if (o.mode == OmniMode::ThesisMesh) checkModeOption(RequestField::Polygons, o.polygons, r);
}

namespace {

using F = RequestField;

// engine, mode and the mode's options.
void readEngineAndMode(const RequestFields& f, const Reader& r, RenderRequest& q) {
  q.engine = f.text(F::Engine).value_or(q.engine);
  if (!engineKindNamed(q.engine)) r.fail(F::Engine, "must be " + engineChoices() + " (got " + quote(q.engine) + ")");
  q.mode = f.text(F::Mode).value_or(q.mode);
  const std::optional<OmniMode> mode = omniModeNamed(q.mode);
  if (!mode) r.fail(F::Mode, "must be exact, cubemap or thesis-mesh (got " + quote(q.mode) + ")");
  if (!engineKindNamed(q.engine, *mode)) r.fail(F::Mode, "only the fast engine has modes other than exact");
  if ((f.has(F::Faces) || f.has(F::FaceSize)) && q.mode == "exact")
    r.fail(f.has(F::Faces) ? F::Faces : F::FaceSize, "only with " + r.name(F::Mode) + " cubemap or thesis-mesh");
  if (f.has(F::Polygons) && q.mode != "thesis-mesh") r.fail(F::Polygons, "only with " + r.name(F::Mode) + " thesis-mesh");
  // Each given option meets its rule as given; only then is it an int.
  const auto narrow = [&f, &r](F field, int fallback) {
    const std::optional<int64_t> v = f.integer(field);
    if (!v) return fallback;
    checkModeOption(field, *v, r);
    return static_cast<int>(*v);
  };
  q.modeOptions.faces = narrow(F::Faces, q.modeOptions.faces);
  q.modeOptions.faceSize = narrow(F::FaceSize, q.modeOptions.faceSize);
  q.modeOptions.polygons = narrow(F::Polygons, q.modeOptions.polygons);
  if (const auto options = q.cubeMap()) checkModeOptions(*options, r.names());
}

// adaptive_spp and target_error: after spp, shading and denoise.
void readAdaptive(const RequestFields& f, const Reader& r, RenderRequest& q) {
  if (const auto target = f.number(F::TargetError)) {
    if (!f.has(F::AdaptiveSpp)) r.fail(F::TargetError, "only with " + r.name(F::AdaptiveSpp));
    if (!(*target > 0.0 && *target <= 1.0)) r.fail(F::TargetError, "must be in (0, 1] (got " + roundTrip(*target) + ")");
    q.targetError = *target;
  }
  const std::optional<int64_t> most = f.integer(F::AdaptiveSpp);
  if (!most || *most == 0) return;
  if (q.engine != "fast" || q.mode != "exact" || q.shading != Shading::Path)
    r.fail(F::AdaptiveSpp, "only with the fast engine's exact mode and " + r.name(F::Shading) + " path");
  if (q.denoise)
    r.fail(F::AdaptiveSpp, "not with " + r.name(F::Denoise) +
                               " (refining some pixels of a filtered frame made it worse: docs/path-tracing.md, \"Adaptive sampling\")");
  if (q.spp < 4)
    r.fail(F::AdaptiveSpp, "needs " + r.name(F::Spp) + " of at least 4 (the first grid's noise is measured from its samples)");
  int64_t grid = q.spp;
  while (grid < *most && grid <= limits::kMaxSpp / 4) grid *= 4;
  if (*most <= q.spp || grid != *most || *most > limits::kMaxSpp)
    r.fail(F::AdaptiveSpp, "must be " + r.name(F::Spp) + " (" + std::to_string(q.spp) + ") times 4, 16, 64, … up to " +
                               std::to_string(limits::kMaxSpp) + " (got " + std::to_string(*most) + ")");
  q.adaptiveSpp = static_cast<int>(*most);
}

// spp, shading, traced, bounces, denoise and seed.
void readSampling(const RequestFields& f, const Reader& r, RenderRequest& q) {
  if (const auto spp = f.integer(F::Spp)) {
    checkSpp(*spp, r.qualified(F::Spp));
    q.spp = static_cast<int>(*spp);
  }
  const std::string shading = f.text(F::Shading).value_or(shadingName(q.shading));
  const auto parsed = parseShading(shading);
  if (!parsed) r.fail(F::Shading, "must be unlit, lit or path (got " + quote(shading) + ")");
  q.shading = *parsed;
  // Said here in the front's words (--shading); makeEngine checks it again for other callers.
  if (const auto kind = q.engineKind())
    checkEngineShading(*kind, q.shading, r.qualified(F::Shading));
  q.traced = f.isOn(F::Traced).value_or(q.traced);
  if (q.traced && (q.engine != "fast" || q.mode != "exact"))
    r.fail(F::Traced, "only with the fast engine in exact mode (the other engines always trace)");
  if (f.has(F::Bounces)) {
    if (q.shading != Shading::Path) r.fail(F::Bounces, "only with " + r.name(F::Shading) + " path");
    q.bounces = r.integerIn(f.integer(F::Bounces), q.bounces, F::Bounces, 0, kMaxBounces);
  }
  if (f.isOn(F::Denoise).value_or(false)) {
    const bool pathTraced = q.shading == Shading::Path || (q.engine == "blender" && q.shading == Shading::Lit);
    if (!pathTraced) r.fail(F::Denoise, "only for path-traced frames: " + r.name(F::Shading) + " path, or the blender engine lit");
    q.denoise = true;
  }
  readAdaptive(f, r, q);
  if (const auto seed = f.integer(F::Seed)) {
    // Only path-traced frames draw random numbers: anywhere else a seed would change nothing.
    if (q.shading != Shading::Path && q.engine != "blender")
      r.fail(F::Seed, "only with " + r.name(F::Shading) + " path or " + r.name(F::Engine) + " blender (nothing else is random; a recording camera's draws take the \"seed\" of the recording)");
    constexpr int64_t kMaxSeed = int64_t{1} << 53;  // exact in every JSON reader and in Python
    if (*seed < 0 || *seed > kMaxSeed) r.fail(F::Seed, "must be in [0, 2^53] (got " + std::to_string(*seed) + ")");
    q.seed = static_cast<uint64_t>(*seed);
  }
}

// threads and timeout: a ground truth's.
void readExternal(const RequestFields& f, const Reader& r, RenderRequest& q) {
  if (const auto threads = f.integer(F::Threads)) {
    checkThreads(*threads, r.qualified(F::Threads));
    q.threads = static_cast<int>(*threads);
  }
  if (const auto timeout = f.number(F::Timeout)) {
    if (q.engine == "fast") r.fail(F::Timeout, "only with " + r.name(F::Engine) + " povray or blender");
    if (!(*timeout > 0.0 && *timeout <= limits::kMaxTimeoutSeconds))
      r.fail(F::Timeout, "must be in (0, " + shortNumber(limits::kMaxTimeoutSeconds) + "] s (got " + roundTrip(*timeout) + ")");
    q.timeoutSeconds = *timeout;
  }
}

}  // namespace

RenderSettings requestedSettings(const RigSpec& rig, const RequestFields& fields) {
  return readRenderRequest(fields, {}).settings(rig);
}

RenderRequest readRenderRequest(const RequestFields& f, const RequestFieldNames& names) {
  const Reader r(names);
  RenderRequest q;
  readEngineAndMode(f, r, q);
  readSampling(f, r, q);
  readExternal(f, r, q);
  return q;
}

}  // namespace omnicam
