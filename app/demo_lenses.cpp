#include "demo_lenses.h"

#include <cstdio>
#include <sstream>

#include "aov_preview.h"
#include "aov_renderer.h"
#include "atomic_file.h"
#include "engines.h"
#include "fast_renderer.h"
#include "image_compare.h"
#include "render_output.h"

namespace omnicam::cli {

namespace {

std::string figure(const std::string& file, const std::string& caption) {
  return "<figure><img src=\"" + file + "\" width=\"360\"><figcaption>" + caption + "</figcaption></figure>\n";
}

std::string decibels(const char* what, const CompareResult& r) {
  char text[160];
  std::snprintf(text, sizeof text, "<br>fast vs %s: PSNR %.2f dB, SSIM %.5f", what, r.psnrDb, r.ssim);
  return text;
}

// The robot's other cameras, where its mirror camera's F' is: an equidistant fisheye of 190°
// looking ahead (the f-θ lens POV-Ray and Cycles both have) and a full panorama.
RigSpec fisheyeRig(const RigSpec& mirror) {
  FThetaLens lens;
  lens.kind = FThetaLens::Kind::Equidistant;
  lens.maxThetaRad = radians(95.0);
  lens.f = 360.0 / (2.0 * lens.maxThetaRad);  // its circle fills the 360×360 image
  lens.cx = lens.cy = 179.5;
  RigSpec rig;
  rig.height = mirror.height;
  rig.kind = LensCameraSpec{lens, 360, 360, {0.0, 0.0, 0.0}};
  return rig;
}

RigSpec panoramaRig(const RigSpec& mirror) {
  RigSpec rig;
  rig.height = mirror.height;
  rig.kind = LensCameraSpec{Equirectangular{720, 360}, 720, 360, {0.0, 0.0, 0.0}};
  return rig;
}

}  // namespace

std::string demoLenses(const std::string& out, const Scene& arena, int spp, bool povray, bool blender) {
  std::printf("demo: lens cameras, the start pose through the mirror, a fisheye and a panorama, %d spp\n", spp);
  const RobotPose pose = arena.startPose;
  const FastRenderer fast(arena);
  const RenderRequest request = readRenderRequest({{RequestField::Spp, int64_t{spp}}}, {});
  const RenderSettings mirror = request.settings(arena.rig), fisheye = request.settings(fisheyeRig(arena.rig)),
                       panorama = request.settings(panoramaRig(arena.rig));
  auto engine = makeEngine(request, arena);
  renderToFile(arena, *engine, pose, mirror, out + "/lens_mirror.png");
  const ImageRGBA fisheyeImage = renderToFile(arena, *engine, pose, fisheye, out + "/lens_fisheye.png").image;
  const ImageRGBA panoramaImage = renderToFile(arena, *engine, pose, panorama, out + "/lens_panorama.png").image;
  const AovFrame aovs = renderAovs(fast, pose, fisheye);
  writeImageAtomic(out + "/lens_fisheye_depth.png", depthPreview(DataImage{aovs.width, aovs.height, 1, aovs.depth}, 6.0));

  std::string fisheyeTruth, panoramaTruth;
  const auto truth = [&](const char* engineName, const RenderSettings& settings, const ImageRGBA& ours, const std::string& file) {
    std::printf("demo: lens cameras, %s ground truth %s\n", engineName, file.c_str());
    auto reference = makeEngine(RenderRequest{engineName}, arena);
    const CompareResult r = compareImages(ours, renderToFile(arena, *reference, pose, settings, out + "/" + file).image);
    return figure(file, std::string(engineName) + "'s own camera" + decibels(engineName, r));
  };
  if (povray) {
    fisheyeTruth += truth("povray", fisheye, fisheyeImage, "lens_fisheye_povray.png");
    panoramaTruth += truth("povray", panorama, panoramaImage, "lens_panorama_povray.png");
  }
  if (blender) panoramaTruth += truth("blender", panorama, panoramaImage, "lens_panorama_blender.png");

  std::ostringstream html;
  html << "<h2>Lens cameras (docs/lens-cameras.md)</h2><p>The same pose through the robot's mirror camera, a 190° "
          "equidistant fisheye looking ahead and a full 360°×180° panorama, each at the mirror's viewpoint F′ and "
          "rendered through the same camera interface. A lens camera gets every output the mirror camera gets; its depth "
          "is the distance along each pixel's ray out to the image's edge (not a cube face's planar depth). POV-Ray's "
          "<code>fisheye</code> and <code>spherical</code> cameras and Cycles' panoramic ones are their ground truths.</p>\n"
       << figure("lens_mirror.png", "the mirror camera") << figure("lens_fisheye.png", "equidistant fisheye, 190°")
       << figure("lens_fisheye_depth.png", "the fisheye's depth along its rays (white = 6 m)") << fisheyeTruth
       << "<figure style=\"max-width:740px\"><img src=\"lens_panorama.png\" width=\"720\"><figcaption>equirectangular "
          "panorama</figcaption></figure>\n"
       << panoramaTruth;
  return html.str();
}

}  // namespace omnicam::cli
