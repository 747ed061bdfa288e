#pragma once
// How a planned dataset's frames are rendered and written (dataset_plan.h): a window of frames
// at a time (a batch of poses per session for a batching engine), each frame's files encoded in
// memory, hashed and written from the frame's task, and each window listed in the manifest.
#include <vector>

#include "dataset_options.h"
#include "dataset_plan.h"
#include "manifest.h"
#include "safe_files.h"

namespace omnicam {

// Renders the frames `todo` of `plan` into `folder` (the dataset folder, opened once) window by window, listing each window's
// frames in `manifest` (written as `plan.range().manifestName`: the first window at once, then at
// most once a second) until done or options.stopRequested. options.onFrame counts from `done`
// of `total`, once per window. Returns the number of frames rendered.
int renderFrames(const DatasetPlan& plan, const SafeFolder& folder, const DatasetRunOptions& options,
                 const std::vector<int>& todo, DatasetManifest& manifest, int done, int total);

}  // namespace omnicam
