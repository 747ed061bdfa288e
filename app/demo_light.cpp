#include "demo_light.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "demo_figures.h"
#include "demo_glance.h"
#include "render_noise.h"
#include "render_output.h"
#include "render_request.h"
#include "scene_loader.h"

namespace omnicam::cli {

namespace {

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

}  // namespace

// Physically based light: the fast renderer's path shading as a dataset renders it (denoised)
// beside Cycles' frame of the same textured hall, and the PSNR between them (docs/path-tracing.md
// measures nine such pairs against 1024-spp references).
std::string demoLight(const std::string& out, const std::string& scenePath, bool blender) {
  const Scene scene = loadScene(scenePath);
  const RenderSettings settings = requestedSettings(
      scene.rig, {{RequestField::Shading, "path"}, {RequestField::Spp, int64_t{kPathDatasetSpp}}, {RequestField::Denoise, true}});
  std::printf("demo: light, fast path shading, %d spp, denoised\n", settings.spp);
  auto fast = makeEngine(RenderRequest{"fast"}, scene);
  const RenderedFile fastFrame = renderToFile(scene, *fast, kGlancePose, settings, out + "/light_fast.png");
  std::ostringstream html;
  html << "<h2>Light: physically based at the fast renderer's speed (<code>--shading path</code>)</h2><p>The textured "
          "hall lit by its four lamps as luminaires of real size (discs of 50 cm), light bouncing off the walls, the "
          "floor and the ceiling (docs/path-tracing.md). <b>fast</b>: omnicam's path tracer as a dataset renders it, "
       << settings.spp << " samples per pixel, indirect light denoised"
       << formatNumbers(" (%.2f s)", fastFrame.sidecar["seconds"].get<double>()) << ".";
  if (!blender) {
    html << " (Cycles' frame: not rendered, <code>--no-blender</code>.)</p><figure><img src=\"light_fast.png\" "
            "width=\"360\"><figcaption>fast, path</figcaption></figure>\n";
    return html.str();
  }
  RenderSettings small = settings;
  small.rig = settings.rig.resized(kLightReferenceSize);
  const ImageRGBA fastSmall = fast->render(kGlancePose, small);
  RenderSettings reference =
      requestedSettings(small.rig, {{RequestField::Shading, "path"}, {RequestField::Spp, int64_t{kLightReferenceSpp}}});
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
       << formatNumbers(" (%.0f s in all)", cyclesSeconds)
       << formatNumbers(". Between them, at that size: <b>PSNR %.1f dB</b> (8-bit sRGB inside the mirror). ", psnr)
       << formatNumbers("The reference is not converged: its own noise, from the difference of its two seeds, is PSNR "
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

}  // namespace omnicam::cli
