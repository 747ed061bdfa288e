#pragma once
// A calibration sequence (docs/calibration.md, "Calibration sequences"): a scene's calibration
// target held in front of a still robot's camera at one pose per frame, as a person waving a
// board would, and what each frame shows of it: every corner's exact raster point through the
// camera's own project() with why a hidden one is hidden. `omnicam dataset` renders the frames and
// writes these files beside them.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "board_poses.h"
#include "calibration_sequence_spec.h"
#include "imaged_corners.h"
#include "scene.h"

namespace omnicam {

// Index of the scene's calibration target named `name`; -1 when there is none.
int findCalibrationTarget(const Scene& scene, const std::string& name);

// Moves calibration target `target` and its board (a quad of scene.objects) to worldFromTarget.
void placeCalibrationTarget(Scene& scene, int target, const Rigid& worldFromTarget);

// The board's pose of every frame in the viewpoint frame of `camera` (the first camera of the
// robot, at worldFromViewpoint): the listed ones, or `random->count` drawn ones, each board's
// outline (its margin included) clearing the floor (z = 0) by boardClearsFloor. InputError, its field under calibration.poses ("random: …",
// "list[3]: …"), when too few can be drawn or a listed board goes through the floor.
std::vector<Rigid> sequenceBoardPoses(const CalibrationSequenceSpec& spec, const Camera& camera, const Rigid& worldFromViewpoint,
                                      const CalibrationTarget& target);

// One frame of one camera in <camera>/calibration/corners.json.
nlohmann::json cornersFrameJson(int frame, const Rigid& viewpointFromTarget, const std::vector<ImagedCorner>& corners);

// A frame of corners.json read back: the board's pose and its seen corners (exact raster points).
struct CornersFrame {
  int frame = 0;
  Rigid viewpointFromTarget = Rigid::Identity();
  std::vector<ImagedCorner> seen;
};
// Every frame of a corners.json's text, strictly (a file of a dataset someone else may have
// written): InputError naming `source` and the field. Corner indices must lie below `corners`, the
// target's count, each once a frame; a seen corner's raster point inside the width × height image.
std::vector<CornersFrame> cornersFramesFromJson(const std::string& text, const std::string& source, int corners, int width,
                                                int height);

}  // namespace omnicam
