#pragma once
// Whether two renders show the same thing, by what their records say they were made from (an
// image's sidecar, a dataset's manifest). A difference here explains a low PSNR before any pixel
// does, and a PASS between renders of different poses would pass nothing.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "robot_pose.h"

namespace omnicam {

// How far apart two poses are: on the floor, and in heading (0° and 360° one heading).
struct PoseDifference {
  double metres = 0.0, degrees = 0.0;
};
PoseDifference poseDifference(const RobotPose& a, const RobotPose& b);
// Poses equal to within 1e-9 (m, degrees): records round-trip their doubles exactly, so anything
// more is another pose.
bool samePose(const RobotPose& a, const RobotPose& b);
std::string poseText(const RobotPose& pose);
std::string poseDifferenceText(const PoseDifference& difference);  // "3.4e-03 mm and 0° apart"

// Poses a pose typed from a printed one (6 digits) can differ by: no image tells them apart.
inline constexpr double kSamePoseToTheEyeMetres = 1e-4, kSamePoseToTheEyeDegrees = 1e-3;

// A setting a record holds: its name in notes, where the record holds it (a JSON pointer), and
// what a record without it holds (one written before the setting was recorded).
struct RecordedSetting {
  const char* name;
  const char* pointer;
  nlohmann::json absent = nullptr;
};
// What an image's sidecar and a dataset's manifest hold of how they were rendered, beyond the pose
// (and, for datasets, the rigs, which are compared camera by camera): the scene's bytes and the
// files it reads, shading, spp, mode, a recording camera, … Engines are left out: comparing one
// engine's render with another's is what `compare` is for.
const std::vector<RecordedSetting>& sidecarSettings();
const std::vector<RecordedSetting>& manifestSettings();

// One note per setting whose values differ between the records `a` and `b` ("none" where a record
// lacks it): "spp differs: A 16, B 4"; an object by its differing members ("rig differs in
// mirror.k, image.size").
std::vector<std::string> recordedSettingNotes(const nlohmann::json& a, const nlohmann::json& b,
                                              const std::vector<RecordedSetting>& settings);

// What two images' sidecars say, where both have one: the pose each was rendered at, and the
// other settings they record differently (recordedSettingNotes). A sidecar that cannot be read is
// a note: the images are still compared.
struct SidecarComparison {
  std::vector<std::string> notes;
  std::string poses;        // "A (x, y, yaw°), B (…) (… apart)" when the poses are not the same; else empty
  bool posesApart = false;  // beyond what a typed pose differs by: images of another place
};
SidecarComparison compareSidecars(const std::string& imageA, const std::string& imageB);

}  // namespace omnicam
