#pragma once
// One render request: which engine renders, in which mode, with which settings (spp, shading,
// threads, timeout). Read by one reader from CLI flags, dataset JSON and Python keyword
// arguments, whose settings are the rows of request_fields.h: each front end names them its own
// way (RequestFieldNames), the rules, the defaults and the messages are these. makeEngine
// (render/engines.h) takes the result.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "omni_mode.h"
#include "render_settings.h"
#include "request_fields.h"

namespace omnicam {

enum class EngineKind;  // engine_capabilities.h

// Seconds an external render (POV-Ray, Blender) may take before it is stopped.
inline constexpr double kDefaultTimeoutSeconds = 600.0;

// The sampling (spp, shading, traced, bounces, seed, denoise) is RenderSampling's, defaults included.
struct RenderRequest : RenderSampling {
  RenderRequest() = default;
  // The defaults, with this engine (a name readRenderRequest accepts).
  explicit RenderRequest(std::string engineName) : engine(std::move(engineName)) {}

  std::string engine = "fast";  // fast, povray or blender
  std::string mode = "exact";   // exact, cubemap or thesis-mesh (fast only)
  CubeMapOptions modeOptions;   // faces, face size, polygons (omni_mode.h's defaults); its own `mode` is unused
  int threads = 0;              // render threads (a ground truth's; Python's Renderer caps the fast engine's); 0: every core
  double timeoutSeconds = kDefaultTimeoutSeconds;

  // The mode's options (their `mode` taken from `mode`), or nullopt for exact.
  std::optional<CubeMapOptions> cubeMap() const {
    if (mode == "exact") return std::nullopt;
    CubeMapOptions options = modeOptions;
    options.mode = omniModeNamed(mode).value_or(OmniMode::CubeMap);
    return options;
  }
  // The engine and mode this request names, or nullopt for a pair no engine has (readRenderRequest refuses those).
  std::optional<EngineKind> engineKind() const;
  // The settings of a render of `rig` with this request: the only way settings are made.
  RenderSettings settings(const RigSpec& rig) const {
    RenderSettings out;
    static_cast<RenderSampling&>(out) = *this;
    out.rig = rig;
    return out;
  }
};

// The rules of the cube-map / thesis-mesh options (faces 5 or 6, 8–8192 texels a face edge,
// 16, 64, 256 or 1024 mirror polygons for the thesis mesh): InputError naming the field as `names`
// does. readRenderRequest and the cube-map renderer both check by it.
void checkModeOptions(const CubeMapOptions& options, const RequestFieldNames& names = {});

// InputError "<prefix><name>: <rule> (got …)" for the first field that breaks a rule: an
// unknown engine, mode or shading, mode options out of range or without the mode that uses them,
// a mode or timeout the engine does not have, spp not a perfect square up to the limit, threads
// out of range, bounces without path shading or out of 0–kMaxBounces, a seed out of 0–2^53.
RenderRequest readRenderRequest(const RequestFields& fields, const RequestFieldNames& names);

// The settings of a render of `rig` with the request `fields` give (readRenderRequest, in the
// library's names): how the demo, the bench and the experiments ask for their renders.
RenderSettings requestedSettings(const RigSpec& rig, const RequestFields& fields);

}  // namespace omnicam
