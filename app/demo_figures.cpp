#include "demo_figures.h"

#include <cstdio>
#include <sstream>

#include "atomic_file.h"
#include "render_output.h"

namespace omnicam::cli {

std::string formatNumbers(const char* fmt, double a, double b, double c, double d) {
  char buf[512];
  std::snprintf(buf, sizeof buf, fmt, a, b, c, d);
  return buf;
}

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
         << formatNumbers(" (%.2f s)", seconds) << "</figcaption></figure>\n";
  }
  for (size_t k = 1; k < images.size(); ++k) {
    const std::string& name = engines[k];
    const CompareResult r = compareImages(images[0], images[k]);
    const std::string diff = stem + "_diff_" + name + ".png";
    writeImageAtomic(out + "/" + diff, differenceHeatmap(images[0], images[k], 0.01));
    html << "<figure><img src=\"" << diff << "\" width=\"360\"><figcaption>|fast − " << name
         << "| (white = 0.01)<br>"
         << formatNumbers("PSNR %.2f dB, RMSE %.2e, SSIM %.5f, max %.4f", r.psnrDb, r.rmse, r.ssim, r.maxAbs) << caveat(name)
         << "</figcaption></figure>\n";
    std::printf("demo: %s, fast vs %s: PSNR %.2f dB, SSIM %.5f\n", label.c_str(), name.c_str(), r.psnrDb, r.ssim);
    result.vsFast.emplace_back(name, r);
  }
  result.html = html.str();
  return result;
}
}  // namespace omnicam::cli
