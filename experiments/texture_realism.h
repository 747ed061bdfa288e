#pragma once
// The thesis' validation experiment (Chapter 4), reproduced with ground truth from projection:
// colour-histogram classifiers trained on rendered frames (labels from instance masks), tested
// on the 100 thesis-loop frames of three arenas, and an EKF driven by the detections.
//
//   train sets  plain           fast lit renders of the plain hall, random poses
//               random_textures fast lit renders of halls whose walls carry random photos
//               path            fast path-traced renders of the textured hall (physically based
//                               light, denoised: docs/path-tracing.md), random poses
//               realistic       the realistic frames' setup (below) at those random poses
//               path_recorded,  the path (plain) frames, each recorded through several cameras
//               plain_recorded  drawn from the presets' ranges (domain randomisation)
//               path_recorded_without_<stage>  the same with one stage held neutral (ablation)
//   test sets   plain           fast lit renders of the plain hall along thesis-loop
//               textured        the same in the hall textured with the "lab" photo
//               path            fast path-traced renders of the textured hall along thesis-loop
//               realistic       Blender Cycles (path traced, lit) renders of the textured hall
//                               (realistic_rendering.h: lamps of real size, converged to the
//                               measured ≥ 35 dB) through the recording-camera model
//                               (recording_camera.h) — our stand-in for the thesis' real ISLA
//                               images, which we do not have
//               realistic_camera_<k>  the same Cycles frames through the k-th --test-camera
//   conditions  plain_to_plain, plain_to_textured, plain_to_realistic (the thesis' three) and
//               random_textures_to_realistic (the question its result begs), and
//               path_to_realistic, realistic_to_path (does physically based light in training
//               carry over to Cycles' frames, and back?), and the recorded sets against the
//               realistic frames and each test camera (do frames through drawn cameras carry over?)
#include <functional>
#include <string>
#include <vector>

#include "beacon_detector.h"
#include "experiment_progress.h"
#include "realistic_rendering.h"
#include "recording_camera.h"
#include "texture_realism_results.h"

namespace omnicam {

// Runs everything and writes outDir/results.json, data/ (CSV and JSON for the figures),
// arenas/, frames/ (one frame per test set with detections drawn) and report.html. Figures are
// drawn by `plotScript` (python3 + matplotlib) from data/ into figures/; an empty path skips
// them. InputError for bad options, OutputError if something cannot be written.
TextureRealismResults runTextureRealism(const TextureRealismOptions& options, const std::string& plotScript,
                                        const ExperimentProgress& progress);

// One frame for the demo: classifiers trained on `trainFrames` plain-hall frames, then one
// textured-hall frame (the lab photo's walls) along thesis-loop with its detections drawn (green
// crosses: visible beacons; yellow circles: correct detections; red: wrong). Writes the hall
// into `arenaDir`.
struct DetectionFrame {
  ImageRGBA drawn;
  int poseIndex = 0, visibleBeacons = 0, truePositives = 0, falsePositives = 0;
};
DetectionFrame texturedHallDetectionFrame(const std::string& fieldScene, const std::string& labPhoto,
                                          const std::string& arenaDir, int size, int spp, int trainFrames);

}  // namespace omnicam
