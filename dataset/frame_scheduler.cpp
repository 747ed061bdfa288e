#include "frame_scheduler.h"

#include "interrupts.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include "frame_outputs.h"
#include "frame_sequence.h"
#include "memory_budget.h"
#include "safe_files.h"
#include "sha256.h"

namespace omnicam {

namespace {

// The manifest is rewritten at most this often while frames complete (and always after the
// first window of frames and at the end).
constexpr double kManifestIntervalSeconds = 1.0;
// Frames the fast engine renders at once: enough to keep every core busy between the serial
// parts (writing, the manifest), few enough that a stop request is honoured quickly.
constexpr int kConcurrentFrames = 8;

// Inside a cancelled parallel_for (a neighbouring frame's write failed) the engine's and the
// encoders' nested loops end early without an error, so what this frame holds may be
// incomplete: nothing of it is written. The neighbour's error ends the run.
void stopIfCancelled() {
  if (tbb::is_current_task_group_canceling()) throw std::runtime_error("frame cancelled");
}

// Frame `index`: every camera's files, encoded in memory, hashed and written. `rgb[c]`, if not
// null, holds camera c's image already rendered (a batching engine); `aovs` is reused memory.
FrameRecord renderFrame(const DatasetPlan& plan, const SafeFolder& dir, int index, std::vector<ImageRGBA*> rgb,
                        AovFrame& aovs) {
  const bool wantsAovs = plan.outputs().anyAov();
  const DatasetSpec& spec = plan.spec();
  // A calibration sequence's frame has its own scene (the target where it holds it).
  const std::unique_ptr<FrameWorld> world = plan.movesTarget() ? plan.frameWorld(index, /*withEngine=*/true, plan.rays() != nullptr) : nullptr;
  Engine& engine = world ? *world->engine : plan.engine();
  const Scene& scene = world ? world->scene : plan.scene();
  const RayScene* rays = world ? world->rays.get() : plan.rays();
  FrameRecord record{index, frameTimestampSeconds(index, spec.frameIntervalSeconds), plan.poses()[index], plan.velocities()[index], {},
                     plan.robotTilt(index)};
  for (size_t c = 0; c < plan.setups().size(); ++c) {
    const CameraSetup& setup = plan.setups()[c];
    const RenderSettings settings = spec.request.settings(plan.frameRig(index, c));
    const CameraPlacement placement = plan.placement(index, c);
    Film film = filmFor(settings, wantsAovs);
    if (wantsAovs) film.reuseAovPlanes(std::move(aovs));
    if (rgb[c]) film.setResolvedColour(std::move(*rgb[c]));
    else engine.render(placement, settings, film);
    // Seeded (and drawn, for a randomised camera) by frame and camera: a resumed or sharded run
    // records the same frames.
    std::optional<RecordingCamera> recording;
    if (spec.recording) {
      const uint64_t drawIndex = static_cast<uint64_t>(index) * plan.setups().size() + c;
      recording = spec.recording->draw(drawIndex);
      film.setResolvedColour(recordFrame(*recording, film.image(), drawIndex));
    }
    std::vector<EncodedFile> files =
        encodeFrameOutputs(scene, rays, settings, setup.camera->name, index, placement, film.image(), film.aovs(),
                           plan.outputs(), plan.ids().classOfInstance);
    if (wantsAovs) aovs = film.takeAovs();
    stopIfCancelled();
    CameraFrame cameraFrame{placement.footAt(0.0), {}, std::nullopt, std::nullopt};
    if (plan.vibrates()) cameraFrame.rig = settings.rig;
    if (spec.recording && spec.recording->randomised()) cameraFrame.recording = recording;
    for (EncodedFile& file : files) {
      dir.writeFile(file.relativePath, file.bytes, Durability::Unsynced);
      cameraFrame.files[outputName(file.kind)] = {file.relativePath, sha256OfBytes(file.bytes)};
    }
    record.cameras[setup.camera->name] = std::move(cameraFrame);
  }
  return record;
}

// A batching engine's images of frames todo[start, end), per camera.
std::vector<std::vector<ImageRGBA>> renderBatch(const DatasetPlan& plan, const std::vector<int>& todo, size_t start, size_t end) {
  std::vector<std::vector<ImageRGBA>> rgb(plan.setups().size());
  for (size_t c = 0; c < plan.setups().size(); ++c) {
    // One rig for the batch: batches of a vibrating or moving plan hold one frame (renderFrames).
    const RenderSettings settings = plan.spec().request.settings(plan.frameRig(todo[start], c));
    rgb[c].resize(end - start);
    renderSequence(
        end - start, end - start, [&](size_t k) { return plan.placement(todo[start + k], c); },
        [&](const std::vector<CameraPlacement>& placements) { return plan.engine().renderMany(placements, settings); },
        [&](size_t k, ImageRGBA&& image, double) { rgb[c][k] = std::move(image); });
  }
  return rgb;
}

}  // namespace

int renderFrames(const DatasetPlan& plan, const SafeFolder& folder, const DatasetRunOptions& options, const std::vector<int>& todo,
                 DatasetManifest& manifest, int done, int total) {
  const Engine& engine = plan.engine();
  auto stop = [&] { return options.stopRequested && options.stopRequested->load(); };
  // A batching engine (Blender) renders a camera's poses of a batch in one session; a concurrent
  // one (fast, exact) renders a window of frames at once, every frame itself in parallel too.
  const EngineCapabilities& can = engine.capabilities();
  // A calibration sequence's frames each have their own scene: rendered one by one, by renderFrame.
  const bool batches = can.batches && !plan.movesTarget();
  const size_t batch = batches          ? (plan.framesHaveOwnSettings() ? 1 : framesPerBatch(engine))
                       : can.concurrent ? static_cast<size_t>(concurrencyWithin(plan.frameBytes(), kConcurrentFrames,
                                                                                     "one frame of this dataset"))
                                             : 1;
  std::vector<AovFrame> aovSlots(std::min(batch, todo.size()));
  auto lastManifest = std::chrono::steady_clock::now();
  int rendered = 0;
  for (size_t start = 0; start < todo.size() && !stop(); start += batch) {
    const size_t end = std::min(todo.size(), start + batch);
    // A window's frames, each set once its files are written.
    std::vector<std::optional<FrameRecord>> records(end - start);
    try {
      std::vector<std::vector<ImageRGBA>> rgb = batches ? renderBatch(plan, todo, start, end)
                                                                 : std::vector<std::vector<ImageRGBA>>(plan.setups().size());
      auto renderOne = [&](size_t k) {
        std::vector<ImageRGBA*> given(plan.setups().size(), nullptr);
        for (size_t c = 0; c < plan.setups().size(); ++c)
          if (!rgb[c].empty()) given[c] = &rgb[c][k];
        records[k] = renderFrame(plan, folder, todo[start + k], given, aovSlots[k]);
      };
      if (can.concurrent) {
        tbb::parallel_for(size_t{0}, end - start, renderOne);
      } else {
        for (size_t k = 0; k < end - start; ++k) renderOne(k);
      }
    } catch (...) {
      // Whatever ended the run (an external renderer ended by SIGTERM or SIGINT, a full disk, a
      // file name taken by a folder): every frame whose files are written is listed, those of
      // this window that finished beside the failing one too, to resume from and for --overwrite
      // to remove. The manifest's own failure would hide the first error, which is the one to say.
      for (std::optional<FrameRecord>& record : records)
        if (record) manifest.frames[record->index] = std::move(*record);
      try {
        writeManifest(folder, manifest, plan.range().manifestName);
      } catch (const std::exception&) {
      }
      throw;
    }
    for (std::optional<FrameRecord>& record : records) {
      manifest.frames[record->index] = std::move(*record);
      ++rendered;
    }
    // Once per window: its frames finish together, and a count told frame by frame would show
    // rates that grow within the window at one instant.
    if (options.onFrame) options.onFrame(done + rendered, total);
    // The first finished window is listed at once, so that a run stopped early, however fast
    // the machine, leaves frames to resume from and a --status that shows them.
    const auto now = std::chrono::steady_clock::now();
    if (start == 0 || std::chrono::duration<double>(now - lastManifest).count() >= kManifestIntervalSeconds) {
      writeManifest(folder, manifest, plan.range().manifestName);
      lastManifest = now;
    }
  }
  return rendered;
}

}  // namespace omnicam
