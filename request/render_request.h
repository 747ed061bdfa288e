#pragma once
// One render request: which engine renders, in which mode, with which settings (spp, shading,
// threads, timeout). Read by one reader from CLI flags, dataset JSON and Python keyword
// arguments: each front end names its fields its own way (RequestFieldNames), the rules, the
// defaults and the messages are these. makeEngine (render/engines.h) takes the result.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "omni_mode.h"
#include "render_settings.h"

namespace omnicam {

// Seconds an external render (POV-Ray, Blender) may take before it is stopped.
inline constexpr double kDefaultTimeoutSeconds = 600.0;

struct RenderRequest {
  RenderRequest() = default;
  // The defaults, with this engine (a name readRenderRequest accepts).
  explicit RenderRequest(std::string engineName) : engine(std::move(engineName)) {}

  std::string engine = "fast";  // fast, povray or blender
  std::string mode = "exact";   // exact, cubemap or thesis-mesh (fast only)
  CubeMapOptions modeOptions;   // faces, face size, polygons (omni_mode.h's defaults); its own `mode` is unused
  int spp = 1;
  Shading shading = Shading::Unlit;
  bool traced = false;          // the fast engine traces even the ideal rig (render_settings.h)
  int threads = 0;              // a ground truth's render threads; 0: every core
  double timeoutSeconds = kDefaultTimeoutSeconds;
  int bounces = kDefaultBounces;  // path shading only
  uint64_t seed = 0;              // path shading and Blender: the random stream
  bool denoise = false;           // path-traced frames: filter the indirect light

  // The mode's options (their `mode` taken from `mode`), or nullopt for exact.
  std::optional<CubeMapOptions> cubeMap() const {
    if (mode == "exact") return std::nullopt;
    CubeMapOptions options = modeOptions;
    options.mode = omniModeNamed(mode).value_or(OmniMode::CubeMap);
    return options;
  }
  // The settings of a render of `rig` with this request.
  RenderSettings settings(const RigSpec& rig) const { return {rig, spp, shading, traced, bounces, seed, denoise}; }
};

// How a front end names each field in messages, and a prefix before them (a spec's file name).
struct RequestFieldNames {
  std::string prefix;
  std::string engine = "engine", mode = "mode", faces = "faces", faceSize = "face_size", polygons = "polygons",
              spp = "spp", shading = "shading", traced = "traced", threads = "threads", timeout = "timeout",
              bounces = "bounces", seed = "seed", denoise = "denoise";
  static RequestFieldNames cli();                         // --engine, --face-size, …
  static RequestFieldNames json(const std::string& file);  // "FILE: engine", "FILE: mode_options.faces", …
};

// The fields as a user gave them: an absent one takes RenderRequest's default.
struct RequestFields {
  std::optional<std::string> engine, mode, shading;
  std::optional<int64_t> faces, faceSize, polygons, spp, threads, bounces, seed;
  std::optional<double> timeoutSeconds;
  std::optional<bool> traced, denoise;
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

}  // namespace omnicam
