// omnicam demo [-o out/demo] [--spp N] [--no-povray] [--no-blender]: the main job. Opens with a
// frame that fills the mirror (the field inside the thesis' hall, walls carrying a real photo) from
// the fast renderer beside POV-Ray's ground truth and their agreement; then renders robocup2006 at
// the thesis start pose (unlit and lit) with the fast renderer, POV-Ray (the physical camera and
// the exact mirror) and Blender, compares them, renders and measures the incidence-angle rings
// with every engine, shows a misaligned physical camera against the ideal one (with POV-Ray's
// truth and the best-fit central model's residual), shows physically based light (the fast path
// tracer's dataset frame beside Cycles' converged frame of the textured hall), renders a small
// two-camera dataset (depth, instance and landmark overlays), and writes PNGs, plots and index.html.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <sstream>

#include "aov_preview.h"
#include "atomic_file.h"
#include "central_fit.h"
#include "cli_util.h"
#include "commands.h"
#include "cubemap_renderer.h"
#include "dataset_runner.h"
#include "demo_lenses.h"
#include "demo_sections.h"
#include "demo_motion.h"
#include "texture_realism.h"
#include "hall_arena.h"
#include "image_compare.h"
#include "markup.h"
#include "number_format.h"
#include "physical_camera.h"
#include "render_noise.h"
#include "render_output.h"
#include "rings.h"
#include "scene_loader.h"
#include "svg_plot.h"
#include "views.h"

namespace omnicam::cli {

namespace {

struct DemoArgs {
  std::string out = "out/demo";
  int spp = 16;
  bool povray = true, blender = true;
  double budgetScale = 1.0;
  std::vector<std::string> only;  // --sections: run these, leave the others out
  std::string section;  // a child renders this one section (demo_sections.h)
};

struct EngineRings {
  std::string engine;
  RingReport report;
};

const char* kColours[] = {"#2ca02c", "#9467bd", "#ff7f0e"};  // fast, povray, blender

std::string format(const char* fmt, double a, double b = 0, double c = 0, double d = 0) {
  char buf[512];
  std::snprintf(buf, sizeof buf, fmt, a, b, c, d);
  return buf;
}

void writeRingPlots(const std::string& out, const OmniCamera& camera, const std::vector<EngineRings>& rings) {
  const double h = rings.front().report.hPx;
  PlotSpec radii{"Incidence-angle circle radii (thesis Fig. 3.12)", "incidence angle θ (degrees)", "radius r (pixels)",
                 640, 400, {}};
  PlotSpec residuals{"Difference from the exact model", "incidence angle θ (degrees)", "r − r_exact (pixels)", 640, 300,
                     {}};
  PlotSeries exact{"exact model (docs/conventions.md §1)", "#1f77b4", {}, {}, false};
  PlotSeries eq32{"thesis Eq. 3.2 with measured h", "#d62728", {}, {}, false};
  PlotSeries eq32Residual = eq32;
  for (int deg = 0; deg <= 135; ++deg) {
    const double t = radians(deg), e = camera.radiusOfTheta(t), q = h * std::sin(t) / (1.0 + std::cos(t));
    exact.x.push_back(deg), exact.y.push_back(e);
    eq32.x.push_back(deg), eq32.y.push_back(q);
    eq32Residual.x.push_back(deg), eq32Residual.y.push_back(q - e);
  }
  radii.series = {exact, eq32};
  residuals.series = {{"exact model", "#1f77b4", {0, 135}, {0, 0}, false}, eq32Residual};
  for (size_t k = 0; k < rings.size(); ++k) {
    PlotSeries measured{"measured, " + rings[k].engine, kColours[k % 3], {}, {}, true}, residual = measured;
    for (const auto& m : rings[k].report.rings) {
      measured.x.push_back(m.thetaDeg), measured.y.push_back(m.measuredPx);
      residual.x.push_back(m.thetaDeg), residual.y.push_back(m.measuredPx - m.exactPx);
    }
    radii.series.push_back(measured);
    residuals.series.push_back(residual);
  }
  writeTextAtomically(out + "/rings_plot.svg", svgPlot(radii));
  writeTextAtomically(out + "/rings_residuals.svg", svgPlot(residuals));
}

struct EngineFigures {
  std::string html;                                          // the renders' figures, then the differences'
  std::vector<std::pair<std::string, CompareResult>> vsFast;  // engine, fast vs engine
  double fastSeconds = 0.0;
};

// Renders `scene` at `pose` with every engine (engines[0] is "fast"): `<stem>_<engine>.png`, then
// for each ground truth `<stem>_diff_<engine>.png` (|fast − engine|, white = 0.01) and its
// comparison with fast. `caveat(engine)`: HTML appended to that comparison's caption.
EngineFigures renderAndCompare(const std::string& out, const std::string& stem, const std::string& label,
                               const Scene& scene, const RobotPose& pose, const RenderSettings& settings,
                               const std::vector<std::string>& engines,
                               const std::function<std::string(const std::string&)>& caveat) {
  EngineFigures result;
  std::ostringstream html;
  std::vector<ImageRGBA> images;
  for (const auto& name : engines) {
    std::printf("demo: %s, %s, %d spp\n", label.c_str(), name.c_str(), settings.spp);
    auto engine = makeEngine(RenderRequest{name}, scene);
    const auto rendered = renderToFile(scene, *engine, pose, settings, out + "/" + stem + "_" + name + ".png");
    images.push_back(rendered.image);
    const double seconds = rendered.sidecar["seconds"].get<double>();
    if (images.size() == 1) result.fastSeconds = seconds;
    html << "<figure><img src=\"" << stem << "_" << name << ".png\" width=\"360\"><figcaption>" << name
         << format(" (%.2f s)", seconds) << "</figcaption></figure>\n";
  }
  for (size_t k = 1; k < images.size(); ++k) {
    const std::string& name = engines[k];
    const CompareResult r = compareImages(images[0], images[k]);
    const std::string diff = stem + "_diff_" + name + ".png";
    writeImageAtomic(out + "/" + diff, differenceHeatmap(images[0], images[k], 0.01));
    html << "<figure><img src=\"" << diff << "\" width=\"360\"><figcaption>|fast − " << name
         << "| (white = 0.01)<br>"
         << format("PSNR %.2f dB, RMSE %.2e, SSIM %.5f, max %.4f", r.psnrDb, r.rmse, r.ssim, r.maxAbs) << caveat(name)
         << "</figcaption></figure>\n";
    std::printf("demo: %s, fast vs %s: PSNR %.2f dB, SSIM %.5f\n", label.c_str(), name.c_str(), r.psnrDb, r.ssim);
    result.vsFast.emplace_back(name, r);
  }
  result.html = html.str();
  return result;
}


// What the report opens with: a frame that fills the mirror — the field inside the thesis' hall,
// walls carrying the real photo — from the fast renderer beside POV-Ray's ground truth. The pose
// sees both goals, the centre circle and the beacons.
const RobotPose kGlancePose{0.0, -0.7, 90.0};

std::string hallScenePath(const std::string& out) { return out + "/hall/hall-textured.json"; }

// The textured hall that the glance, light and texture-realism sections share, written once
// before any section runs.
void writeDemoHall(const std::string& out, const std::string& fieldScene) {
  HallOptions hall;
  hall.fieldScene = fieldScene;
  hall.photos = {kLabPhoto};
  std::filesystem::create_directories(out + "/hall");
  writeHallArena(hall, hallScenePath(out));
}

EngineFigures renderGlance(const std::string& out, const DemoArgs& a) {
  const Scene scene = loadScene(hallScenePath(out));
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.spp = a.spp;
  settings.shading = Shading::Lit;
  std::vector<std::string> engines{"fast"};
  if (a.povray) engines.push_back("povray");  // the exact ground truth; Blender lit is not a pixel comparison
  return renderAndCompare(out, "glance", "at a glance: robocup2006 in the textured hall, lit", scene, kGlancePose,
                          settings, engines, [](const std::string&) { return std::string(); });
}

// Each engine's ring RMS against the exact model, as the start-pose section measured them.
struct RingSummary {
  std::string engine;
  double rmsPxExact = 0.0;
};

std::string glanceSection(const EngineFigures& glance, const std::vector<RingSummary>& rings, int spp) {
  std::ostringstream html;
  html << "<h2>At a glance</h2>\n<p>omnicam simulates a catadioptric omnidirectional camera — a camera looking up "
          "into a hyperbolic mirror, as on soccer and rescue robots — and proves its images right against ground "
          "truth. Here the RoboCup 2006 field inside the thesis' hall, its walls carrying a real 360&deg; photo "
          "(<code>omnicam arena hall --photo</code>), seen from "
       << format("(%.1f m, %.1f m, %.0f&deg;)", kGlancePose.x, kGlancePose.y, kGlancePose.yawDeg) << ", lit, " << spp
       << " samples per pixel. <b>fast</b>: omnicam's renderer, every ray straight from the closed-form model"
       << format(" (%.2f s)", glance.fastSeconds) << ". ";
  for (const auto& [engine, r] : glance.vsFast)
    html << "<b>" << engine << "</b>: the ground truth, a pinhole camera looking up into the exact mirror. They agree "
         << format("at <b>PSNR %.1f dB</b> (SSIM %.5f, largest difference %.4f of full scale)", r.psnrDb, r.ssim,
                   r.maxAbs)
         << ". ";
  if (glance.vsFast.empty()) html << "(No ground truth: <code>--no-povray</code>.) ";
  if (!rings.empty()) {
    html << "The incidence-angle rings below lie ";
    for (size_t k = 0; k < rings.size(); ++k)
      html << (k == 0 ? "" : k + 1 == rings.size() ? " and " : ", ") << format("<b>%.4f px</b>", rings[k].rmsPxExact)
           << " RMS (" << rings[k].engine << ")";
    html << " from the exact model.";
  }
  html << "</p>\n" << glance.html;
  return html.str();
}

// The texture-realism experiment in one frame: the hall with real-photo walls, beacons found by
// classifiers trained on the plain hall (docs/experiments.md).
std::string demoTexturedHall(const std::string& out, const std::string& scenePath) {
  std::printf("demo: textured hall, colour-histogram beacon detection\n");
  const DetectionFrame frame = texturedHallDetectionFrame(
      scenePath, kLabPhoto, out + "/hall", 360, 4, 8);
  writeImageAtomic(out + "/hall_detections.png", frame.drawn);
  std::printf("demo: textured hall frame %d: %d of %d visible beacons found, %d false positives\n", frame.poseIndex,
              frame.truePositives, frame.visibleBeacons, frame.falsePositives);
  std::ostringstream html;
  html << "<h2>Texture realism (<code>omnicam experiment texture-realism</code>)</h2><p>The field inside the "
          "thesis' hall, walls textured with a planar projection of a real 360&deg; photo (<code>omnicam arena "
          "hall --photo</code>). Colour-histogram classifiers trained on 8 frames of the <i>plain</i> hall (labels "
          "from instance masks) find "
       << frame.truePositives << " of " << frame.visibleBeacons << " visible beacons in thesis-loop frame "
       << frame.poseIndex << ", with " << frame.falsePositives
       << " false positives. Green crosses: projected beacons; yellow circles: correct detections; red: wrong.</p>"
          "<figure><img src=\"hall_detections.png\" width=\"360\"></figure>\n";
  return html.str();
}

// Cycles' reference of the light section, cheap enough for any machine: the same view at half the
// width (a quarter of the pixels), two seeds, and their mean as the reference; the pair's
// difference states the reference's own noise.
constexpr int kLightReferenceSize = 180;
constexpr int kLightReferenceSpp = 144;  // 12², as every spp

ImageRGBA meanOf(const ImageRGBA& a, const ImageRGBA& b) {
  ImageRGBA mean = a;
  for (size_t k = 0; k < mean.pixels.size(); ++k) mean.pixels[k] = 0.5f * (a.pixels[k] + b.pixels[k]);
  return mean;
}

// Physically based light: the fast renderer's path shading as a dataset renders it (denoised)
// beside Cycles' frame of the same textured hall, and the PSNR between them (docs/path-tracing.md
// measures nine such pairs against 1024-spp references).
std::string demoLight(const std::string& out, const std::string& scenePath, bool blender) {
  const Scene scene = loadScene(scenePath);
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.shading = Shading::Path;
  settings.spp = kPathDatasetSpp;
  settings.denoise = true;
  std::printf("demo: light, fast path shading, %d spp, denoised\n", settings.spp);
  auto fast = makeEngine(RenderRequest{"fast"}, scene);
  const RenderedFile fastFrame = renderToFile(scene, *fast, kGlancePose, settings, out + "/light_fast.png");
  std::ostringstream html;
  html << "<h2>Light: physically based at the fast renderer's speed (<code>--shading path</code>)</h2><p>The textured "
          "hall lit by its four lamps as luminaires of real size (discs of 50 cm), light bouncing off the walls, the "
          "floor and the ceiling (docs/path-tracing.md). <b>fast</b>: omnicam's path tracer as a dataset renders it, "
       << settings.spp << " samples per pixel, indirect light denoised"
       << format(" (%.2f s)", fastFrame.sidecar["seconds"].get<double>()) << ".";
  if (!blender) {
    html << " (Cycles' frame: not rendered, <code>--no-blender</code>.)</p><figure><img src=\"light_fast.png\" "
            "width=\"360\"><figcaption>fast, path</figcaption></figure>\n";
    return html.str();
  }
  RenderSettings small = settings;
  small.rig = settings.rig.resized(kLightReferenceSize);
  const ImageRGBA fastSmall = fast->render(kGlancePose, small);
  RenderSettings reference = small;
  reference.spp = kLightReferenceSpp;
  reference.denoise = false;
  auto cycles = makeEngine(RenderRequest{"blender"}, scene);
  std::vector<RenderedFile> seeds;
  for (uint64_t seed : {1, 2}) {
    reference.seed = seed;
    std::printf("demo: light, Blender Cycles, %d px, %d spp, seed %d\n", kLightReferenceSize, reference.spp,
                static_cast<int>(seed));
    seeds.push_back(renderToFile(scene, *cycles, kGlancePose, reference,
                                 out + "/light_cycles_seed" + std::to_string(seed) + ".png"));
  }
  const ImageRGBA cyclesMean = meanOf(seeds[0].image, seeds[1].image);
  writeImageAtomic(out + "/light_cycles.png", cyclesMean);
  const double pairPsnr = measureRenderNoise(seeds[0].image, seeds[1].image).psnrDb;
  // The mean of two independent frames carries half the variance of one: 3 dB above either.
  const double referenceNoisePsnr = psnrAgainstConvergedFromPair(pairPsnr) + 10.0 * std::log10(2.0);
  const double psnr = measureRenderNoise(fastSmall, cyclesMean).psnrDb;
  std::printf("demo: light, fast (%d spp, denoised) vs Cycles (2 x %d spp): %.2f dB; Cycles' own noise %.2f dB\n",
              settings.spp, reference.spp, psnr, referenceNoisePsnr);
  const double cyclesSeconds = seeds[0].sidecar["seconds"].get<double>() + seeds[1].sidecar["seconds"].get<double>();
  html << " <b>blender</b>: Cycles' frame of the same scene at " << kLightReferenceSize << "×" << kLightReferenceSize
       << " pixels, the mean of two seeds of " << reference.spp << " samples per pixel, unfiltered"
       << format(" (%.0f s in all)", cyclesSeconds)
       << format(". Between them, at that size: <b>PSNR %.1f dB</b> (8-bit sRGB inside the mirror). ", psnr)
       << format("The reference is not converged: its own noise, from the difference of its two seeds, is PSNR "
                 "%.1f dB against a converged frame, so part of the gap is Cycles' noise, not the fast "
                 "renderer's. ",
                 referenceNoisePsnr)
       << "docs/path-tracing.md compares such frames with 1024-spp references (38.6–39.4 dB); the demo keeps the "
          "reference small so that it finishes on a slow machine.</p>\n<figure><img src=\"light_fast.png\" "
          "width=\"360\"><figcaption>fast, path, "
       << settings.spp << " spp, denoised</figcaption></figure><figure><img src=\"light_cycles.png\" "
                          "width=\"360\"><figcaption>Cycles, mean of 2 × "
       << reference.spp << " spp, " << kLightReferenceSize << " px</figcaption></figure>\n";
  return html.str();
}

// The rig as built: the ideal camera beside one whose pinhole sits 2 mm off the mirror's focus and
// is turned by 1°, their difference, POV-Ray's ground truth of the misaligned rig, and the
// best-fit central model's residual map (docs/physical-camera.md).
std::string demoPhysicalCamera(const std::string& out, const Scene& arena, int spp, bool povray) {
  RenderSettings settings;
  settings.rig = arena.rig;
  settings.spp = spp;
  RenderSettings misaligned = settings;
  misaligned.rig.mount.offsetMm = {2.0, -1.0, 1.0};
  misaligned.rig.mount.rotationDeg = {1.0, -0.5, 0.5};
  std::printf("demo: physical camera, ideal vs 2 mm / 1 deg misaligned, %d spp\n", spp);
  const FastRenderer fast(arena);
  const ImageRGBA ideal = fast.render(arena.startPose, settings);
  const ImageRGBA moved = fast.render(arena.startPose, misaligned);
  writeImageAtomic(out + "/physical_ideal.png", ideal);
  writeImageAtomic(out + "/physical_misaligned.png", moved);
  writeImageAtomic(out + "/physical_difference.png", differenceHeatmap(ideal, moved, 0.5));
  const CompareResult change = compareImages(ideal, moved);
  std::ostringstream figures;
  figures << "<figure><img src=\"physical_ideal.png\" width=\"360\"><figcaption>ideal rig</figcaption></figure>\n"
          << "<figure><img src=\"physical_misaligned.png\" width=\"360\"><figcaption>pinhole moved (2, −1, 1) mm, "
             "turned (1, −0.5, 0.5)°</figcaption></figure>\n"
          << "<figure><img src=\"physical_difference.png\" width=\"360\"><figcaption>|ideal − misaligned| (white = 0.5)"
          << format("<br>PSNR %.2f dB: the misalignment is not a detail", change.psnrDb) << "</figcaption></figure>\n";
  if (povray) {
    std::printf("demo: physical camera, POV-Ray ground truth of the misaligned rig\n");
    auto engine = makeEngine(RenderRequest{"povray"}, arena);
    const auto truth = renderToFile(arena, *engine, arena.startPose, misaligned, out + "/physical_povray.png");
    const CompareResult r = compareImages(moved, truth.image);
    std::printf("demo: physical camera, fast vs POV-Ray: PSNR %.2f dB\n", r.psnrDb);
    figures << "<figure><img src=\"physical_povray.png\" width=\"360\"><figcaption>POV-Ray, the same physical pinhole"
            << format("<br>fast vs POV-Ray: PSNR %.2f dB, SSIM %.5f", r.psnrDb, r.ssim) << "</figcaption></figure>\n";
  }
  const PhysicalCamera camera(misaligned.rig);
  const CentralApproximation& fit = camera.centralApproximation();
  const std::vector<float> residual = centralResidualMap(camera, fit, 1.0);
  const double scale = std::max(1e-6, fit.residuals[3].maxPx);
  writeImageAtomic(out + "/physical_central_residual.png", scalarHeatmap(residual, camera.width(), camera.height(), scale));
  figures << "<figure><img src=\"physical_central_residual.png\" width=\"360\"><figcaption>best-fit central (Mei) "
             "model's reprojection error for points 1 m away"
          << format(" (white = %.2f px)", scale) << "</figcaption></figure>\n";
  std::ostringstream table;
  table << "<table><tr><th>points at</th><th>rms (px)</th><th>max (px)</th></tr>\n";
  for (const auto& r : fit.residuals)
    table << "<tr><td>" << (r.distanceM == 0.0 ? std::string("infinity") : roundTrip(r.distanceM) + " m") << "</td>"
          << format("<td>%.3f</td><td>%.3f</td></tr>\n", r.rmsPx, r.maxPx);
  table << "</table>\n";
  return "<h2>The physical camera (docs/physical-camera.md)</h2><p>No real catadioptric camera is the ideal one. "
         "Here the pinhole sits 2 mm off the mirror's focus and is turned by 1°: every pixel's ray now leaves the "
         "mirror from its own point, and omnicam traces it exactly (pixel → lens → pinhole ray → quadric → "
         "reflection); POV-Ray, tracing the same physical pinhole, is the ground truth. No central model describes "
         "this camera: the best-fit unified (Mei) model, which a calibration toolbox would recover, is off by the "
         "pixels below; every sidecar and dataset states it, and <code>omnicam camera-rays</code> writes the exact "
         "ray of every pixel.</p>\n" +
         figures.str() + table.str();
}

// A small dataset as a researcher would make one: two omnicams on the robot along the thesis'
// loop, every output; the report shows its depth, instances, classes and landmark annotations.
std::string demoDataset(const std::string& out, const std::string& scenePath) {
  namespace fs = std::filesystem;
  const std::string specPath = out + "/dataset_spec.json";
  const nlohmann::json spec = {
      {"format", "omnicam-dataset/1"},
      {"description", "omnicam demo: two cameras along the thesis loop"},
      {"scene", fs::absolute(scenePath).string()},
      {"spp", 4},
      {"shading", "lit"},
      {"size", 256},
      {"poses", {{"path", "thesis-loop"}, {"frames", 6}}},
      {"cameras", {{{"name", "front"}, {"mount", {{"x", 0.1}, {"y", 0.0}, {"yaw_deg", 0.0}}}},
                   {{"name", "rear"}, {"mount", {{"x", -0.1}, {"y", 0.0}, {"yaw_deg", 180.0}}},
                    {"rig", {{"height", 0.3}}}}}},
      {"outputs", {{"coco", true}}}};
  writeTextAtomically(specPath, spec.dump(2) + "\n");
  DatasetRunOptions options;
  options.dir = out + "/dataset";
  options.overwrite = true;  // the demo's own folder, remade each run
  std::printf("demo: dataset of 6 frames x 2 cameras (rgb, depth, instance, semantic, normal, landmarks, coco)\n");
  const DatasetRunResult result = runDataset(loadDatasetSpec(specPath), options);
  const DatasetVerifyResult verified = verifyDataset(options.dir);
  std::ostringstream html;
  html << "<h2>A reference dataset (<code>omnicam dataset</code>)</h2><p>" << result.frames
       << " frames × 2 cameras (front: F' 0.40 m high, 10 cm ahead of the robot's centre; rear: 0.30 m high, 10 cm behind, "
          "turned 180°) along the thesis loop, written to <code>dataset/</code> with <code>manifest.json</code> (every "
          "file's SHA-256: <code>omnicam dataset --verify</code> "
       << (verified.ok() ? "passes" : "FAILS") << " on " << verified.files
       << " files), OpenCV / Kalibr / camodocal intrinsics and <code>poses.tum</code> per camera. Spec: "
          "<code>dataset_spec.json</code>. Depth: metres along each pixel centre's ray from F' (yellow near, blue 6 m); "
          "instances and classes: one colour per id; landmarks: projected ground truth, green = visible, red = "
          "occluded (never labelled by hand); COCO: each camera's <code>coco.json</code> (the goals and beacons as "
          "masks in COCO's RLE and boxes, the landmarks as keypoints), drawn here from the file alone.</p>\n";
  const nlohmann::json frontCoco = readJsonFile(options.dir + "/front/coco.json");
  for (const std::string camera : {"front", "rear"}) {
    for (int frame : {0, 3}) {
      char stem[64];
      std::snprintf(stem, sizeof stem, "%s/%%s/%06d", camera.c_str(), frame);
      auto file = [&](const char* kind, const char* ext) {
        char path[160];
        std::snprintf(path, sizeof path, stem, kind);
        return options.dir + "/" + path + ext;
      };
      const std::string prefix = "dataset_" + camera + "_" + std::to_string(frame);
      int w = 0, h = 0;
      writeImageAtomic(out + "/" + prefix + "_depth.png", depthPreview(readDataExr(file("depth", ".exr")), 6.0));
      const std::vector<uint16_t> instance = readUint16Png(file("instance", ".png"), w, h);
      writeImageAtomic(out + "/" + prefix + "_instance.png", idPreview(instance, w, h));
      const std::vector<uint16_t> semantic = readUint16Png(file("semantic", ".png"), w, h);
      writeImageAtomic(out + "/" + prefix + "_semantic.png", idPreview(semantic, w, h));
      writeImageAtomic(out + "/" + prefix + "_landmarks.png",
                       drawLandmarkAnnotations(readImage(file("rgb", ".png")), readJsonFile(file("landmarks", ".json"))));
      const nlohmann::json coco = camera == "front" ? frontCoco : readJsonFile(options.dir + "/rear/coco.json");
      writeImageAtomic(out + "/" + prefix + "_coco.png", drawCocoAnnotations(readImage(file("rgb", ".png")), coco, frame + 1));
      html << "<div><b>" << camera << ", frame " << frame << "</b><br>";
      for (const char* kind : {"landmarks", "coco", "depth", "instance", "semantic"})
        html << "<figure style=\"max-width:260px\"><img src=\"" << prefix << "_" << kind << ".png\" width=\"256\"><figcaption>"
             << kind << "</figcaption></figure>";
      html << "</div>\n";
    }
  }
  return html.str();
}

// The open field from the thesis' start pose, unlit and lit, by every engine.
std::string openFieldSection(const DemoArgs& a, const Scene& arena, const std::vector<std::string>& engines) {
  std::ostringstream views;
  for (Shading shading : {Shading::Unlit, Shading::Lit}) {
    RenderSettings settings;
    settings.rig = arena.rig;
    settings.spp = a.spp;
    settings.shading = shading;
    const std::string s = shadingName(shading);
    views << "<h3>" << s << "</h3>\n"
          << renderAndCompare(a.out, "robocup2006_" + s, "robocup2006, thesis start pose, " + s, arena,
                              arena.startPose, settings, engines,
                              [&](const std::string& name) {
                                return name == "blender" && shading == Shading::Lit
                                           ? "<br>Blender lit is path traced (physical lights, indirect light): "
                                             "realism, not a pixel comparison (docs/conventions.md §2)"
                                           : "";
                              })
                 .html;
  }
  return views.str();
}

// The incidence-angle rings of every engine (thesis Figs. 3.11-3.12): images, reports, plots.
struct RingSection {
  std::vector<EngineRings> rings;
  std::string figures, summary, table;
};

RingSection ringSection(const DemoArgs& a, const Scene& ringScene, const std::vector<std::string>& engines) {
  RenderSettings ringSettings;
  ringSettings.rig = ringScene.rig;
  ringSettings.spp = a.spp;
  const OmniCamera ringCamera = ringSettings.rig.camera();
  RingSection out;
  std::ostringstream ringFigures, ringTable, ringSummary;
  for (const auto& name : engines) {
    std::printf("demo: incidence-angle rings, %s\n", name.c_str());
    auto engine = makeEngine(RenderRequest{name}, ringScene);
    const auto rendered = renderToFile(ringScene, *engine, ringScene.startPose, ringSettings,
                                       a.out + "/rings_" + name + ".png");
    out.rings.push_back({name, measureRings(rendered.image, ringCamera, defaultRingThetasDeg())});
    const RingReport& r = out.rings.back().report;
    writeTextAtomically(a.out + "/rings_" + name + ".json", ringReportToJson(r).dump(2) + "\n");
    ringFigures << "<figure><img src=\"rings_" << name << ".png\" width=\"360\"><figcaption>" << name
                << "</figcaption></figure>\n";
    ringSummary << "<li>" << name
                << format(": RMS against the exact model <b>%.4f px</b> (max %.4f px); Eq. 3.2 MSE <b>%.4f px²</b>; "
                          "h = %.4f px",
                          r.rmsPxExact, r.maxAbsPxExact, r.msePx2Eq32, r.hPx)
                << "</li>\n";
    std::printf("demo: rings %s: RMS %.4f px vs exact model, Eq. 3.2 MSE %.4f px^2\n", name.c_str(), r.rmsPxExact,
                r.msePx2Eq32);
  }
  writeRingPlots(a.out, ringCamera, out.rings);
  ringTable << "<tr><th>θ (°)</th><th>exact (px)</th><th>Eq. 3.2 (px)</th>";
  for (const auto& e : out.rings) ringTable << "<th>" << e.engine << " (px)</th><th>" << e.engine << " − exact</th>";
  ringTable << "</tr>\n";
  for (size_t k = 0; k < out.rings[0].report.rings.size(); ++k) {
    const auto& m = out.rings[0].report.rings[k];
    ringTable << format("<tr><td>%.0f</td><td>%.4f</td><td>%.4f</td>", m.thetaDeg, m.exactPx, m.eq32Px);
    for (const auto& e : out.rings)
      ringTable << format("<td>%.4f</td><td>%+.4f</td>", e.report.rings[k].measuredPx,
                          e.report.rings[k].measuredPx - e.report.rings[k].exactPx);
    ringTable << "</tr>\n";
  }
  out.figures = ringFigures.str(), out.summary = ringSummary.str(), out.table = ringTable.str();
  return out;
}

// The thesis' method (Fig. 3.4 with numbers) and the views of thesis §3.2.1.
struct MethodSection {
  std::string method, views;
};

MethodSection methodSection(const DemoArgs& a, const Scene& arena) {
  std::ostringstream method, viewFigures;
  RenderSettings settings;
  settings.rig = arena.rig;
  settings.spp = a.spp;
  const FastRenderer fast(arena);
  const CubeMapRenderer cube(fast);
  const ImageRGBA exact = fast.render(arena.startPose, settings);
  std::vector<std::pair<std::string, CubeMapOptions>> modes;
  for (int polygons : {16, 64, 256, 1024}) {
    CubeMapOptions o;
    o.mode = OmniMode::ThesisMesh;
    o.polygons = polygons;
    modes.emplace_back(std::to_string(polygons) + " polygons", o);
  }
  modes.emplace_back("cube map, 6 faces", CubeMapOptions{});
  for (size_t k = 0; k < modes.size(); ++k) {
    std::printf("demo: thesis method, %s\n", modes[k].first.c_str());
    const ImageRGBA image = cube.render(arena.startPose, settings, modes[k].second);
    const std::string file = "method_" + std::to_string(k) + ".png";
    writeImageAtomic(a.out + "/" + file, image);
    method << "<figure><img src=\"" << file << "\" width=\"270\"><figcaption>" << modes[k].first
           << format("<br>PSNR %.2f dB vs exact", compareImages(exact, image).psnrDb) << "</figcaption></figure>\n";
  }
  const OmniCamera camera = settings.rig.camera();
  for (const auto& [kind, variant, name] :
       std::vector<std::tuple<ViewKind, ViewVariant, std::string>>{{ViewKind::BirdsEye, ViewVariant::Exact, "birdseye_exact"},
                                                                   {ViewKind::BirdsEye, ViewVariant::Thesis, "birdseye_thesis"},
                                                                   {ViewKind::Panorama, ViewVariant::Exact, "panorama_exact"},
                                                                   {ViewKind::Panorama, ViewVariant::Thesis, "panorama_thesis"}}) {
    ViewSpec spec;
    spec.kind = kind;
    spec.variant = variant;
    writeImageAtomic(a.out + "/" + name + ".png", applyViewMap(buildViewMap(spec, camera), exact));
    viewFigures << "<figure style=\"max-width:" << (kind == ViewKind::Panorama ? 1100 : 420) << "px\"><img src=\""
                << name << ".png\"><figcaption>" << name << "</figcaption></figure>\n";
  }
  return {method.str(), viewFigures.str()};
}

// The sections in report order; a section's bit in the exit code is its place here. Costs are
// what each renders on an idle 2-core machine at 16 spp, by engine (measured 2026-11-28 with
// `omnicam demo`, `--no-blender` and `--no-povray --no-blender`; the whole demo took 54 s).
const std::vector<DemoSection>& demoSections() {
  static const std::vector<DemoSection> sections = {
      {"glance", "At a glance", 1.5, 2.0, 0.0, true},
      {"start-pose", "The thesis camera at its start pose: renders, rings, the thesis' method, views", 3.0, 8.5, 11.5, true},
      {"light", "Light: physically based at the fast renderer's speed", 2.0, 0.0, 15.0, false},
      {"physical", "The physical camera", 1.0, 1.6, 0.0, true},
      {"lenses", "Lens cameras", 2.0, 2.3, 2.2, true},
      {"robot", "Time in the camera, a reference dataset, texture realism", 2.0, 0.0, 0.0, true},
  };
  return sections;
}

// The start-pose section runs first: the glance cites its rings.
const std::vector<std::string> kRunOrder = {"start-pose", "glance", "light", "physical", "lenses", "robot"};

std::string ringSummaryPath(const DemoArgs& a) { return a.out + "/sections/start-pose-rings.json"; }

std::vector<RingSummary> readRingSummary(const DemoArgs& a) {
  std::vector<RingSummary> rings;
  if (!std::filesystem::is_regular_file(std::filesystem::symlink_status(ringSummaryPath(a)))) return rings;
  for (const auto& r : readJsonFile(ringSummaryPath(a))) rings.push_back({r.at("engine"), r.at("rms_px_exact")});
  return rings;
}

// The open field, the rings, the thesis' method and the views, from the thesis' start pose.
std::string startPoseHtml(const DemoArgs& a) {
  std::error_code ignored;
  std::filesystem::remove(ringSummaryPath(a), ignored);  // the glance cites only this run's rings
  const std::string dir = scenesDir();
  const Scene arena = loadScene(dir + "/robocup2006.json");
  const Scene ringScene = loadScene(dir + "/incidence-rings.json");
  std::vector<std::string> engines{"fast"};
  if (a.povray) engines.push_back("povray");
  if (a.blender) engines.push_back("blender");
  const std::string views = openFieldSection(a, arena, engines);
  const RingSection rings = ringSection(a, ringScene, engines);
  const MethodSection method = methodSection(a, arena);
  nlohmann::json summary = nlohmann::json::array();
  for (const auto& r : rings.rings) summary.push_back({{"engine", r.engine}, {"rms_px_exact", r.report.rmsPxExact}});
  writeTextAtomically(ringSummaryPath(a), summary.dump(1) + "\n");
  std::ostringstream html;
  html << R"(<h2>The open field from the thesis' start pose</h2>
<p>The RoboCup 2006 Four-Legged field seen by the simulated catadioptric camera (k = 11.546, c = 2.321 cm, rim 45°
above the horizon, 360×360) from the thesis start pose, )"
       << a.spp << R"( samples per pixel on a regular grid. <b>fast</b>: omnicam's renderer, every ray straight from the
closed-form model (no mirror). )" << (a.povray ? R"(<b>povray</b>: the ground truth — a pinhole camera looking up into the exact
hyperboloidal mirror (a quadric), traced by POV-Ray 3.7 at the same sample positions. )" : "")
       << (a.blender ? R"(<b>blender</b>: the second ground truth — Cycles (CPU, box filter, fixed seed, no denoising)
looking into a mirror mesh certified to deviate less than 0.5 µm from the quadric; it samples randomly inside each
pixel, so it converges with spp.)" : "")
       << "</p>\n" << views
       << R"(<h2>Incidence-angle rings (thesis Figs. 3.11–3.12)</h2><ul>)" << rings.summary
       << R"(</ul><p>docs/conventions.md §1: Eq. 3.2 against the exact model has MSE 0.256 px² — the thesis' "below one pixel".</p>
)" << rings.figures
       << R"(<figure style="max-width:660px"><img src="rings_plot.svg" width="640"><br><img src="rings_residuals.svg" width="640">
<figcaption>measured radii against the exact model and the thesis' Eq. 3.2</figcaption></figure>
<table>)" << rings.table
       << R"(</table>
<h2>The thesis' method: cube faces mapped onto a mirror mesh (thesis Fig. 3.4, measured)</h2>
<p>Texture coordinates interpolated linearly across each mirror polygon distort the image; the cube map with
per-pixel lookups does not. See <code>docs/thesis-reproduction.md</code> (<code>omnicam study</code>).</p>
)" << method.method
       << R"(<h2>Views (thesis §3.2.1): bird's-eye (Eqs. 3.3–3.5) and panorama (Eqs. 3.6–3.7)</h2>
<p>Bird's-eye: a map seen from above (right = forward, up = robot's left), ground at z<sub>w</sub> = 40 pixel units.
Panorama: centre = forward, top = rim. <i>thesis</i> uses the parabolic Eq. 3.4 / radius-linear rows; <i>exact</i>
the model of docs/conventions.md §1.</p>
)" << method.views;
  return html.str();
}

// What a child `omnicam demo --section NAME` renders; returns the section's HTML. Run alone (to
// reproduce it), a section writes the shared hall itself.
std::string sectionHtml(const DemoArgs& a) {
  const std::string dir = scenesDir();
  const bool needsHall = a.section == "glance" || a.section == "light" || a.section == "robot";
  if (needsHall && !std::filesystem::exists(std::filesystem::symlink_status(hallScenePath(a.out))))
    writeDemoHall(a.out, dir + "/robocup2006.json");
  if (a.section == "start-pose") return startPoseHtml(a);
  if (a.section == "glance") return glanceSection(renderGlance(a.out, a), readRingSummary(a), a.spp);
  if (a.section == "light") return demoLight(a.out, hallScenePath(a.out), a.blender);
  const Scene arena = loadScene(dir + "/robocup2006.json");
  if (a.section == "physical") return demoPhysicalCamera(a.out, arena, a.spp, a.povray);
  if (a.section == "lenses") return demoLenses(a.out, arena, a.spp, a.povray, a.blender);
  if (a.section == "robot") {  // one after the other, as the progress lines say
    const std::string motion = demoMotion(a.out, arena, a.spp);
    const std::string dataset = demoDataset(a.out, dir + "/robocup2006.json");
    return motion + dataset + demoTexturedHall(a.out, dir + "/robocup2006.json");
  }
  throw std::logic_error("unknown demo section " + a.section);  // checked by checkSectionNames
}

// Refuses names that are not sections, before anything is written.
void checkSectionNames(const std::vector<std::string>& names, const std::string& flag) {
  std::string known;
  for (const DemoSection& s : demoSections()) known += (known.empty() ? "" : ", ") + s.name;
  for (const std::string& name : names)
    if (std::none_of(demoSections().begin(), demoSections().end(), [&](const DemoSection& s) { return s.name == name; }))
      throw InputError(flag + ": unknown section " + quote(name) + " (the sections are " + known + ")");
}

void renderOneSection(const DemoArgs& a) {
  // Line by line into the section's log: a section ended on its budget keeps what it said.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  ensureDirectory(a.out + "/sections", "-o");
  const std::string html = sectionHtml(a);
  writeTextAtomically(a.out + "/sections/" + a.section + ".html", html);
}

std::vector<std::string> sectionCommand(const DemoArgs& a, const std::string& section) {
  std::vector<std::string> argv{std::filesystem::read_symlink("/proc/self/exe").string(), "demo", "--section", section,
                                "-o", std::filesystem::absolute(a.out).string(), "--spp", std::to_string(a.spp)};
  if (!a.povray) argv.push_back("--no-povray");
  if (!a.blender) argv.push_back("--no-blender");
  return argv;
}

const char* kReportHead = R"(<!doctype html><html><head><meta charset="utf-8"><title>omnicam demo</title>
<style>body{font-family:sans-serif;max-width:1150px;margin:2em auto;color:#222}
figure{display:inline-block;margin:0 1em 1em 0;vertical-align:top;max-width:380px}figcaption{font-size:90%;color:#555}
img{image-rendering:pixelated;background:#444}table{border-collapse:collapse;font-size:85%}
td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}
.short{border-left:6px solid #d62728;background:#fdf0f0;padding:0.3em 1em}pre{white-space:pre-wrap;font-size:80%}</style></head><body>
<h1>omnicam demo</h1>
)";

// The sections' table at the end: what each took against its budget.
std::string sectionsTable(const std::vector<SectionRun>& runs) {
  std::ostringstream html;
  html << "<h3>How this report was made</h3><p>Each section ran as its own <code>omnicam demo --section</code> "
          "with a time budget scaled to what it renders (<code>--budget-scale</code> stretches them); a section that "
          "fails or runs out of time is ended with its renderers and marked, and the others are kept.</p><table>"
          "<tr><th>section</th><th>outcome</th><th>seconds</th><th>budget (s)</th></tr>\n";
  for (size_t k = 0; k < runs.size(); ++k)
    html << "<tr><td>" << demoSections()[k].name << "</td><td>"
         << (runs[k].outcome == SectionOutcome::Done ? "done" : escapeMarkup(runs[k].reason)) << "</td>"
         << format("<td>%.1f</td><td>%.3g</td></tr>\n", runs[k].seconds, runs[k].budgetSeconds);
  html << "</table>\n";
  return html.str();
}

int runDemo(const DemoArgs& a) {
  namespace fs = std::filesystem;
  checkSpp(a.spp, "--spp");  // before any folder is made
  if (!a.section.empty()) checkSectionNames({a.section}, "--section");
  checkSectionNames(a.only, "--sections");
  ensureDirectory(a.out, "-o");
  if (!a.section.empty()) {
    renderOneSection(a);
    return 0;
  }
  ensureDirectory(a.out + "/sections", "-o");
  try {
    writeDemoHall(a.out, scenesDir() + "/robocup2006.json");
  } catch (const std::exception& e) {  // the sections that need the hall fail, are marked, and say why
    std::printf("demo: the textured hall could not be written: %s\n", oneLine(e.what()).c_str());
  }
  const DemoBudgetInputs budget{a.spp, a.povray, a.blender, a.budgetScale};
  const std::vector<DemoSection>& sections = demoSections();
  std::vector<SectionRun> runs(sections.size());
  for (size_t n = 0; n < kRunOrder.size(); ++n) {
    const size_t k = static_cast<size_t>(
        std::find_if(sections.begin(), sections.end(), [&](const DemoSection& s) { return s.name == kRunOrder[n]; }) -
        sections.begin());
    if (!a.only.empty() && std::find(a.only.begin(), a.only.end(), sections[k].name) == a.only.end()) {
      runs[k].outcome = SectionOutcome::NotRun;
      runs[k].reason = "not run (--sections)";
      continue;
    }
    const double seconds = sectionBudgetSeconds(sections[k], budget);
    std::printf("demo: section %zu/%zu, %s (budget %.3g s)\n", n + 1, kRunOrder.size(), sections[k].name.c_str(), seconds);
    std::fflush(stdout);
    runs[k] = runDemoSection(sections[k], sectionCommand(a, sections[k].name),
                             (fs::absolute(a.out) / "sections").string(), seconds);
    if (runs[k].outcome == SectionOutcome::Done)
      std::printf("demo: section %s done in %.1f s\n", sections[k].name.c_str(), runs[k].seconds);
    else
      std::printf("demo: section %s fell short: it %s; reproduce with: %s\n", sections[k].name.c_str(),
                  runs[k].reason.c_str(), runs[k].command.c_str());
  }
  std::ostringstream html;
  html << kReportHead;
  std::string shortfalls;
  for (size_t k = 0; k < runs.size(); ++k)
    if (fellShort(runs[k]))
      shortfalls += (shortfalls.empty() ? "" : ", ") + escapeMarkup(sections[k].name) + " (" + escapeMarkup(runs[k].reason) + ")";
  if (!shortfalls.empty())
    html << "<p class=\"short\"><b>Sections that fell short:</b> " << shortfalls
         << ". They are marked below; the rest of the report is complete.</p>\n";
  for (size_t k = 0; k < runs.size(); ++k)
    if (runs[k].outcome != SectionOutcome::NotRun)
      html << (runs[k].outcome == SectionOutcome::Done ? runs[k].html : shortSectionHtml(sections[k], runs[k]));
  html << R"(
<p>Every image has a sidecar (<code>*.png.json</code>): engine and version, scene SHA-256, pose, rig, spp, seconds,
and OpenCV <code>cv::omnidir</code> intrinsics.</p>
)" << sectionsTable(runs)
       << "</body></html>\n";
  writeTextAtomically(a.out + "/index.html", html.str());
  const int code = demoExitCode(runs);
  if (code != 0) std::printf("demo: sections that fell short: %s (exit %d)\n", shortfalls.c_str(), code);
  std::printf("demo: open %s\n", (fs::absolute(a.out) / "index.html").string().c_str());
  return code;
}

}  // namespace

void addDemoCommand(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* cmd = app.add_subcommand("demo", "Main job: fast vs POV-Ray renders and rings, the physical and lens cameras "
                                             "(mirror, fisheye, panorama), with an HTML report. Exit 0, or 64 + one bit "
                                             "per section that fell short (docs/conventions.md)");
  cmd->add_option("-o,--output", args->out, "Report folder (default out/demo)");
  cmd->add_option("--spp", args->spp, "Samples per pixel, n*n (default 16)")->check(integerIn(1, INT32_MAX));
  cmd->add_flag("!--no-povray", args->povray, "Skip the POV-Ray ground truth");
  cmd->add_flag("!--no-blender", args->blender, "Skip the Blender ground truth");
  cmd->add_option("--budget-scale", args->budgetScale,
                  "Multiply every section's time budget (default 1; a slow or busy machine: 2 or more)")
      ->check(numberIn(0, 1000, true));
  cmd->add_option("--sections", args->only, "Run only these sections (comma-separated: glance, start-pose, light, "
                  "physical, lenses, robot); the report lists the others as not run")
      ->delimiter(',');
  cmd->add_option("--section", args->section, "Render one section into the report folder (what the demo runs for each)")
      ->group("");
  cmd->callback([args, cmd, &exitCode] {
    refuseUnless(*cmd, "--sections", args->section.empty(), "the whole demo (not with --section)");
    refuseUnless(*cmd, "--budget-scale", args->section.empty(), "the whole demo (not with --section)");
    exitCode = runDemo(*args);
  });
}

}  // namespace omnicam::cli
