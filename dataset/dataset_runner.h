#pragma once
// Renders a dataset spec into a folder (docs/dataset-format.md), resumably: finished frames are
// listed in DIR/manifest.json with their files' SHA-256; a rerun of the same spec keeps every
// frame whose files still hash right, redoes the rest and removes temporaries left by a killed
// run. The result does not depend on where a run was interrupted.
#include <string>
#include <vector>

#include "dataset_folder.h"
#include "dataset_options.h"
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

struct DatasetRunResult {
  int frames = 0;    // in the spec (a shard's: in the shard)
  int kept = 0;      // verified and kept from an earlier run
  int rendered = 0;  // rendered by this run
  bool stopped = false;
  bool stoppedWaiting = false;  // stopped while another shard held shards/: nothing was looked at or written
  std::vector<std::string> notes;  // e.g. outputs a ground-truth engine does not write
};

// InputError for a bad spec or scene, a folder holding something else than this dataset
// (OtherDatasetError: another dataset, unless overwrite), or a link, special file or file in the
// way inside the folder (nothing inside is followed: docs/robustness.md); ExternalError from a
// ground-truth engine; OutputError if a file cannot be written.
DatasetRunResult runDataset(const DatasetSpec& spec, const DatasetRunOptions& options);

// What every shard of `count` of the dataset `header` (DatasetPlan::header) would check of DIR
// before rendering, checked once: InputError (OtherDatasetError for another dataset's manifest,
// another spec's or count's shards). For a Slurm submission, which would otherwise queue tasks
// that all refuse the folder. DIR may not exist yet.
void checkShardsMayJoin(const std::string& dir, const nlohmann::json& header, int count);

}  // namespace omnicam
