#include "omni_mode.h"

namespace omnicam {

const char* omniModeName(OmniMode mode) {
  switch (mode) {
    case OmniMode::Exact: return "exact";
    case OmniMode::CubeMap: return "cubemap";
    case OmniMode::ThesisMesh: return "thesis-mesh";
  }
  return "?";
}

std::optional<OmniMode> omniModeNamed(const std::string& name) {
  for (OmniMode mode : {OmniMode::Exact, OmniMode::CubeMap, OmniMode::ThesisMesh})
    if (name == omniModeName(mode)) return mode;
  return std::nullopt;
}

}  // namespace omnicam
