#pragma once
// A texture as an opaque float image (alpha 1), as the exporters hand it to other engines: the glTF's
// PNG, the Blender job's linear EXR, POV-Ray's EXR with the material's colour multiplied in.
#include "image.h"
#include "texture.h"

namespace omnicam {

// Each texel's linear RGB times `tint` (per channel), alpha 1; rows as the texture holds them.
ImageRGBA opaqueImage(const Texture& texture, const Vec3f& tint = Vec3f::Ones());

}  // namespace omnicam
