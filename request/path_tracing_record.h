#pragma once
// What a path-traced frame's metadata (a render's sidecar, a dataset's manifest) records of how
// it was sampled: enough to render it again.
#include <nlohmann/json.hpp>
#include <string_view>

#include "render_settings.h"

namespace omnicam {

// {"bounces", "seed", "denoise"}, and with adaptive sampling "adaptive_spp" and "target_error".
inline nlohmann::json pathTracingRecord(const RenderSampling& sampling) {
  nlohmann::json record = {{"bounces", sampling.bounces}, {"seed", sampling.seed}, {"denoise", sampling.denoise}};
  if (sampling.adaptiveSpp > 0) {
    record["adaptive_spp"] = sampling.adaptiveSpp;
    record["target_error"] = sampling.targetError;
  }
  return record;
}

// What a frame records of its random sampling: a `path` frame its pathTracingRecord; any other
// frame of the blender engine (Cycles samples every frame, lit ones path traced by its own bounce
// settings, docs/blender.md) its seed and whether it was filtered; null for a frame that draws no
// random numbers.
inline nlohmann::json randomSamplingRecord(std::string_view engine, const RenderSampling& sampling) {
  if (sampling.shading == Shading::Path) return pathTracingRecord(sampling);
  if (engine == "blender") return {{"seed", sampling.seed}, {"denoise", sampling.denoise}};
  return nullptr;
}

}  // namespace omnicam
