#pragma once
// What each engine can render, as one row per engine (and fast mode): every caller checks a
// request against it the same way (checkEngineRenders), before anything is written, and the
// message names the engines that can.
#include <optional>
#include <string>
#include <vector>

#include "omni_mode.h"
#include "placement.h"
#include "render_settings.h"
#include "rig.h"

namespace omnicam {

// One identity per engine and fast mode: its row below holds its names and what it renders.
enum class EngineKind { FastExact, FastCubeMap, FastThesisMesh, Povray, Blender };

struct EngineCapabilities {
  EngineKind kind = EngineKind::FastExact;
  const char* engine = "";     // as requests, sidecars and manifests name it: fast, povray, blender
  OmniMode mode = OmniMode::Exact;  // the fast engine's modes; the ground truths' is exact
  const char* shownName = "";  // in messages: "the povray engine", "the fast engine's cube-map mode"
  // Cameras: a camera off the mirror's focus (false: the ideal rig only, central by
  // construction), the mirror shapes it has exact surfaces of, a distorting lens.
  bool misalignedCamera = true;
  std::vector<MirrorShape> mirrorShapes;
  bool lensDistortion = true;
  // The cameras without a mirror it renders (rig.lens): every model, or these by lensModelName
  // (lens_models.h).
  bool everyLensModel = false;
  std::vector<std::string> lensModels;
  // Its lens cameras centre their image (the principal point at the image's centre) and their
  // panoramas are symmetric about their direction (POV-Ray's own cameras); Cycles' shift instead.
  bool centredLensesOnly = false;
  // Its fisheyes are Cycles' panoramic cameras, whose settings Blender clamps: fisheye_fov ≥ 10°,
  // fisheye_lens ≤ 100 mm on the 36 mm sensor (refused beyond, never clamped).
  bool cyclesLensLimits = false;
  // Time: a robot moving while the shutter is open, a rolling shutter, stratified time samples.
  bool motion = true, rollingShutter = true, timeSamples = true;
  // Physically based light (Shading::Path).
  bool pathShading = false;
  // Per-pixel ground truth (AOVs) beside the colour.
  bool aovs = false;
  // Rendering many frames at once is cheaper than one at a time (callers then batch frames).
  bool batches = false;
  // Several frames may render at once, from different threads.
  bool concurrent = false;
  // Why a missing capability is missing, where the engine has a reason worth telling.
  std::string why;
};

const EngineCapabilities& capabilitiesOf(EngineKind engine);
// The fast engine's kind in this mode.
EngineKind fastEngineKind(OmniMode mode);
// The engine of this name in this mode (omni_mode.h's names), or nullopt for none.
std::optional<EngineKind> engineKindNamed(const std::string& engine, OmniMode mode = OmniMode::Exact);
// "fast, povray or blender": the engines a request may name.
std::string engineChoices();

// InputError naming what `engine` cannot render of this rig at this placement (and its AOVs when
// `aovs`), and which engines can; nothing when it can.
void checkEngineRenders(EngineKind engine, const RigSpec& rig, const CameraPlacement& placement, bool aovs = false);
// InputError naming the engines that shade this way, unless `engine` does; the message starts
// with `shadingField` as the user's front names the setting ("--shading path: …").
void checkEngineShading(EngineKind engine, Shading shading, const std::string& shadingField = "shading");

}  // namespace omnicam
