// path_convergence: what decides whether Cycles' kept frames are reused.
#include "path_convergence.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "blender_renderer.h"
#include "scratch_folder.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;

// Sets an environment variable for one scope; the previous value comes back after.
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const std::string& value) : name_(name) {
    if (const char* before = std::getenv(name)) before_ = before;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnvironment() { before_ ? (void)::setenv(name_, before_->c_str(), 1) : (void)::unsetenv(name_); }

 private:
  const char* name_;
  std::optional<std::string> before_;
};

// Frames Cycles rendered through another driver are other frames (the driver of 2026-12-03 hands
// Cycles linear textures): a kept frame is keyed by the driver's bytes, not its name.
TEST(CyclesFramesKey, ChangesWithTheBlenderDriversBytes) {
  const test_support::ScratchFolder dir("cycles_key");
  const Scene scene;
  const RenderSettings settings;
  const std::vector<RobotPose> poses{{1.0, 2.0, 30.0}};
  const std::string shipped = blenderDriverFile();
  const nlohmann::json base = [&] {
    const ScopedEnvironment driver("OMNICAM_BLENDER_DRIVER", shipped);
    return cyclesFramesKey(scene, poses, settings, 0);
  }();
  const fs::path copy = dir.path() / "copy.py", edited = dir.path() / "edited.py";
  fs::copy_file(shipped, copy);
  fs::copy_file(shipped, edited);
  std::ofstream(edited, std::ios::app) << "# another driver\n";
  {
    const ScopedEnvironment driver("OMNICAM_BLENDER_DRIVER", copy.string());
    EXPECT_EQ(cyclesFramesKey(scene, poses, settings, 0), base);  // the same bytes elsewhere
  }
  {
    const ScopedEnvironment driver("OMNICAM_BLENDER_DRIVER", edited.string());
    EXPECT_NE(cyclesFramesKey(scene, poses, settings, 0), base);
  }
  EXPECT_NE(cyclesFramesKey(scene, poses, settings, 1), cyclesFramesKey(scene, poses, settings, 0));
}

}  // namespace
}  // namespace omnicam
