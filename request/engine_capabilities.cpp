#include "engine_capabilities.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>

#include "errors.h"
#include "mirror_mesh.h"
#include "number_format.h"

namespace omnicam {

namespace {

const std::vector<MirrorShape> kEveryShape = {MirrorShape::Hyperboloid, MirrorShape::Paraboloid, MirrorShape::Sphere,
                                              MirrorShape::Cone};

EngineCapabilities fastExact() {
  EngineCapabilities c;
  c.kind = EngineKind::FastExact;
  c.engine = "fast";
  c.shownName = "the fast engine";
  c.mirrorShapes = kEveryShape;
  c.everyLensModel = true;  // it traces lens_models.h itself
  c.aovs = true;
  c.pathShading = true;
  c.concurrent = true;  // a pure function of the placement
  return c;
}

EngineCapabilities fastCentral(EngineKind kind, OmniMode mode, const char* shownName) {
  EngineCapabilities c;
  c.kind = kind;
  c.engine = "fast";
  c.mode = mode;
  c.shownName = shownName;
  c.misalignedCamera = false;
  c.mirrorShapes = {MirrorShape::Hyperboloid};
  c.lensDistortion = false;
  c.motion = c.rollingShutter = c.timeSamples = false;
  c.aovs = true;  // from the exact pixel → ray map, whatever the colour's mode
  return c;
}

EngineCapabilities povray() {
  EngineCapabilities c;
  c.kind = EngineKind::Povray;
  c.engine = "povray";
  c.shownName = "the povray engine";
  c.mirrorShapes = kEveryShape;
  c.lensModels = {"fisheye_equidistant", "equirectangular", "pinhole"};  // fisheye, spherical, perspective
  c.centredLensesOnly = true;
  c.lensDistortion = false;
  return c;
}

EngineCapabilities blender() {
  EngineCapabilities c;
  c.kind = EngineKind::Blender;
  c.engine = "blender";
  c.shownName = "the blender engine";
  c.mirrorShapes.assign(std::begin(kCertifiedMeshShapes), std::end(kCertifiedMeshShapes));
  // Cycles' panoramic cameras (fisheye equidistant or lens polynomial, equisolid, equirectangular) and its perspective one.
  c.lensModels = {"fisheye_equidistant", "fisheye_equisolid", "fisheye_polynomial", "equirectangular", "pinhole"};
  c.cyclesLensLimits = true;
  c.lensDistortion = false;
  c.rollingShutter = false;
  c.timeSamples = false;
  c.batches = true;
  c.pathShading = true;
  c.why = "Cycles samples time continuously over the exposure, and its rolling shutter is approximate";
  return c;
}

// The engines a user can pick, as messages name them.
const std::vector<EngineKind> kChoices = {EngineKind::FastExact, EngineKind::Povray, EngineKind::Blender};

// "a, b or c".
std::string listWithOr(const std::vector<std::string>& names) {
  std::string out;
  for (size_t k = 0; k < names.size(); ++k) out += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  return out;
}

// "the fast engine or the povray engine": the engines that have what `has` asks.
// The engines that have what `refusing` lacks. A mode of the fast engine that refuses sends the
// user to its exact mode, not to "the fast engine" it already is.
std::string enginesThat(const EngineCapabilities& refusing, const std::function<bool(const EngineCapabilities&)>& has) {
  const bool fastMode = std::string_view(refusing.engine) == "fast" && refusing.mode != OmniMode::Exact;
  std::vector<std::string> names;
  for (EngineKind e : kChoices)
    if (has(capabilitiesOf(e)))
      names.push_back(fastMode && e == EngineKind::FastExact ? "the fast engine's exact mode" : capabilitiesOf(e).shownName);
  return listWithOr(names);
}

bool hasShape(const EngineCapabilities& c, MirrorShape shape) {
  return std::find(c.mirrorShapes.begin(), c.mirrorShapes.end(), shape) != c.mirrorShapes.end();
}

// What keeps an engine's own camera from being this lens: "" when nothing does.
std::string lensProblem(const LensCameraSpec& lens, bool centredOnly, bool cyclesLimits) {
  const double cx = (lens.width - 1) / 2.0, cy = (lens.height - 1) / 2.0;
  const auto centred = [&](double x, double y) { return std::abs(x - cx) <= 1e-9 * lens.width && std::abs(y - cy) <= 1e-9 * lens.height; };
  if (const auto* p = std::get_if<PinholeRadTan>(&lens.model)) {
    if (!p->distortion.none()) return "distortion: its perspective camera has no lens distortion";
    if (p->fx != p->fy) return "fx, fy: its perspective camera has square pixels (fx = fy)";
    if (centredOnly && !centred(p->cx, p->cy)) return "cx, cy: its perspective camera centres the image ((width − 1)/2, (height − 1)/2)";
  } else if (const auto* f = std::get_if<FThetaLens>(&lens.model)) {
    if (centredOnly && !centred(f->cx, f->cy)) return "cx, cy: its fisheye centres the image circle ((width − 1)/2, (height − 1)/2)";
    if (cyclesLimits && f->maxThetaRad < radians(5.0)) return "fov_deg: Cycles' fisheyes see at least 10 degrees";
    if (cyclesLimits && f->kind == FThetaLens::Kind::Equisolid && f->f * 36.0 / lens.width > 100.0)
      return "f_px: Cycles' equisolid lens is at most 100 mm on its 36 mm sensor (f_px at most " + shortNumber(100.0 / 36.0 * lens.width) + ")";
  } else if (const auto* e = std::get_if<Equirectangular>(&lens.model)) {
    if (centredOnly && (e->lonMinRad != -e->lonMaxRad || e->latMinRad != -e->latMaxRad))
      return "longitude_deg, latitude_deg: its panorama is symmetric about its direction ([−a, a]; turn the camera instead)";
  }
  return "";
}

bool hasLens(const EngineCapabilities& c, const std::string& model) {
  return c.everyLensModel || std::find(c.lensModels.begin(), c.lensModels.end(), model) != c.lensModels.end();
}

void checkLensCamera(const EngineCapabilities& c, const LensCameraSpec& lens) {
  const std::string model = lensModelName(lens.model);
  if (!hasLens(c, model))
    throw InputError(std::string("rig.lens.model: ") + c.shownName + " has no " + model + " camera; render it with " +
                     enginesThat(c, [&model](const EngineCapabilities& e) { return hasLens(e, model); }));
  // An engine without lens distortion traces its own cameras, which are not every lens of a model.
  const auto rendersThisLens = [&](const EngineCapabilities& e) {
    return hasLens(e, model) && (e.lensDistortion || lensProblem(lens, e.centredLensesOnly, e.cyclesLensLimits).empty());
  };
  if (!rendersThisLens(c))
    throw InputError("rig.lens." + lensProblem(lens, c.centredLensesOnly, c.cyclesLensLimits) + " (" + c.shownName +
                     "); render this lens with " + enginesThat(c, rendersThisLens));
}

void checkMirrorCamera(const EngineCapabilities& c, const MirrorRig& rig) {
  const std::string shown = c.shownName;
  if (!c.misalignedCamera && !rig.ideal())
    throw InputError(shown + " is central by construction and renders the ideal rig only (the hyperboloid with its camera "
                     "at F); this rig's mirror shape or camera (rig.mirror, rig.camera) differs: render it in exact mode");
  const MirrorShape shape = rig.shapeKind();
  if (!hasShape(c, shape))
    throw InputError(std::string("rig.mirror.shape: ") + shown + " has no exact " + mirrorShapeName(shape) +
                     " mirror; render it with " + enginesThat(c, [shape](const EngineCapabilities& e) { return hasShape(e, shape); }));
  if (!c.lensDistortion && !rig.mount.distortion.none())
    throw InputError("rig.camera.distortion: " + shown + " has no lens distortion; render it with " +
                     enginesThat(c, [](const EngineCapabilities& e) { return e.lensDistortion; }));
}

void checkCamera(const EngineCapabilities& c, const RigSpec& rig) {
  std::visit(Overloaded{[&](const MirrorRig& mirror) { checkMirrorCamera(c, mirror); },
                        [&](const LensCameraSpec& lens) { checkLensCamera(c, lens); }},
             rig.kind);
}

void checkMotion(const EngineCapabilities& c, const RigSpec& rig, const CameraPlacement& placement) {
  if (!moving(placement, rig)) return;
  const std::string shown = c.shownName, why = c.why.empty() ? "" : " (" + c.why + ")";
  if (!c.motion)
    throw InputError(shown + " renders still frames only (a robot with a velocity, seen through an open rig.shutter, moves): "
                     "render the robot still, or render it with " + enginesThat(c, [](const EngineCapabilities& e) { return e.motion; }) +
                     " (docs/motion.md lists what each engine renders)");
  if (!c.rollingShutter && rig.shutter.rolling)
    throw InputError(shown + " renders motion blur through a global shutter only" + why + ": render a rolling shutter with " +
                     enginesThat(c, [](const EngineCapabilities& e) { return e.rollingShutter; }) + " (docs/motion.md)");
  if (!c.timeSamples && rig.shutter.timeSamples > 0)
    throw InputError(shown + " has no fixed time instants" + why + ": rig.shutter.time_samples needs " +
                     enginesThat(c, [](const EngineCapabilities& e) { return e.timeSamples; }) + " (docs/motion.md)");
}

}  // namespace

const EngineCapabilities& capabilitiesOf(EngineKind engine) {
  static const EngineCapabilities rows[] = {fastExact(),
                                            fastCentral(EngineKind::FastCubeMap, OmniMode::CubeMap, "the fast engine's cube-map mode"),
                                            fastCentral(EngineKind::FastThesisMesh, OmniMode::ThesisMesh, "the fast engine's thesis-mesh mode"),
                                            povray(), blender()};
  return rows[static_cast<int>(engine)];
}

EngineKind fastEngineKind(OmniMode mode) { return *engineKindNamed("fast", mode); }

std::optional<EngineKind> engineKindNamed(const std::string& engine, OmniMode mode) {
  for (EngineKind kind : {EngineKind::FastExact, EngineKind::FastCubeMap, EngineKind::FastThesisMesh, EngineKind::Povray, EngineKind::Blender})
    if (capabilitiesOf(kind).engine == engine && capabilitiesOf(kind).mode == mode) return kind;
  return std::nullopt;
}

std::string engineChoices() {
  std::vector<std::string> names;
  for (EngineKind e : kChoices) names.push_back(capabilitiesOf(e).engine);
  return listWithOr(names);
}

void checkEngineRenders(EngineKind engine, const RigSpec& rig, const CameraPlacement& placement, bool aovs) {
  const EngineCapabilities& c = capabilitiesOf(engine);
  checkCamera(c, rig);
  checkMotion(c, rig, placement);
  if (aovs && !c.aovs)
    throw InputError(std::string(c.shownName) + " renders colour only; per-pixel ground truth (depth, instances, normals) needs " +
                     enginesThat(c, [](const EngineCapabilities& e) { return e.aovs; }));
}

void checkEngineShading(EngineKind engine, Shading shading, const std::string& shadingField) {
  const EngineCapabilities& c = capabilitiesOf(engine);
  if (shading == Shading::Path && !c.pathShading)
    throw InputError(shadingField + " path: " + c.shownName + " has no physically based light; render it with " +
                     enginesThat(c, [](const EngineCapabilities& e) { return e.pathShading; }));
}

}  // namespace omnicam
