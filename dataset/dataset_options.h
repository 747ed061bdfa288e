#pragma once
// How one run of a dataset spec goes: the folder, overwriting, the shard, threads, progress and
// stopping (dataset_runner.h).
#include <atomic>
#include <functional>
#include <string>
#include <vector>

namespace omnicam {

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
  // Called once before rendering, the folder checked: what the user should know of the run
  // (DatasetPlan::notes), then the frames kept from an earlier run, of `total`.
  std::function<void(const std::vector<std::string>& notes)> onNotes;
  std::function<void(int kept, int total)> onStart;
  // Called as frames finish: frames done (kept + rendered) of `total`. A window's frames (8 with
  // the fast engine, a batch with Blender) finish together, so `done` grows by up to that many.
  std::function<void(int done, int total)> onFrame;
  // Checked between frames: set (e.g. by SIGINT) to stop after the frame in progress; a shard
  // waiting for shards/ stops waiting.
  const std::atomic<bool>* stopRequested = nullptr;
  // Called once when a shard must wait for another shard's check of the folder (it holds shards/
  // for the moment between its check and its first manifest).
  std::function<void()> onWaitForShards;
};

}  // namespace omnicam
