#include "demo_glance.h"

#include <filesystem>
#include <sstream>

#include "demo_figures.h"
#include "hall_arena.h"
#include "render_request.h"
#include "scene_loader.h"
#include "safe_files.h"

namespace omnicam::cli {

std::string hallScenePath(const std::string& out) { return out + "/hall/hall-textured.json"; }

void writeDemoHall(const std::string& out, const std::string& fieldScene) {
  HallOptions hall;
  hall.fieldScene = fieldScene;
  hall.photos = {kLabPhoto};
  makeFoldersInside(out, "hall");  // not through a link planted under its name
  writeHallArena(hall, hallScenePath(out));
}

namespace {

EngineFigures renderGlance(const std::string& out, int spp, bool povray) {
  const Scene scene = loadScene(hallScenePath(out));
  const RenderSettings settings = requestedSettings(scene.rig, {{RequestField::Spp, int64_t{spp}}, {RequestField::Shading, "lit"}});
  std::vector<std::string> engines{"fast"};
  if (povray) engines.push_back("povray");  // the exact ground truth; Blender lit is not a pixel comparison
  return renderAndCompare(out, "glance", "at a glance: robocup2006 in the textured hall, lit", scene, kGlancePose,
                          settings, engines, [](const std::string&) { return std::string(); });
}

std::string glanceSection(const EngineFigures& glance, const std::vector<RingSummary>& rings, int spp) {
  std::ostringstream html;
  html << "<h2>At a glance</h2>\n<p>omnicam simulates a catadioptric omnidirectional camera — a camera looking up "
          "into a hyperbolic mirror, as on soccer and rescue robots — and proves its images right against ground "
          "truth. Here the RoboCup 2006 field inside the thesis' hall, its walls carrying a real 360&deg; photo "
          "(<code>omnicam arena hall --photo</code>), seen from "
       << formatNumbers("(%.1f m, %.1f m, %.0f&deg;)", kGlancePose.x, kGlancePose.y, kGlancePose.yawDeg) << ", lit, " << spp
       << " samples per pixel. <b>fast</b>: omnicam's renderer, every ray straight from the closed-form model"
       << formatNumbers(" (%.2f s)", glance.fastSeconds) << ". ";
  for (const auto& [engine, r] : glance.vsFast)
    html << "<b>" << engine << "</b>: the ground truth, a pinhole camera looking up into the exact mirror. They agree "
         << formatNumbers("at <b>PSNR %.1f dB</b> (SSIM %.5f, largest difference %.4f of full scale)", r.psnrDb, r.ssim,
                   r.maxAbs)
         << ". ";
  if (glance.vsFast.empty()) html << "(No ground truth: <code>--no-povray</code>.) ";
  if (!rings.empty()) {
    html << "The incidence-angle rings below lie ";
    for (size_t k = 0; k < rings.size(); ++k)
      html << (k == 0 ? "" : k + 1 == rings.size() ? " and " : ", ") << formatNumbers("<b>%.4f px</b>", rings[k].rmsPxExact)
           << " RMS (" << rings[k].engine << ")";
    html << " from the exact model.";
  }
  html << "</p>\n" << glance.html;
  return html.str();
}

}  // namespace

std::string demoGlance(const std::string& out, int spp, bool povray, const std::vector<RingSummary>& rings) {
  return glanceSection(renderGlance(out, spp, povray), rings, spp);
}

}  // namespace omnicam::cli
