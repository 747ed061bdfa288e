#include "demo_texture_realism.h"

#include <cstdio>
#include <sstream>

#include "hall_arena.h"
#include "image.h"
#include "texture_realism.h"

namespace omnicam::cli {

// The texture-realism experiment in one frame: the hall with real-photo walls, beacons found by
// classifiers trained on the plain hall (docs/experiments.md).
std::string demoTexturedHall(const std::string& out, const std::string& scenePath) {
  std::printf("demo: textured hall, colour-histogram beacon detection\n");
  const DetectionFrame frame = texturedHallDetectionFrame(
      scenePath, kLabPhoto, out + "/hall", 360, 4, 8);
  writeImageAtomic(out + "/hall_detections.png", frame.drawn);
  std::printf("demo: textured hall frame %d: %d of %d visible beacons found, %d false positives\n", frame.poseIndex,
              frame.truePositives, frame.visibleBeacons, frame.falsePositives);
  std::ostringstream html;
  html << "<h2>Texture realism (<code>omnicam experiment texture-realism</code>)</h2><p>The field inside the "
          "thesis' hall, walls textured with a planar projection of a real 360&deg; photo (<code>omnicam arena "
          "hall --photo</code>). Colour-histogram classifiers trained on 8 frames of the <i>plain</i> hall (labels "
          "from instance masks) find "
       << frame.truePositives << " of " << frame.visibleBeacons << " visible beacons in thesis-loop frame "
       << frame.poseIndex << ", with " << frame.falsePositives
       << " false positives. Green crosses: projected beacons; yellow circles: correct detections; red: wrong.</p>"
          "<figure><img src=\"hall_detections.png\" width=\"360\"></figure>\n";
  return html.str();
}

}  // namespace omnicam::cli
