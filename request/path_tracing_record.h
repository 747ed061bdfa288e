#pragma once
// What a path-traced frame's metadata (a render's sidecar, a dataset's manifest) records of how
// it was sampled: enough to render it again.
#include <nlohmann/json.hpp>

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

}  // namespace omnicam
