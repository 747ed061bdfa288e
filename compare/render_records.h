#pragma once
// Whether two renders show the same thing, by what their records say they were made from (an
// image's sidecar, a dataset's manifest). A difference here explains a low PSNR before any pixel
// does, and a PASS between renders of different poses would pass nothing.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "robot_pose.h"

namespace omnicam {

// Poses equal to within 1e-9 (m, m, degrees): records round-trip their doubles exactly, so
// anything more is another pose.
bool samePose(const RobotPose& a, const RobotPose& b);
std::string poseText(const RobotPose& pose);

// A setting a record holds: its name in notes, and where the record holds it (a JSON pointer).
struct RecordedSetting {
  const char* name;
  const char* pointer;
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

// Two images' sidecars, where both have one: InputError when they were rendered at different poses
// (a comparison of them would compare nothing), else recordedSettingNotes. A sidecar that cannot
// be read is a note: the images are still compared.
std::vector<std::string> sidecarNotes(const std::string& imageA, const std::string& imageB);

}  // namespace omnicam
