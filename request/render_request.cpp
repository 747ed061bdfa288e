#include "render_request.h"

#include <algorithm>

#include "engine_capabilities.h"
#include "errors.h"
#include "input_limits.h"
#include "number_format.h"

namespace omnicam {

RequestFieldNames RequestFieldNames::cli() {
  RequestFieldNames n;
  n.engine = "--engine", n.mode = "--mode", n.faces = "--faces", n.faceSize = "--face-size", n.polygons = "--polygons";
  n.spp = "--spp", n.shading = "--shading", n.traced = "--traced", n.threads = "--threads", n.timeout = "--timeout";
  n.bounces = "--bounces", n.seed = "--seed", n.denoise = "--denoise";
  return n;
}

RequestFieldNames RequestFieldNames::json(const std::string& file) {
  RequestFieldNames n;
  n.prefix = showPath(file) + ": ";
  n.faces = "mode_options.faces", n.faceSize = "mode_options.face_size", n.polygons = "mode_options.polygons";
  n.timeout = "timeout_s";
  return n;
}

namespace {

class Reader {
 public:
  explicit Reader(const RequestFieldNames& names) : names_(names) {}
  [[noreturn]] void fail(const std::string& field, const std::string& rule) const {
    throw InputError(names_.prefix + field + ": " + rule);
  }
  int integerIn(const std::optional<int64_t>& given, int fallback, const std::string& field, int64_t lo, int64_t hi,
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

void checkModeOptions(const CubeMapOptions& o, const RequestFieldNames& names) {
  const Reader r(names);
  if (o.faces != 5 && o.faces != 6) r.fail(names.faces, "must be 5 or 6 (got " + std::to_string(o.faces) + ")");
  r.integerIn(o.faceSize, o.faceSize, names.faceSize, 8, 8192, " texels");
  if (o.mode == OmniMode::ThesisMesh && o.polygons != 16 && o.polygons != 64 && o.polygons != 256 && o.polygons != 1024)
    r.fail(names.polygons, "must be 16, 64, 256 or 1024 (got " + std::to_string(o.polygons) + ")");
}

RenderRequest readRenderRequest(const RequestFields& f, const RequestFieldNames& names) {
  const Reader r(names);
  RenderRequest q;
  q.engine = f.engine.value_or(q.engine);
  if (!engineKindNamed(q.engine)) r.fail(names.engine, "must be " + engineChoices() + " (got " + quote(q.engine) + ")");
  q.mode = f.mode.value_or(q.mode);
  const std::optional<OmniMode> mode = omniModeNamed(q.mode);
  if (!mode) r.fail(names.mode, "must be exact, cubemap or thesis-mesh (got " + quote(q.mode) + ")");
  if (!engineKindNamed(q.engine, *mode)) r.fail(names.mode, "only the fast engine has modes other than exact");
  if ((f.faces || f.faceSize) && q.mode == "exact")
    r.fail(f.faces ? names.faces : names.faceSize, "only with " + names.mode + " cubemap or thesis-mesh");
  if (f.polygons && q.mode != "thesis-mesh") r.fail(names.polygons, "only with " + names.mode + " thesis-mesh");
  const auto narrow = [](const std::optional<int64_t>& v, int fallback) {
    return v ? static_cast<int>(std::clamp<int64_t>(*v, INT32_MIN, INT32_MAX)) : fallback;
  };
  q.modeOptions.faces = narrow(f.faces, q.modeOptions.faces);
  q.modeOptions.faceSize = narrow(f.faceSize, q.modeOptions.faceSize);
  q.modeOptions.polygons = narrow(f.polygons, q.modeOptions.polygons);
  if (const auto options = q.cubeMap()) checkModeOptions(*options, names);
  if (f.spp) checkSpp(*f.spp, names.prefix + names.spp);
  q.spp = f.spp ? static_cast<int>(*f.spp) : q.spp;
  const std::string shading = f.shading.value_or(shadingName(q.shading));
  const auto parsed = parseShading(shading);
  if (!parsed) r.fail(names.shading, "must be unlit, lit or path (got " + quote(shading) + ")");
  q.shading = *parsed;
  q.traced = f.traced.value_or(q.traced);
  if (q.traced && (q.engine != "fast" || q.mode != "exact"))
    r.fail(names.traced, "only with the fast engine in exact mode (the other engines always trace)");
  if (f.threads) checkThreads(static_cast<int>(std::clamp<int64_t>(*f.threads, -1, limits::kMaxThreads + 1)), names.prefix + names.threads);
  q.threads = f.threads ? static_cast<int>(*f.threads) : q.threads;
  if (f.bounces) {
    if (q.shading != Shading::Path) r.fail(names.bounces, "only with " + names.shading + " path");
    q.bounces = r.integerIn(f.bounces, q.bounces, names.bounces, 0, kMaxBounces);
  }
  if (f.denoise && *f.denoise) {
    const bool pathTraced = q.shading == Shading::Path || (q.engine == "blender" && q.shading == Shading::Lit);
    if (!pathTraced) r.fail(names.denoise, "only for path-traced frames: " + names.shading + " path, or the blender engine lit");
    q.denoise = true;
  }
  if (f.seed) {
    constexpr int64_t kMaxSeed = int64_t{1} << 53;  // exact in every JSON reader and in Python
    if (*f.seed < 0 || *f.seed > kMaxSeed)
      r.fail(names.seed, "must be in [0, 2^53] (got " + std::to_string(*f.seed) + ")");
    q.seed = static_cast<uint64_t>(*f.seed);
  }
  if (f.timeoutSeconds) {
    if (q.engine == "fast") r.fail(names.timeout, "only with " + names.engine + " povray or blender");
    if (!(*f.timeoutSeconds > 0.0 && *f.timeoutSeconds <= limits::kMaxTimeoutSeconds))
      r.fail(names.timeout, "must be in (0, " + shortNumber(limits::kMaxTimeoutSeconds) + "] s (got " +
                                shortNumber(*f.timeoutSeconds) + ")");
    q.timeoutSeconds = *f.timeoutSeconds;
  }
  return q;
}

}  // namespace omnicam
