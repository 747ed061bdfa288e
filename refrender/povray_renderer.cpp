#include "povray_renderer.h"

#include <cstdlib>
#include <filesystem>

#include "atomic_file.h"
#include "errors.h"
#include "make_camera.h"
#include "external_process.h"
#include "job_folder.h"
#include "povray_exporter.h"

namespace omnicam {

namespace fs = std::filesystem;

namespace {

// POV-Ray reads $HOME/.povray/3.7/povray.conf; the job's HOME is the job folder.
void writeRestrictiveConfig(const std::string& jobDir) {
  const fs::path dir = fs::path(jobDir) / ".povray" / "3.7";
  fs::create_directories(dir);
  writeTextAtomically((dir / "povray.conf").string(),
                      "[File I/O Security]\nrestricted\n[Shellout Security]\nforbidden\n"
                      "[Permitted Paths]\nread+write = " + jobDir + "\n");
}

}  // namespace

std::string povrayVersion(const std::string& executable) {
  JobFolder job("omnicam-povray", false);
  writeRestrictiveConfig(job.path());
  const ProcessResult r = runProcess({executable, "--version"}, job.path(), job.path() + "/version.log", 30.0);
  if (r.exitCode != 0) return "";
  const std::string tail = tailOfFile(job.path() + "/version.log", 200);
  const size_t at = tail.find("POV-Ray ");
  return at == std::string::npos ? "povray" : tail.substr(at, tail.find('\n', at) - at);
}

ImageRGBA downsampleWithRimAlpha(const ImageRGBA& large, int n, const Camera& camera) {
  ImageRGBA image(camera.width(), camera.height());
  const float weight = 1.0f / static_cast<float>(n * n);
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i) {
      float sum[3] = {0, 0, 0};
      for (int b = 0; b < n; ++b)
        for (int a = 0; a < n; ++a) {
          const float* px = large.at(i * n + a, j * n + b);
          for (int c = 0; c < 3; ++c) sum[c] += px[c];
        }
      float* out = image.at(i, j);
      for (int c = 0; c < 3; ++c) out[c] = sum[c] * weight;
      out[3] = camera.coverage(i, j, n);
    }
  return image;
}

ImageRGBA renderWithPovray(const Scene& scene, const RobotPose& pose, const RenderSettings& settings,
                           const PovrayOptions& options) {
  const PovrayJob job = exportPovray(scene, pose, settings);
  JobFolder folder("omnicam-povray", options.keepJobFolder);
  writePovrayJob(job, folder.path(), options.threads);
  writeRestrictiveConfig(folder.path());
  const std::string log = folder.path() + "/povray.log";
  const ProcessResult r = runProcess({options.executable, "render.ini"}, folder.path(), log, options.timeoutSeconds);
  if (r.notFound) throw ExternalError("povray: not found (install it with `make deps`): " + showPath(options.executable));
  if (r.timedOut)
    throw ExternalError("povray: timed out after " + std::to_string(static_cast<int>(options.timeoutSeconds)) +
                        " s; last output:\n" + r.logTail);
  const std::string output = folder.path() + "/render.exr";
  if (r.exitCode != 0 || !fs::exists(output))
    throw ExternalError("povray: failed (exit " + std::to_string(r.exitCode) + "); last output:\n" + r.logTail);
  ImageRGBA large;
  try {
    large = readImage(output);
  } catch (const InputError& e) {
    throw ExternalError(std::string("povray: unreadable output: ") + e.what());
  }
  if (large.width != job.width || large.height != job.height)
    throw ExternalError("povray: output has the wrong size");
  return downsampleWithRimAlpha(large, job.samplesPerAxis, *makeCamera(settings.rig));
}

}  // namespace omnicam
