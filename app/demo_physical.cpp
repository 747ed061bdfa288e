#include "demo_physical.h"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <vector>

#include "aov_preview.h"
#include "atomic_file.h"
#include "central_fit.h"
#include "demo_figures.h"
#include "fast_renderer.h"
#include "number_format.h"
#include "physical_camera.h"
#include "render_output.h"
#include "render_request.h"

namespace omnicam::cli {

// The rig as built: the ideal camera beside one whose pinhole sits 2 mm off the mirror's focus and
// is turned by 1°, their difference, POV-Ray's ground truth of the misaligned rig, and the
// best-fit central model's residual map (docs/physical-camera.md).
std::string demoPhysicalCamera(const std::string& out, const Scene& arena, int spp, bool povray) {
  const RenderSettings settings = requestedSettings(arena.rig, {{RequestField::Spp, int64_t{spp}}});
  RenderSettings misaligned = settings;
  misaligned.rig.mirrorRig().mount.offsetMm = {2.0, -1.0, 1.0};
  misaligned.rig.mirrorRig().mount.rotationDeg = {1.0, -0.5, 0.5};
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
          << formatNumbers("<br>PSNR %.2f dB: the misalignment is not a detail", change.psnrDb) << "</figcaption></figure>\n";
  if (povray) {
    std::printf("demo: physical camera, POV-Ray ground truth of the misaligned rig\n");
    auto engine = makeEngine(RenderRequest{"povray"}, arena);
    const auto truth = renderToFile(arena, *engine, arena.startPose, misaligned, out + "/physical_povray.png");
    const CompareResult r = compareImages(moved, truth.image);
    std::printf("demo: physical camera, fast vs POV-Ray: PSNR %.2f dB\n", r.psnrDb);
    figures << "<figure><img src=\"physical_povray.png\" width=\"360\"><figcaption>POV-Ray, the same physical pinhole"
            << formatNumbers("<br>fast vs POV-Ray: PSNR %.2f dB, SSIM %.5f", r.psnrDb, r.ssim) << "</figcaption></figure>\n";
  }
  const PhysicalCamera camera(misaligned.rig);
  const CentralApproximation& fit = camera.centralApproximation();
  const std::vector<float> residual = centralResidualMap(camera, fit, 1.0);
  const double scale = std::max(1e-6, fit.residuals[3].maxPx);
  writeImageAtomic(out + "/physical_central_residual.png", scalarHeatmap(residual, camera.width(), camera.height(), scale));
  figures << "<figure><img src=\"physical_central_residual.png\" width=\"360\"><figcaption>best-fit central (Mei) "
             "model's reprojection error for points 1 m away"
          << formatNumbers(" (white = %.2f px)", scale) << "</figcaption></figure>\n";
  std::ostringstream table;
  table << "<table><tr><th>points at</th><th>rms (px)</th><th>max (px)</th></tr>\n";
  for (const auto& r : fit.residuals)
    table << "<tr><td>" << (r.distanceM == 0.0 ? std::string("infinity") : roundTrip(r.distanceM) + " m") << "</td>"
          << formatNumbers("<td>%.3f</td><td>%.3f</td></tr>\n", r.rmsPx, r.maxPx);
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

}  // namespace omnicam::cli
