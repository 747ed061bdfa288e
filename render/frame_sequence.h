#pragma once
// A sequence of frames rendered in order and handed over one by one: the one batching loop of
// `render --path`, a dataset run and the experiments. An engine that batches (its capabilities'
// `batches`: Blender, one session per batch) gets up to `framesPerBatch` placements at a time; any
// other gets one, so each frame is delivered as soon as it is rendered.
#include <cstddef>
#include <functional>
#include <vector>

#include "engines.h"

namespace omnicam {

// Renders a batch of placements (an engine's renderMany, or a caller's own session).
using BatchRenderer = std::function<std::vector<ImageRGBA>(const std::vector<CameraPlacement>&)>;
// Receives frame `index`'s image and the seconds it took (its batch's time over its frames).
using FrameSink = std::function<void(size_t index, ImageRGBA&& image, double seconds)>;

// Frames [0, count): placementOf(index) each, rendered by `render` in batches of `framesPerBatch`
// (at least 1), delivered in order to `deliver`. `stop`, when set and true before a batch, ends
// the sequence early. Returns the frames delivered.
size_t renderSequence(size_t count, size_t framesPerBatch, const std::function<CameraPlacement(size_t)>& placementOf,
                      const BatchRenderer& render, const FrameSink& deliver, const std::function<bool()>& stop = {});

// The batch size an engine wants: kFramesPerBatch for one that batches, else 1.
size_t framesPerBatch(const Engine& engine);

}  // namespace omnicam
