#include "demo_start_pose.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <tuple>

#include "atomic_file.h"
#include "cli_util.h"
#include "cubemap_renderer.h"
#include "demo_figures.h"
#include "json_text.h"
#include "render_output.h"
#include "render_request.h"
#include "rings.h"
#include "scene_loader.h"
#include "svg_plot.h"
#include "views.h"
#include "safe_files.h"

namespace omnicam::cli {

namespace {

// What the section renders: where, and with which engines.
struct StartPose {
  std::string out;
  int spp = 16;
  bool povray = true, blender = true;
};

struct EngineRings {
  std::string engine;
  RingReport report;
};

const char* kColours[] = {"#2ca02c", "#9467bd", "#ff7f0e"};  // fast, povray, blender

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
    const double t = radians(deg), e = camera.radiusOfTheta(t), q = thesisEq32Radius(h, t);
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

// The open field from the thesis' start pose, unlit and lit, by every engine.
std::string openFieldSection(const StartPose& a, const Scene& arena, const std::vector<std::string>& engines) {
  std::ostringstream views;
  for (Shading shading : {Shading::Unlit, Shading::Lit}) {
    const RenderSettings settings =
        requestedSettings(arena.rig, {{RequestField::Spp, int64_t{a.spp}}, {RequestField::Shading, shadingName(shading)}});
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

RingSection ringSection(const StartPose& a, const Scene& ringScene, const std::vector<std::string>& engines) {
  const RenderSettings ringSettings = requestedSettings(ringScene.rig, {{RequestField::Spp, int64_t{a.spp}}});
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
                << formatNumbers(": RMS against the exact model <b>%.4f px</b> (max %.4f px); Eq. 3.2 MSE <b>%.4f px²</b>; "
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
    ringTable << formatNumbers("<tr><td>%.0f</td><td>%.4f</td><td>%.4f</td>", m.thetaDeg, m.exactPx, m.eq32Px);
    for (const auto& e : out.rings)
      ringTable << formatNumbers("<td>%.4f</td><td>%+.4f</td>", e.report.rings[k].measuredPx,
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

MethodSection methodSection(const StartPose& a, const Scene& arena) {
  std::ostringstream method, viewFigures;
  const RenderSettings settings = requestedSettings(arena.rig, {{RequestField::Spp, int64_t{a.spp}}});
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
           << formatNumbers("<br>PSNR %.2f dB vs exact", compareImages(exact, image).psnrDb) << "</figcaption></figure>\n";
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

// The rings the start-pose section measured, for the glance; in the demo's folder.
const char* const kRingSummaryFile = "sections/start-pose-rings.json";
std::string ringSummaryPath(const std::string& out) { return out + "/" + kRingSummaryFile; }

// The open field, the rings, the thesis' method and the views, from the thesis' start pose.
std::string startPoseHtml(const StartPose& a) {
  removeFileInside(a.out, kRingSummaryFile);  // the glance cites only this run's rings
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
  writeTextAtomically(ringSummaryPath(a.out), summary.dump(1) + "\n");
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

}  // namespace

std::string demoStartPose(const std::string& out, int spp, bool povray, bool blender) {
  return startPoseHtml(StartPose{out, spp, povray, blender});
}

std::vector<RingSummary> readRingSummary(const std::string& out) {
  std::vector<RingSummary> rings;
  if (entryInside(out, kRingSummaryFile) != EntryKind::File) return rings;
  for (const auto& r : nlohmann::json::parse(readFileInside(out, kRingSummaryFile, 1 << 20)))
    rings.push_back({r.at("engine"), r.at("rms_px_exact")});
  return rings;
}

}  // namespace omnicam::cli
