#include "render_settings.h"

#include <cmath>

namespace omnicam {

const char* shadingName(Shading shading) { return shading == Shading::Lit ? "lit" : "unlit"; }

std::optional<Shading> parseShading(const std::string& name) {
  if (name == "unlit") return Shading::Unlit;
  if (name == "lit") return Shading::Lit;
  return std::nullopt;
}

std::optional<int> samplesPerAxis(int spp) {
  if (spp < 1) return std::nullopt;
  const int n = static_cast<int>(std::lround(std::sqrt(static_cast<double>(spp))));
  if (n * n != spp) return std::nullopt;
  return n;
}

}  // namespace omnicam
