#pragma once
// For the tests that prove output independent of the thread count: run work on exactly N TBB
// threads, also on a machine with fewer cores, and prove that N threads were there.
//
// A task_arena of N threads alone gets no more workers than the machine's cores − 1, and a
// global_control only caps: together they give N threads anywhere. Workers come when TBB wakes
// them — on a loaded machine often hundreds of milliseconds late, after a short job is done — so
// the work starts only once all N threads have met in the arena (a rendezvous that waits for
// them, however long the machine takes), with the others ready to take its tasks. Give it work
// of some tens of milliseconds: a job of a few milliseconds may still be done by one thread.
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <set>
#include <thread>

namespace omnicam {

// Runs `work` in an arena of `threads` threads, all of them running in the arena when it starts.
// Returns how many distinct threads met there: `threads`, or fewer if TBB never supplied them
// (given up after a minute, so that a test fails instead of hanging).
template <class Work>
int runOnThreads(int threads, const Work& work) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
  tbb::task_arena arena(threads);
  std::mutex mutex;
  std::set<std::thread::id> met;
  std::atomic<int> arrived{0};
  const auto giveUp = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  const std::thread::id caller = std::this_thread::get_id();
  arena.execute([&] {
    // One iteration per thread; each holds its thread until all have arrived, so no thread can
    // take two and every thread of the arena takes one. Then the caller's iteration runs the
    // work while the others, just released, look for tasks in the arena: the work's.
    tbb::parallel_for(
        0, threads, 1,
        [&](int) {
          {
            const std::lock_guard<std::mutex> lock(mutex);
            met.insert(std::this_thread::get_id());
          }
          ++arrived;
          while (arrived.load() < threads && std::chrono::steady_clock::now() < giveUp) std::this_thread::yield();
          if (std::this_thread::get_id() == caller) work();
        },
        tbb::simple_partitioner());
  });
  return static_cast<int>(met.size());
}

// A frame of `scene` at its start pose rendered on one thread and on four, each by its own
// renderer (so that its tables are built there too): the one-thread frame, once both were checked
// bit-identical and to have had their threads.
template <class Renderer, class Settings>
auto expectSameFrameOnOneAndFourThreads(const typename Renderer::SceneType& scene, const Settings& settings) {
  const Renderer rendererOne(scene), rendererFour(scene);
  decltype(rendererOne.render(scene.startPose, settings)) one, four;
  EXPECT_EQ(runOnThreads(1, [&] { one = rendererOne.render(scene.startPose, settings); }), 1);
  EXPECT_EQ(runOnThreads(4, [&] { four = rendererFour.render(scene.startPose, settings); }), 4);
  EXPECT_TRUE(one.pixels == four.pixels) << "the frame depends on the thread count";
  return one;
}

}  // namespace omnicam
