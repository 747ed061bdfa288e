#pragma once
// The fast renderer's modes and their options, apart from the renderer (fastrender/
// cubemap_renderer.h implements them) so that the engine interface (render/engines.h) can name
// them without including a renderer.
#include <optional>
#include <string>

namespace omnicam {

enum class OmniMode { Exact, CubeMap, ThesisMesh };
// "exact", "cubemap", "thesis-mesh": the names requests, sidecars and manifests use.
const char* omniModeName(OmniMode mode);
std::optional<OmniMode> omniModeNamed(const std::string& name);

struct CubeMapOptions {
  OmniMode mode = OmniMode::CubeMap;
  int faces = 6;         // 5 (thesis) or 6
  int faceSize = 512;    // texels per face edge
  int polygons = 1024;   // thesis-mesh: 16, 64, 256 or 1024
  bool rasterize = true; // unlit faces by rasterisation (else, and for lit: one ray per used texel)
};

}  // namespace omnicam
