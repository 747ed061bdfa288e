#include "pose_sampler.h"

#include <algorithm>
#include <random>

#include "errors.h"
#include "free_space.h"
#include "number_format.h"
#include "triangulate.h"

namespace omnicam {

namespace {

// A uniform double in [0, 1) from 53 random bits: the same on every platform.
double unitDraw(std::mt19937_64& generator) { return static_cast<double>(generator() >> 11) * 0x1.0p-53; }

}  // namespace

std::vector<RobotPose> datasetPoses(const DatasetSpec& spec, const Scene& scene, double topHeight) {
  switch (spec.poseSource) {
    case PoseSource::List:
      return spec.poseList;
    case PoseSource::Path: {
      const CameraPath* path = scene.findPath(spec.pathName);
      if (!path)
        throw InputError(showPath(spec.file) + ": poses.path: scene " + showPath(scene.path) + " " + scene.noPathText(spec.pathName));
      // Timed waypoints are all kept: "frames" then caps the frames taken along them.
      if (spec.timing.kind != PathTiming::Kind::None) return path->poses;
      if (spec.pathFrames > static_cast<int>(path->poses.size()))
        throw InputError(showPath(spec.file) + ": poses.frames: path " + quote(spec.pathName) + " has only " +
                         std::to_string(path->poses.size()) + " poses");
      const size_t n = spec.pathFrames ? spec.pathFrames : path->poses.size();
      checkFrameCount(spec, n, "poses.path");  // a whole path is only counted now
      return {path->poses.begin(), path->poses.begin() + n};
    }
    case PoseSource::Random: {
      const RandomPoses& r = spec.random;
      std::mt19937_64 generator(r.seed);
      std::vector<RobotPose> poses;
      if (r.clearance == 0.0) {
        for (int k = 0; k < r.count; ++k) {
          const double x = r.xMin + (r.xMax - r.xMin) * unitDraw(generator);
          const double y = r.yMin + (r.yMax - r.yMin) * unitDraw(generator);
          poses.push_back({x, y, r.yawMinDeg + (r.yawMaxDeg - r.yawMinDeg) * unitDraw(generator)});
        }
        return poses;
      }
      const FreeSpace free(scene, topHeight, {r.xMin, r.xMax, r.yMin, r.yMax}, r.clearance);
      if (free.empty())
        throw InputError(showPath(spec.file) + ": poses.random: no free space with " + shortNumber(r.clearance) +
                         " m clearance in the region [" + shortNumber(r.xMin) + ", " + shortNumber(r.xMax) + "] x [" +
                         shortNumber(r.yMin) + ", " + shortNumber(r.yMax) + "] m");
      for (int k = 0; k < r.count; ++k) {
        const double pick = unitDraw(generator), a = unitDraw(generator), b = unitDraw(generator);
        const Vec2 p = free.pointFromDraws(pick, a, b);
        poses.push_back({p.x(), p.y(), r.yawMinDeg + (r.yawMaxDeg - r.yawMinDeg) * unitDraw(generator)});
      }
      return poses;
    }
  }
  return {};
}

}  // namespace omnicam
