#include "calibration_study.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <mutex>

#include "atomic_file.h"
#include "board_poses.h"
#include "calibration_sequence.h"
#include "ekf_drive.h"
#include "errors.h"
#include "experiment_folder.h"
#include "fast_renderer.h"
#include "imaged_corners.h"
#include "landmark_geometry.h"
#include "make_camera.h"
#include "placement.h"
#include "plot_script.h"
#include "render_request.h"
#include "safe_files.h"
#include "scene_loader.h"
#include "target_detection.h"

namespace omnicam {

namespace fs = std::filesystem;
using nlohmann::json;

CalibrationStudyOptions CalibrationStudyOptions::quick() {
  CalibrationStudyOptions o;
  o.size = 720;
  o.views = 12;
  o.offsetsMm = {2.0};
  o.tiltsDeg = {};
  o.distortedLens = false;
  o.seeds = 1;
  o.reduced = true;
  return o;
}

RigSpec Misalignment::rig(const RigSpec& nominal, const LensDistortion& lens) const {
  RigSpec r = nominal;
  if (kind == "lateral") r.mirrorRig().mount.offsetMm[0] = amount;
  if (kind == "axial") r.mirrorRig().mount.offsetMm[2] = amount;
  if (kind == "tilt") r.mirrorRig().mount.rotationDeg[0] = amount;
  if (distorted) r.mirrorRig().mount.distortion = lens;
  return r;
}

std::string Misalignment::label() const {
  char text[64];
  if (kind == "ideal") std::snprintf(text, sizeof text, "ideal");
  else std::snprintf(text, sizeof text, "%s %g %s", kind.c_str(), amount, kind == "tilt" ? "deg" : "mm");
  return std::string(text) + (distorted ? ", lens" : "");
}

namespace {

// Each source as results.json names it and as the report titles it, in the enum's order.
struct CornerSourceRow {
  const char* name;
  const char* title;
};
constexpr CornerSourceRow kCornerSourceRows[] = {
    {"exact", "exact corners"}, {"detected", "detected, clean"}, {"detected_noisy", "detected, recorded"}};

}  // namespace

const char* cornerSourceName(CornerSource source) { return kCornerSourceRows[static_cast<size_t>(source)].name; }
const char* cornerSourceTitle(CornerSource source) { return kCornerSourceRows[static_cast<size_t>(source)].title; }

namespace {

constexpr CornerSource kSources[] = {CornerSource::Exact, CornerSource::Detected, CornerSource::DetectedNoisy};
// The board waved in front of the camera: Kalibr's 6 × 6 AprilGrid of 88 mm tags (0.75 m wide),
// its centre 0.3–1.0 m from F', tilted up to 40°, at least 24 corners seen.
const AprilGrid kGrid{6, 6, 0.088, 0.3, 0};
constexpr int kMinSeenCorners = 24;
// A calibration with a larger training RMS is one a user would throw away: counted as failed.
constexpr double kMaxUsableRmsPx = 2.0;
// Triangulated points whose two true rays meet at less than this are ill-conditioned (points
// almost along the baseline) and left out.
constexpr double kMinTriangulationAngleRad = 5.0 * kPi / 180.0;

// The room the board is waved in: a floor and a grey backdrop far away (the background), the
// board (moved to each pose) on it.
std::string roomSceneText() {
  return R"({"format": "omnicam-scene/1", "name": "calibration study room", "background": [0.5, 0.5, 0.5],
  "materials": {"floor": {"color": [0.35, 0.33, 0.3]}},
  "objects": [
    {"name": "floor", "type": "quad", "material": "floor", "origin": [-5, -5, 0], "edge_u": [10, 0, 0], "edge_v": [0, 10, 0]},
    {"name": "grid", "type": "calibration_target", "origin": [1, 0, 0.5], "x_axis": [0, 1, 0], "y_axis": [0, 0, 1],
     "pattern": {"kind": "aprilgrid", "tag_rows": 6, "tag_columns": 6, "tag_size": 0.088, "tag_spacing": 0.3}}]}
)";
}

std::vector<Misalignment> sweep(const CalibrationStudyOptions& o) {
  std::vector<Misalignment> out;
  for (bool distorted : {false, true}) {
    if (distorted && !o.distortedLens) break;
    out.push_back({"ideal", 0.0, distorted});
    for (double mm : o.offsetsMm) out.push_back({"lateral", mm, distorted});
    for (double mm : o.offsetsMm) out.push_back({"axial", mm, distorted});
    for (double deg : o.tiltsDeg) out.push_back({"tilt", deg, distorted});
  }
  return out;
}

// One seed's board poses with each source's corners.
struct SeedViews {
  std::vector<Rigid> viewpointFromTarget;
  std::vector<std::vector<CalibrationView>> bySource;  // [source][view]; a view may be empty
};

SeedViews seedViews(const CalibrationStudyOptions& o, const Scene& room, const RigSpec& rig, const Camera& camera, int seed) {
  BoardPoseOptions poses;
  poses.count = o.views;
  poses.seed = static_cast<uint64_t>(seed);
  poses.minSeenCorners = kMinSeenCorners;
  poses.floorZ = -rig.height;  // the room's floor, in the viewpoint frame the poses are drawn in
  const Rigid worldFromViewpoint = CameraPlacement(RobotPose{}).worldFromViewpoint(rig);
  SeedViews out;
  out.viewpointFromTarget = boardPoses(camera, Rigid::Identity(), kGrid, poses);
  out.bySource.assign(3, std::vector<CalibrationView>(out.viewpointFromTarget.size()));
  const std::vector<Vec3> points = targetCorners(kGrid);
  const RenderSettings settings = requestedSettings(rig, {{RequestField::Spp, int64_t{o.spp}}});
  for (size_t v = 0; v < out.viewpointFromTarget.size(); ++v) {
    Scene scene = room;
    placeCalibrationTarget(scene, 0, worldFromViewpoint * out.viewpointFromTarget[v]);
    const FastRenderer renderer(scene);
    // Exact corners as the render shows them: seen, in the room (the floor may hide some).
    std::vector<DetectedCorner> exact;
    for (const ImagedCorner& c : imagedCorners(camera, worldFromViewpoint, &renderer.rays(), scene.calibrationTargets[0]))
      if (c.sight == CornerSight::Seen) exact.push_back({c.index, c.raster});
    out.bySource[0][v] = calibrationView(points, exact);
    const ImageRGBA image = renderer.render(RobotPose{}, settings);
    out.bySource[1][v] = calibrationView(points, detectAprilGrid(image, kGrid, ImageHandedness::Mirrored));
    const ImageRGBA recorded = recordFrame(o.recording, image, static_cast<uint64_t>(seed) * 1000 + v);
    out.bySource[2][v] = calibrationView(points, detectAprilGrid(recorded, kGrid, ImageHandedness::Mirrored));
  }
  return out;
}

CalibrationRun calibrate(const CalibrationStudyOptions& o, const Camera& camera, const PixelRays& rays, const SeedViews& seed,
                         CornerSource source, int seedNumber) {
  CalibrationRun run;
  run.source = source;
  run.seed = seedNumber;
  std::vector<CalibrationView> views;
  std::vector<Rigid> poses;
  const std::vector<CalibrationView>& all = seed.bySource[static_cast<size_t>(source)];
  for (size_t v = 0; v < all.size(); ++v)
    if (all[v].raster.size() >= 4) {
      views.push_back(all[v]);
      poses.push_back(seed.viewpointFromTarget[v]);
      run.corners += static_cast<int>(all[v].raster.size());
    }
  run.views = static_cast<int>(views.size());
  if (views.size() < 3) {
    run.fit.failure = "fewer than 3 views with corners";
    return run;
  }
  run.fit = calibrateOmnidir(views, camera.width(), camera.height(), OmnidirOptions{});
  if (!run.fit.converged) return run;
  // OpenCV reports convergence for fits that went astray (few or badly spread corners): a user
  // would reject them by their RMS.
  if (!(run.fit.rms <= kMaxUsableRmsPx)) {
    run.fit.converged = false;
    run.diverged = true;
    run.fit.failure = "diverged (RMS " + std::to_string(run.fit.rms) + " px)";
    return run;
  }
  run.model = calibratedModel(run.fit, poses);
  for (double d : o.heldOutDistancesM) run.heldOut.push_back(heldOutError(rays, *run.model, d));
  run.triangulation = triangulationError(camera, *run.model, o.triangulationDistanceM, o.triangulationBaselineM);
  return run;
}

// The measurements along thesis-loop of every beacon the rig images, by each model of its rays.
struct LoopMeasurements {
  std::vector<std::vector<Measurement>> trueRays, nominal, calibrated, calibratedExact;
  int count = 0;
};

LoopMeasurements loopMeasurements(const Scene& field, const std::vector<RobotPose>& loop, const RigSpec& rig, const Camera& camera,
                                  const CentralApproximation* calibrated, const CentralApproximation* calibratedExact) {
  RigSpec nominalRig = rig;
  nominalRig.mirrorRig().mount = CameraMount{};  // the rig as designed: what the thesis assumed
  LoopMeasurements m;
  for (auto* list : {&m.trueRays, &m.nominal, &m.calibrated, &m.calibratedExact}) list->resize(loop.size());
  for (size_t k = 0; k < loop.size(); ++k) {
    const Rigid viewpointFromWorld = CameraPlacement(loop[k]).worldFromViewpoint(rig).inverse();
    for (const Landmark& l : field.landmarks) {
      const Vec3 p = viewpointFromWorld * l.position;
      const std::optional<Vec2> raster = camera.project(p);
      if (!raster || !camera.images(*raster)) continue;
      const Vec2 landmark = l.position.head<2>();
      const auto add = [&](std::vector<std::vector<Measurement>>& list, const std::optional<RangeBearing>& z) {
        if (z) list[k].push_back({landmark, *z});
      };
      if (const std::optional<CameraRay> ray = camera.generateRay({*raster})) add(m.trueRays, rangeBearingAlong(ray->origin, ray->direction, p.z()));
      add(m.nominal, rangeBearingFromRaster(nominalRig, *raster, l.position.z()));
      for (auto [model, list] : {std::pair{calibrated, &m.calibrated}, std::pair{calibratedExact, &m.calibratedExact}})
        if (model)
          if (const auto d = model->direction(*raster)) add(*list, rangeBearingAlong(model->viewpoint, *d, p.z()));
      ++m.count;
    }
  }
  return m;
}

EkfComparison compareEkf(const Scene& field, const std::vector<RobotPose>& loop, const Drive& drive, const RigSpec& rig,
                         const Camera& camera, const std::vector<CalibrationRun>& runs) {
  // Seed 1's calibrations, placed by their own extrinsics.
  const auto modelOf = [&](CornerSource source) -> const CentralApproximation* {
    for (const CalibrationRun& run : runs)
      if (run.seed == 1 && run.source == source && run.model) return &*run.model;
    return nullptr;
  };
  const CentralApproximation* noisy = modelOf(CornerSource::DetectedNoisy);
  const CentralApproximation* exact = modelOf(CornerSource::Exact);
  const LoopMeasurements m = loopMeasurements(field, loop, rig, camera, noisy, exact);
  const auto ekfError = [&](const std::vector<std::vector<Measurement>>& list) {
    return runEkf(drive, [&](size_t k) { return &list[k]; }).meanErrorCm();
  };
  EkfComparison e;
  e.measurements = m.count;
  e.odometryCm = runEkf(drive, [](size_t) { return nullptr; }).meanOdometryErrorCm();
  e.trueRaysCm = ekfError(m.trueRays);
  const EkfTrace nominalTrace = runEkf(drive, [&](size_t k) { return &m.nominal[k]; });
  e.nominalCm = nominalTrace.meanErrorCm();
  e.nominalUsedShare = nominalTrace.used + nominalTrace.gated > 0
                           ? static_cast<double>(nominalTrace.used) / (nominalTrace.used + nominalTrace.gated)
                           : 0.0;
  // No calibration, no calibrated localisation (NaN: "—" in the report).
  e.calibratedCm = noisy ? ekfError(m.calibrated) : std::nan("");
  e.calibratedExactCm = exact ? ekfError(m.calibratedExact) : std::nan("");
  return e;
}

// A residual map (px at 0.5 m) as little-endian float32 rows, NaN where nothing is imaged.
void writeResidualMap(const fs::path& file, const std::vector<float>& map) {
  writeTextAtomically(file.string(), std::string(reinterpret_cast<const char*>(map.data()), map.size() * sizeof(float)));
}

// A label as a file name part: letters and digits, runs of anything else one '_'.
std::string slug(const std::string& label) {
  std::string s;
  for (char c : label) {
    if (std::isalnum(static_cast<unsigned char>(c))) s += c;
    else if (!s.empty() && s.back() != '_') s += '_';
  }
  while (!s.empty() && s.back() == '_') s.pop_back();
  return s;
}

// The rigs whose residual maps the report shows.
bool mapped(const Misalignment& m) {
  return !m.distorted && (m.kind == "ideal" || (m.kind == "lateral" && m.amount == 2.0) || (m.kind == "axial" && m.amount == 2.0) ||
                          (m.kind == "tilt" && m.amount == 1.0));
}

}  // namespace

// Points `distance` from F' on the true rays of a pixel grid, seen again after the robot drove
// `baseline` forward: each triangulated from the two rays the calibrated model gives their
// pixels (midpoint of the closest points), against the truth.
TriangulationError triangulationError(const Camera& camera, const CentralApproximation& model, double distance, double baseline) {
  const Vec3 moved(baseline, 0.0, 0.0);
  const int stride = std::max(1, camera.width() / 48);
  std::vector<double> errors;
  for (int j = stride / 2; j < camera.height(); j += stride)
    for (int i = stride / 2; i < camera.width(); i += stride) {
      const Vec2 a(i + 0.5, j + 0.5);
      const std::optional<CameraRay> ray = camera.generateRay({a});
      if (!ray) continue;
      const Vec3 point = pointAtDistance(*ray, Vec3::Zero(), distance);
      const std::optional<Vec2> b = camera.project(point - moved);
      if (!b || !camera.images(*b)) continue;
      if ((point.normalized()).dot((point - moved).normalized()) > std::cos(kMinTriangulationAngleRad)) continue;
      const std::optional<Vec3> da = model.direction(a), db = model.direction(*b);
      if (!da || !db) continue;
      const Vec3 oa = model.viewpoint, ob = model.viewpoint + moved;
      // Closest points of oa + s·da and ob + t·db.
      const Vec3 w = oa - ob;
      const double aa = da->dot(*da), ab = da->dot(*db), bb = db->dot(*db), aw = da->dot(w), bw = db->dot(w);
      const double denominator = aa * bb - ab * ab;
      if (!(denominator > 1e-12)) continue;
      const double s = (ab * bw - bb * aw) / denominator, t = (aa * bw - ab * aw) / denominator;
      const Vec3 midpoint = 0.5 * ((oa + s * *da) + (ob + t * *db));
      errors.push_back(1e3 * (midpoint - point).norm());
    }
  TriangulationError out;
  out.points = static_cast<int>(errors.size());
  if (errors.empty()) return out;
  std::sort(errors.begin(), errors.end());
  out.medianMm = errors[errors.size() / 2];
  out.p90Mm = errors[static_cast<size_t>(0.9 * static_cast<double>(errors.size() - 1))];
  return out;
}

CalibrationStudyResults runCalibrationStudy(const CalibrationStudyOptions& o, const std::string& plotScript,
                                            const ExperimentProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path out(o.outDir);
  makeRunFolders(o.outDir, {"arenas", "data"}, !plotScript.empty());
  writeTextAtomically((out / "arenas/calibration-room.json").string(), roomSceneText());
  const Scene room = loadScene((out / "arenas/calibration-room.json").string());
  const Scene field = loadScene(o.fieldScene);
  const CameraPath* loopPath = field.findPath("thesis-loop");
  if (!loopPath) throw InputError(showPath(o.fieldScene) + ": paths: no \"thesis-loop\"");
  const Drive drive = makeDrive(loopPath->poses, 7);
  RigSpec nominal = room.rig;
  nominal.mirrorRig().imageSize = o.size;

  CalibrationStudyResults results;
  results.width = o.size;
  const std::vector<Misalignment> rigs = sweep(o);
  results.rigs.resize(rigs.size());
  // Each rig's seeds are calibrated, then its EKF drives: both counted, so that the rate and the
  // time left cover the study's work, not its calibrations alone.
  const int total = static_cast<int>(rigs.size()) * (o.seeds + 1);
  std::atomic<int> done{0};
  std::mutex progressMutex;
  const auto stepDone = [&] {
    const int now = ++done;
    const std::lock_guard<std::mutex> lock(progressMutex);
    if (progress) progress("calibrations and EKF drives", now, total);
  };
  tbb::parallel_for(size_t{0}, rigs.size(), [&](size_t r) {
    RigOutcome& outcome = results.rigs[r];
    outcome.misalignment = rigs[r];
    const RigSpec rig = rigs[r].rig(nominal, o.typicalLens);
    const std::shared_ptr<const Camera> camera = makeCamera(rig);
    const CentralApproximation best = fitCentralApproximation(*camera);
    outcome.truth = best.intrinsics;
    // Every pixel's true ray, traced once for every model's held-out error on this rig.
    const PixelRays rays = pixelRays(*camera);
    for (double d : o.heldOutDistancesM) outcome.bestFitHeldOut.push_back(heldOutError(rays, best, d));
    std::vector<SeedViews> seeds(static_cast<size_t>(o.seeds));
    std::vector<std::vector<CalibrationRun>> runs(seeds.size());
    tbb::parallel_for(size_t{0}, seeds.size(), [&](size_t s) {
      const int seed = static_cast<int>(s) + 1;
      seeds[s] = seedViews(o, room, rig, *camera, seed);
      for (CornerSource source : kSources) runs[s].push_back(calibrate(o, *camera, rays, seeds[s], source, seed));
      stepDone();
    });
    for (auto& list : runs) outcome.runs.insert(outcome.runs.end(), list.begin(), list.end());
    outcome.ekf = compareEkf(field, loopPath->poses, drive, rig, *camera, outcome.runs);
    stepDone();
    if (mapped(rigs[r]))
      for (const CalibrationRun& run : outcome.runs)
        if (run.seed == 1 && run.model && run.source != CornerSource::Detected)
          writeResidualMap(out / ("data/residual_" + slug(rigs[r].label()) + "_" + cornerSourceName(run.source) + ".f32"),
                           centralResidualMap(rays, *run.model, 0.5));
  });
  results.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writeTextAtomically((out / "results.json").string(), calibrationStudyJson(results, o).dump(1) + "\n");
  if (!plotScript.empty()) runPlotScript(plotScript, o.outDir);
  return results;
}

namespace {

json heldOutJson(const std::vector<HeldOutError>& list) {
  json a = json::array();
  for (const HeldOutError& h : list)
    a.push_back({{"distance_m", h.distanceM}, {"median_px", h.medianPx}, {"rms_px", h.rmsPx}, {"max_px", h.maxPx},
                 {"median_mrad", h.medianMrad}, {"rms_mrad", h.rmsMrad}, {"unmodelled_share", h.unmodelledShare}});
  return a;
}

json intrinsicsJson(double xi, double gx, double gy, double cx, double cy, const std::array<double, 4>& d) {
  return {{"xi", xi}, {"gamma_x", gx}, {"gamma_y", gy}, {"cx", cx}, {"cy", cy}, {"k1", d[0]}, {"k2", d[1]}, {"p1", d[2]}, {"p2", d[3]}};
}

}  // namespace

json calibrationStudyJson(const CalibrationStudyResults& r, const CalibrationStudyOptions& o) {
  json rigs = json::array();
  for (const RigOutcome& rig : r.rigs) {
    json runs = json::array();
    for (const CalibrationRun& run : rig.runs) {
      json j = {{"source", cornerSourceName(run.source)}, {"seed", run.seed}, {"views", run.views}, {"corners", run.corners},
                {"converged", run.fit.converged}, {"diverged", run.diverged}};
      if (!run.fit.converged) {
        j["failure"] = run.fit.failure;
      } else {
        j["rms_px"] = run.fit.rms;
        j["used_views"] = run.fit.usedViews.size();
        j["intrinsics"] = intrinsicsJson(run.fit.xi, run.fit.gammaX, run.fit.gammaY, run.fit.cx, run.fit.cy, run.fit.distortion);
        j["held_out"] = heldOutJson(run.heldOut);
        j["triangulation"] = {{"median_mm", run.triangulation.medianMm}, {"p90_mm", run.triangulation.p90Mm},
                              {"points", run.triangulation.points}};
      }
      runs.push_back(j);
    }
    const MeiIntrinsics& t = rig.truth;
    rigs.push_back({{"kind", rig.misalignment.kind},
                    {"amount", rig.misalignment.amount},
                    {"lens", rig.misalignment.distorted},
                    {"label", rig.misalignment.label()},
                    {"slug", slug(rig.misalignment.label())},
                    {"truth", intrinsicsJson(t.xi, t.gammaX, t.gammaY, t.cx, t.cy, {t.lens.k1, t.lens.k2, t.lens.p1, t.lens.p2})},
                    {"best_fit_held_out", heldOutJson(rig.bestFitHeldOut)},
                    {"runs", runs},
                    {"ekf_cm", {{"odometry", rig.ekf.odometryCm}, {"true_rays", rig.ekf.trueRaysCm}, {"nominal", rig.ekf.nominalCm}, {"nominal_used_share", rig.ekf.nominalUsedShare},
                                {"calibrated_noisy", rig.ekf.calibratedCm}, {"calibrated_exact", rig.ekf.calibratedExactCm},
                                {"measurements", rig.ekf.measurements}}}});
  }
  return {{"study", kCalibrationStudy},
          {"image_size", o.size},
          {"spp", o.spp},
          {"views", o.views},
          {"seeds", o.seeds},
          {"target", "Kalibr AprilGrid 6 x 6, tag 0.088 m, spacing 0.3"},
          {"held_out_distances_m", o.heldOutDistancesM},
          {"triangulation", {{"distance_m", o.triangulationDistanceM}, {"baseline_m", o.triangulationBaselineM}}},
          {"seconds", r.seconds},
          {"rigs", rigs}};
}

}  // namespace omnicam
