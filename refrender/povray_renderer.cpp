#include "povray_renderer.h"

#include <algorithm>
#include <condition_variable>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>

#include "atomic_file.h"
#include "errors.h"
#include "make_camera.h"
#include "external_process.h"
#include "motion.h"
#include "job_folder.h"
#include "memory_budget.h"
#include "number_format.h"
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
  const ProcessResult r = runRenderer({executable, "--version"}, job.path(), job.path() + "/version.log", 30.0);
  if (r.exitCode != 0) return "";
  const std::string tail = tailOfFile(job.path() + "/version.log", 200);
  const size_t at = tail.find("POV-Ray ");
  return at == std::string::npos ? "povray" : tail.substr(at, tail.find('\n', at) - at);
}

namespace {

// POV-Ray processes of a moving frame run at once: a short job is mostly POV-Ray waiting. Each
// renders on one thread; with render threads given, at most that many run.
constexpr int kConcurrentPovrayJobs = 8;
// A moving frame's renders are summed in job order as they arrive; one that finishes before an
// earlier one waits, and a job starts only within this many of the next to be summed. So at most
// this many renders are held, however many lines and instants the frame has.
constexpr size_t kHeldPovrayRenders = 2 * kConcurrentPovrayJobs;

// Renders one exported job (a region of it, if given) in a private job folder: the n×-larger image.
ImageRGBA runPovrayJob(const PovrayJob& job, const PovrayOptions& options, int threads,
                       const std::optional<PovrayRegion>& region = std::nullopt) {
  JobFolder folder("omnicam-povray", options.keepJobFolder);
  writePovrayJob(job, folder.path(), threads, region);
  writeRestrictiveConfig(folder.path());
  const std::string log = folder.path() + "/povray.log";
  // POV-Ray 3.7 gives up when its render threads do not start within its own fixed time, which a
  // loaded machine (several POV-Ray processes at once) can cause. Nothing was rendered then, so
  // the job runs again.
  constexpr int kStartupAttempts = 3;
  constexpr const char* kWorkerStartupTimeout = "Timed out waiting for worker thread startup";
  ProcessResult r;
  for (int attempt = 1;; ++attempt) {
    r = runRenderer({options.executable, "render.ini"}, folder.path(), log, options.timeoutSeconds);
    if (r.exitCode == 0 || r.notFound || r.timedOut || attempt == kStartupAttempts ||
        r.logTail.find(kWorkerStartupTimeout) == std::string::npos)
      break;
  }
  // Another executable than Debian's was asked for (OMNICAM_POVRAY): installing POV-Ray would not help.
  if (r.notFound)
    throw ExternalError("povray: not found: " + showPath(options.executable) +
                        (options.executable == PovrayOptions{}.executable ? " (install it with `make deps`)" : " (as OMNICAM_POVRAY names it)"));
  if (r.timedOut)
    throw ExternalError("povray: timed out after " + shortNumber(options.timeoutSeconds) +
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
  return large;
}

// One POV-Ray render of a moving frame: one readout line (all of them for a global shutter) at
// one of its instants.
struct InstantJob {
  int line = 0, instant = 0;
};

// The region of the n×-larger image that holds a line's samples.
PovrayRegion regionOfLine(const Shutter& shutter, int line, int width, int height, int n) {
  if (!shutter.rolling) return {0, height * n, 0, width * n};
  const bool rows = shutter.rolling->readout == Readout::TopToBottom || shutter.rolling->readout == Readout::BottomToTop;
  int first = line;  // the line's row or column in the image
  if (shutter.rolling->readout == Readout::BottomToTop) first = height - 1 - line;
  if (shutter.rolling->readout == Readout::RightToLeft) first = width - 1 - line;
  return rows ? PovrayRegion{first * n, (first + 1) * n, 0, width * n} : PovrayRegion{0, height * n, first * n, (first + 1) * n};
}

// A moving frame as the mean of still POV-Ray renders (docs/motion.md): one per line and instant,
// with the robot and mirror where they are then; each render gives exactly the samples the fast
// renderer traces at that line and instant. POV-Ray spends most of a short job waiting, so several
// run at once.
void renderMovingWithPovray(const Scene& scene, const CameraPlacement& placement, const RenderSettings& settings,
                            const PovrayOptions& options, Film& film) {
  const Shutter& shutter = settings.rig.shutter;
  const int n = *samplesPerAxis(settings.spp), width = settings.rig.imageWidth(), height = settings.rig.imageHeight();
  const PixelInstants instants = pixelInstants(shutter, n);
  std::vector<InstantJob> jobs;
  for (int line = 0; line < lineCount(shutter, width, height); ++line)
    for (int m = 0; m < instants.count; ++m) jobs.push_back({line, m});
  // Each render is the whole n×-larger image (RGBA floats; while decoded, its channels too).
  const int64_t renderBytes = static_cast<int64_t>(width) * n * height * n * 32;
  // A job starts only within kHeldPovrayRenders of the next to be summed: running and held ones together.
  const size_t atOnce = std::min(jobs.size(), kHeldPovrayRenders);
  requireMemory(static_cast<int64_t>(atOnce) * renderBytes + static_cast<int64_t>(width) * height * 16,
                "POV-Ray's moving frame (" + std::to_string(atOnce) + " of its " + std::to_string(jobs.size()) + " renders of " +
                    std::to_string(width * n) + "x" + std::to_string(height * n) + " pixels held at once)");
  RenderSettings still = settings;
  still.rig.shutter = {};
  // Each sample from the render of its line and instant, summed into the film in job order (a
  // fixed order).
  film.begin();
  std::mutex mutex;
  std::condition_variable summed;
  size_t nextToSum = 0;
  bool stopped = false;
  std::map<size_t, ImageRGBA> held;  // finished, waiting for an earlier job
  if (options.onRenderSummed) options.onRenderSummed(0, static_cast<int>(jobs.size()));
  const int processes = options.threads > 0 ? std::min(options.threads, kConcurrentPovrayJobs) : kConcurrentPovrayJobs;
  runConcurrently(jobs.size(), processes, [&](size_t k) {
    {
      std::unique_lock<std::mutex> lock(mutex);
      summed.wait(lock, [&] { return stopped || k < nextToSum + kHeldPovrayRenders; });
      if (stopped) return;
    }
    const InstantJob& job = jobs[k];
    const double seconds = lineStart(shutter, job.line) + instantTime(shutter, job.instant, instants.count);
    // Any failure (a render, or summing it) stops the jobs waiting for their turn; runConcurrently
    // rethrows it once the running ones are done.
    const auto stopOthers = [&] {
      const std::lock_guard<std::mutex> lock(mutex);
      stopped = true;
      summed.notify_all();
    };
    ImageRGBA render;
    try {
      render = runPovrayJob(exportPovray(scene, placement.frozenAt(seconds), still), options, /*threads=*/1,
                            regionOfLine(shutter, job.line, width, height, n));
    } catch (...) {
      stopOthers();
      throw;
    }
    std::unique_lock<std::mutex> lock(mutex);
    try {
      held.emplace(k, std::move(render));
      for (auto next = held.find(nextToSum); next != held.end(); next = held.find(nextToSum)) {
        const InstantJob& done = jobs[nextToSum];
        film.accumulateSupersampled(next->second, instants.passes, [&](int i, int j, int a, int b, int pass) {
          return lineOf(shutter, i, j, width, height) == done.line && instantOf(shutter, a, b, n, pass) == done.instant;
        });
        held.erase(next);
        ++nextToSum;
        if (options.onRenderSummed) options.onRenderSummed(static_cast<int>(nextToSum), static_cast<int>(jobs.size()));
      }
    } catch (...) {
      lock.unlock();
      stopOthers();
      throw;
    }
    summed.notify_all();
  });
  film.setRimAlpha(*makeCamera(settings.rig));
  film.resolve(instants.passes);
}

}  // namespace

void renderWithPovray(const Scene& scene, const CameraPlacement& placement, const RenderSettings& settings,
                      const PovrayOptions& options, Film& film) {
  checkRenderSettings(settings);
  checkPlacement(placement);
  film.requireFits(settings, "renderWithPovray");
  if (moving(placement, settings.rig)) return renderMovingWithPovray(scene, placement, settings, options, film);
  const PovrayJob job = exportPovray(scene, placement, settings);
  film.reduceSupersampled(runPovrayJob(job, options, options.threads), *makeCamera(settings.rig));
}

ImageRGBA renderWithPovray(const Scene& scene, const CameraPlacement& placement, const RenderSettings& settings,
                           const PovrayOptions& options) {
  Film film = filmFor(settings);
  renderWithPovray(scene, placement, settings, options, film);
  return film.takeImage();
}

}  // namespace omnicam
