#pragma once
// A dataset rendered in shards (`omnicam dataset SPEC -o DIR --shard I/N`, by hand or as a Slurm
// job array): shard I renders frames [F·I/N, F·(I+1)/N) into the shared DIR and lists them in
// DIR/shards/shard-I-of-N.json; merging writes DIR/manifest.json from every shard's manifest.
// A merged dataset is the same as one rendered in one go (fast engine: byte for byte).
#include <optional>
#include <string>
#include <vector>

#include "held_name.h"
#include "manifest.h"
#include "safe_files.h"

namespace omnicam {

struct ShardState {
  int index = 0;
  bool started = false;   // its manifest exists
  int frames = 0;         // in its range
  int finished = 0;       // listed in its manifest
  bool complete = false;  // every frame finished, and (when checked) every file hashes right
  bool running = false;   // a run on this machine renders it now (holdShard)
  std::vector<std::string> problems;  // from checking the files
};

// Every shard of `count` (1 … kMaxShards, else InputError); `checkFiles` re-hashes each finished shard's files (what a resubmission
// needs to know: a corrupt shard is rendered again).
std::vector<ShardState> shardStates(const std::string& dir, int count, bool checkFiles);

// A run of shard `index` of `count` into DIR (an existing folder) holds this while it renders:
// nullopt when another run on this machine holds it — the same shard is rendered there now. Two
// runs of one shard would render the same frames and each replace the other's manifest.
std::optional<HeldName> holdShard(const std::string& dir, int index, int count);

// The shard counts (1 … kMaxShards) that have manifests in DIR/shards/ (normally one).
std::vector<int> shardCountsIn(const std::string& dir);

// Removes DIR/shards/shard-I-of-N.json of the dataset `header` (each that reads as one of its
// manifests; anything else stays), then shards/ if it is left empty: a dataset replaced by a run
// in one go leaves no shards that would make its folder look half sharded.
void removeShardManifestsOf(const SafeFolder& dir, const nlohmann::json& header);

// What finishes a folder of shards not merged: merging them when every shard of a count is
// finished, else running the shards left (one line, for messages).
std::string unmergedShardsNextStep(const std::string& dir);

// A dataset's manifest.json, for reading the dataset: in a folder of shards not merged yet, the
// message says what finishes it (unmergedShardsNextStep), not only that the manifest is missing.
DatasetManifest readMergedDatasetManifest(const SafeFolder& dir);

// Why a run of the dataset `header` as a shard of `count` may not write into DIR beside the
// shards there: shards of another count, or of another dataset (naming what differs). Empty if
// it may (no shards, or only this dataset's of this count).
std::string shardsConflict(const std::string& dir, const nlohmann::json& header, int count);
// The count part of that alone (a Slurm submission knows no header yet): "" when every shard in
// DIR is of `count`.
std::string shardCountConflict(const std::string& dir, int count);

struct MergeResult {
  int frames = 0, finished = 0;
  int started = 0;  // shards with a manifest, of the count merged
  std::vector<int> incompleteShards;
  bool complete() const { return incompleteShards.empty() && finished == frames; }
};

// Writes DIR/manifest.json from the shard manifests (complete or not: what is finished is listed)
// and removes temporaries killed shards left behind. InputError if no shard has started, or the
// shards (or an existing manifest) come from different specs, scenes or engines.
MergeResult mergeDatasetShards(const std::string& dir, int count);

}  // namespace omnicam
