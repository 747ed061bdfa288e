#pragma once
// What the demo's sections share: numbers printed into captions, and one view rendered by every
// engine with fast's difference from each ground truth.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "image_compare.h"
#include "render_settings.h"
#include "scene.h"

namespace omnicam::cli {

// printf's `fmt` with up to four numbers; at most 511 characters.
std::string formatNumbers(const char* fmt, double a, double b = 0, double c = 0, double d = 0);

struct EngineFigures {
  std::string html;                                          // the renders' figures, then the differences'
  std::vector<std::pair<std::string, CompareResult>> vsFast;  // engine, fast vs engine
  double fastSeconds = 0.0;
};

// Renders `scene` at `pose` with every engine (engines[0] is "fast"): `<stem>_<engine>.png`, then
// for each ground truth `<stem>_diff_<engine>.png` (|fast − engine|, white = 0.01) and its
// comparison with fast. `caveat(engine)`: HTML appended to that comparison's caption.
EngineFigures renderAndCompare(const std::string& out, const std::string& stem, const std::string& label,
                               const Scene& scene, const RobotPose& pose, const RenderSettings& settings,
                               const std::vector<std::string>& engines,
                               const std::function<std::string(const std::string&)>& caveat);

}  // namespace omnicam::cli
