#pragma once
// The demo's "glance" section, what the report opens with: a frame that fills the mirror (the
// field inside the thesis' hall, walls carrying a real photo) from the fast renderer beside
// POV-Ray's ground truth, and the start-pose section's ring errors. Its hall and pose are also
// the light and texture-realism sections'.
#include <string>
#include <vector>

#include "demo_start_pose.h"
#include "robot_pose.h"

namespace omnicam::cli {

// The pose sees both goals, the centre circle and the beacons.
inline const RobotPose kGlancePose{0.0, -0.7, 90.0};

std::string hallScenePath(const std::string& out);

// The textured hall that the glance, light and texture-realism sections share, written once
// before any section runs.
void writeDemoHall(const std::string& out, const std::string& fieldScene);

// Writes glance_*.png into `out`; returns the section's HTML, citing `rings`.
std::string demoGlance(const std::string& out, int spp, bool povray, const std::vector<RingSummary>& rings);

}  // namespace omnicam::cli
