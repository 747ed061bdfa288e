#pragma once
// Renders a dataset spec into a folder (docs/dataset-format.md), resumably: finished frames are
// listed in DIR/manifest.json with their files' SHA-256; a rerun of the same spec keeps every
// frame whose files still hash right, redoes the rest and removes temporaries left by a killed
// run. The result does not depend on where a run was interrupted.
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "dataset_folder.h"
#include "dataset_spec.h"
#include "errors.h"
#include "manifest.h"

namespace omnicam {

// The folder holds a dataset made from another spec, scene or engine; overwriting
// (DatasetRunOptions::overwrite) would replace it.
class OtherDatasetError : public InputError {
 public:
  using InputError::InputError;
};

struct DatasetRunOptions {
  std::string dir;
  // Replace the dataset in the folder (another spec's, or this one's from scratch): only the
  // files its manifest lists in the dataset layout are removed, and its camera folders if that
  // leaves them empty. A folder without a readable manifest is never overwritten.
  bool overwrite = false;
  // Shard `shardIndex` of `shardCount` (dataset_shards.h): frames [F·i/n, F·(i+1)/n) only, listed
  // in DIR/shards/shard-i-of-n.json instead of DIR/manifest.json, so that shards on different
  // machines can fill one shared folder at once (a Slurm array of one task is shard 0 of 1).
  // shardCount 0: the whole dataset, listed in DIR/manifest.json.
  int shardIndex = 0, shardCount = 0;
  // Threads for the whole run (TBB's, POV-Ray's Work_Threads, Blender's -t); 0: every core. Under
  // Slurm, the cores the task was given (docs/cluster.md).
  int threads = 0;
  // Called once before rendering: frames kept from an earlier run, of `total`.
  std::function<void(int kept, int total)> onStart;
  // Called after every finished frame: frames done (kept + rendered) of `total`.
  std::function<void(int done, int total)> onFrame;
  // Checked between frames: set (e.g. by SIGINT) to stop after the frame in progress.
  const std::atomic<bool>* stopRequested = nullptr;
};

struct DatasetRunResult {
  int frames = 0;    // in the spec (a shard's: in the shard)
  int kept = 0;      // verified and kept from an earlier run
  int rendered = 0;  // rendered by this run
  bool stopped = false;
  std::vector<std::string> notes;  // e.g. outputs a ground-truth engine does not write
};

// InputError for a bad spec or scene, a folder holding something else than this dataset
// (OtherDatasetError: another dataset, unless overwrite), or a link, special file or file in the
// way inside the folder (nothing inside is followed: docs/robustness.md); ExternalError from a
// ground-truth engine; OutputError if a file cannot be written.
DatasetRunResult runDataset(const DatasetSpec& spec, const DatasetRunOptions& options);

}  // namespace omnicam
