#pragma once
// The multilayer layout's frame file (docs/dataset-format.md, "The multilayer layout"): one
// OpenEXR per frame and camera holding the colour and every AOV as named channels, and the
// frame's annotations as text attributes of its header, from which they are gathered into one
// file per camera. Written by the dataset runner, read by the dataset reader; each kind's
// channels and their type are its row's (output_kinds.h):
//
//   R, G, B, A                      colour, linear, premultiplied alpha   half
//   depth.Z                         metres along the ray from F'          float32 (exact)
//   normal.X, normal.Y, normal.Z    world frame, unit                     half
//   instance.I, semantic.I          instance and class ids                uint32
//   header "omnicam:landmarks", "omnicam:coco": the frame's annotations (JSON text)
#include <map>
#include <string>
#include <vector>

#include "aov_frame.h"
#include "exr_channels.h"
#include "image.h"
#include "frame_planes.h"
#include "output_kinds.h"

namespace omnicam {

// The header attribute holding annotation `kind`'s JSON text.
std::string multilayerAttribute(OutputKind kind);

// The frame file of `outputs`' images (colour always), each from its plane of `frame`, with
// `annotations` (JSON text by kind) in its header, compressed losslessly as asked.
std::vector<unsigned char> encodeMultilayerFrame(const std::string& path, const FramePlanes& frame,
                                                 const std::set<OutputKind>& outputs,
                                                 const std::map<OutputKind, std::string>& annotations,
                                                 FrameCompression compression);

}  // namespace omnicam
