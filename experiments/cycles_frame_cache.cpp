#include "cycles_frame_cache.h"

#include <cstdio>
#include <optional>

#include "blender_renderer.h"
#include "engines.h"
#include "errors.h"
#include "realistic_rendering.h"
#include "frame_sequence.h"
#include "input_limits.h"
#include "safe_files.h"
#include "sha256.h"

namespace omnicam {

namespace {

// outDir/cycles/, its frames named by the hash of what makes them (the header says what).
class CyclesFrameCache {
 public:
  CyclesFrameCache(const TextureRealismOptions& o, const Scene& textured) : folder_(o.outDir) {
    folder_.makeFolders("cycles");
    Sha256 key;
    key.update("omnicam texture-realism cycles frame v2\n");
    key.update(readFileInside(o.outDir, "arenas/hall-textured.json", limits::kMaxJsonFileBytes));
    key.update(sha256OfFile(o.labPhoto));
    // What Cycles is given (the job's files at the hall's origin, the driver): a changed exporter,
    // texture or driver renders anew.
    key.update(realisticJobDigest(textured, RobotPose{}, o.realistic, o.size, o.realistic.spp, 0));
    key.update(o.realistic.describe() + "\n" + o.realistic.tracing.toJson().dump() + "\n" +
               std::to_string(o.realistic.lampDiameter) + " " + std::to_string(o.realistic.spp) + " " + std::to_string(o.size));
    base_ = key.hex();
  }
  std::string nameOf(const RobotPose& pose) const {
    char text[160];
    std::snprintf(text, sizeof text, "%a %a %a", pose.x, pose.y, pose.yawDeg);
    return "cycles/" + sha256OfBytes(base_ + text).substr(0, 32) + ".exr";
  }
  std::optional<ImageRGBA> find(const RobotPose& pose) const {
    const std::string name = nameOf(pose);
    if (folder_.entry(name) != EntryKind::File) return std::nullopt;
    const std::string bytes = folder_.readFile(name, limits::kMaxInputFileBytes);
    return readImageFromMemory(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), folder_.path() + "/" + name);
  }
  ImageRGBA keep(const RobotPose& pose, const ImageRGBA& image) const {
    const std::string name = nameOf(pose);
    const std::vector<unsigned char> bytes = encodeImage(name, image);
    folder_.writeFile(name, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), Durability::Unsynced);
    return readImageFromMemory(bytes.data(), bytes.size(), folder_.path() + "/" + name);
  }

 private:
  SafeFolder folder_;
  std::string base_;
};

}  // namespace

std::vector<ImageRGBA> cyclesFrames(const TextureRealismOptions& o, const Scene& textured, const std::vector<RobotPose>& poses,
                                    const std::function<void()>& step, CyclesCount& count) {
  const CyclesFrameCache cache(o, textured);
  std::vector<ImageRGBA> frames(poses.size());
  std::vector<size_t> missing;
  for (size_t k = 0; k < poses.size(); ++k) {
    if (std::optional<ImageRGBA> kept = cache.find(poses[k])) {
      frames[k] = std::move(*kept);
      ++count.reused;
      step();
    } else {
      missing.push_back(k);
    }
  }
  renderSequence(
      missing.size(), kFramesPerBatch, [&](size_t m) { return CameraPlacement(poses[missing[m]]); },
      [&](const std::vector<CameraPlacement>& batch) {
        std::vector<RobotPose> batchPoses;
        for (const CameraPlacement& p : batch) batchPoses.push_back(p.robot());
        return renderRealistic(textured, batchPoses, o.realistic, o.size, o.realistic.spp, 0, o.blenderTimeoutSeconds);
      },
      [&](size_t m, ImageRGBA&& image, double) {
        frames[missing[m]] = cache.keep(poses[missing[m]], image);
        ++count.rendered;
        step();
      });
  return frames;
}

}  // namespace omnicam
