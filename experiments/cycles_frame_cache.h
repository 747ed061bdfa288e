#pragma once
// The texture-realism experiment's Cycles frames, kept between runs: outDir/cycles/ holds one
// linear EXR per frame, named by the hash of what the experiment chooses (the hall's file, the lab
// photo's bytes, the setup, size, spp, pose, and what Cycles is given — the Blender job's files and
// the driver's bytes, realisticJobDigest; not Blender's version: after changing that, delete the
// folder). A run that only adds test cameras or conditions renders
// none.
#include <functional>
#include <vector>

#include "image.h"
#include "placement.h"
#include "scene.h"
#include "texture_realism_results.h"

namespace omnicam {

struct CyclesCount {
  int rendered = 0, reused = 0;
};

// The linear Cycles frames of the textured hall (`textured`, written as outDir/arenas/
// hall-textured.json) at `poses`: kept ones read back, the others rendered by Blender (one session
// per batch of the missing poses) and kept. Every frame is used as decoded from its file, so runs
// with and without kept frames agree exactly. `step` after each frame.
std::vector<ImageRGBA> cyclesFrames(const TextureRealismOptions& o, const Scene& textured, const std::vector<RobotPose>& poses,
                                    const std::function<void()>& step, CyclesCount& count);

}  // namespace omnicam
