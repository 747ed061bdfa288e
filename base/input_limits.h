#pragma once
// The documented bounds on every input (docs/conventions.md, "Ranges and limits"). Checked
// before any work starts, so a mistake gets exit 2 and one line, never an abort, a bad_alloc
// or minutes of swapping.
#include <cstdint>

namespace omnicam::limits {

// World coordinates of scene geometry, lights, landmarks and robot poses (metres). Embree
// traces in float: beyond 10 km a millimetre is no longer resolved.
inline constexpr double kMaxWorldCoordinate = 1e4;
// Lengths (radii, sizes) of scene primitives (metres) — at least a micrometre, at most 20 km.
inline constexpr double kMinLength = 1e-6;
inline constexpr double kMaxLength = 2e4;
// A texture's repeats across its surface (scale): beyond, float texture coordinates lose the
// texel, and the engines round them each their own way.
inline constexpr double kMaxTextureScale = 1e4;
// Robot yaw (degrees); any value in range is taken modulo 360.
inline constexpr double kMaxYawDeg = 1e6;

// Rig: ranges in which the mirror, the physical camera and POV-Ray's millimetre units are all
// well conditioned (POV-Ray and the fast renderer agree across them; tested).
inline constexpr double kMinRigHeight = 0.01, kMaxRigHeight = 100.0;  // F' above the floor (m)
inline constexpr double kMinMirrorK = 2.0, kMaxMirrorK = 100.0;        // k in (2, 100]
inline constexpr double kMinMirrorC = 1e-3, kMaxMirrorC = 1.0;         // focal distance (m)
inline constexpr int kMinImageSize = 8, kMaxImageSize = 16384;         // rendered image (px)
// The other mirror shapes (rig.mirror.shape): sizes (paraboloid h, sphere radius, cone rim
// radius) and the camera's distance below the design point, metres.
inline constexpr double kMinMirrorSize = 1e-3, kMaxMirrorSize = 1.0;
inline constexpr double kMaxCameraDistance = 10.0;
// The physical camera's mount (rig.camera): how far it may sit from its ideal pose. Generous for
// a misaligned rig, small enough that the mirror still fills a useful part of the image.
inline constexpr double kMaxCameraOffsetMm = 100.0;           // each axis
inline constexpr double kMaxCameraRotationDeg = 30.0;         // each axis
inline constexpr double kMaxDistortion = 10.0;                // |k1|, |k2|, |k3|
inline constexpr double kMaxTangentialDistortion = 1.0;       // |p1|, |p2|
inline constexpr double kMaxPrincipalPointOffsetPx = 4096.0;  // each axis
// The rig's tilt on the robot (rig.tilt_deg: roll, pitch), degrees each.
inline constexpr double kMaxRigTiltDeg = 30.0;

// Samples: spp = n² with n ≤ 32, and one frame's samples (size² × spp) fit well inside the
// 32-bit offsets the renderers index them with.
inline constexpr int kMaxSpp = 1024;
// Motion (docs/motion.md): the robot's speed and turn rate, a shutter's exposure, line time and
// fixed instants.
inline constexpr double kMaxSpeed = 100.0;                 // m/s
inline constexpr double kMaxYawRateDegPerS = 36000.0;      // 100 turns a second
inline constexpr double kMaxExposureS = 10.0;
inline constexpr double kMaxLineTimeUs = 1e5;
inline constexpr int kMaxTimeSamples = 256;
inline constexpr int64_t kMaxSamplesPerFrame = int64_t{1} << 28;

// Threads a render or a dataset run may be given (0: every core).
inline constexpr int kMaxThreads = 4096;

// How long an external renderer (POV-Ray, Blender) may take for one render (s): a week.
inline constexpr double kMaxTimeoutSeconds = 7 * 24 * 3600.0;

// Images read (textures, glTF images, images given to view/compare/rings): the header is
// checked against these before any pixel is decoded.
inline constexpr int kMaxImageDimension = 16384;
inline constexpr int64_t kMaxImagePixels = int64_t{1} << 27;  // e.g. 16384 × 8192

// Any file a scene pulls in (glTF, buffer): read whole, so bounded. JSON files (scenes, sidecars,
// rigs) are parsed into a tree about ten times their size: large meshes belong in glTF.
inline constexpr int64_t kMaxInputFileBytes = int64_t{1} << 30;
inline constexpr int64_t kMaxJsonFileBytes = int64_t{64} << 20;
// JSON nesting (objects and arrays, the root counts as 1) of every JSON input. omnicam's own
// formats need fewer than 10 levels; the bound keeps every recursive walk of a parsed tree
// (dump(), tinygltf's extras) far from the stack's end.
inline constexpr int kMaxJsonDepth = 64;
// Objects, triangles and vertices per scene (glTF included).
inline constexpr int64_t kMaxTriangles = int64_t{1} << 25;

}  // namespace omnicam::limits
