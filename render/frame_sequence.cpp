#include "frame_sequence.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace omnicam {

size_t renderSequence(size_t count, size_t framesPerBatch, const std::function<CameraPlacement(size_t)>& placementOf,
                      const BatchRenderer& render, const FrameSink& deliver, const std::function<bool()>& stop) {
  const size_t batch = std::max<size_t>(1, framesPerBatch);
  size_t delivered = 0;
  for (size_t first = 0; first < count; first += batch) {
    if (stop && stop()) break;
    const size_t last = std::min(count, first + batch);
    std::vector<CameraPlacement> placements;
    for (size_t index = first; index < last; ++index) placements.push_back(placementOf(index));
    const auto start = std::chrono::steady_clock::now();
    std::vector<ImageRGBA> images = render(placements);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / static_cast<double>(last - first);
    if (images.size() != last - first) throw std::logic_error("renderSequence: a batch came back with the wrong number of frames");
    for (size_t k = 0; k < images.size(); ++k, ++delivered) deliver(first + k, std::move(images[k]), seconds);
  }
  return delivered;
}

size_t framesPerBatch(const Engine& engine) { return engine.capabilities().batches ? kFramesPerBatch : 1; }

}  // namespace omnicam
