// `omnicam ros SPEC`: the live ROS 1 sensor (ros/live_sensor.h, docs/ros.md).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "atomic_file.h"
#include "cli_util.h"
#include "commands.h"
#include "dataset_spec.h"
#include "errors.h"
#include "interrupts.h"
#include "live_sensor.h"
#include "ros_transport.h"
#include "number_format.h"

namespace omnicam::cli {

namespace {

struct RosArgs {
  std::string spec;
  LiveSensorOptions options;
};

// A ROS node's own arguments (`from:=to` remappings, roslaunch's `__name:=` and `__log:=`) go to
// ROS; anything else is a mistake. Private parameters (`_name:=value`) too: the node reads none,
// and roscpp would wait for a master without limit to set them.
std::vector<std::string> rosArgumentsOf(const std::vector<std::string>& extras) {
  for (const std::string& extra : extras) {
    if (extra.find(":=") == std::string::npos || extra.rfind(":=", 0) == 0)
      throw InputError("ros: unexpected argument " + quote(extra) + " (ROS arguments are from:=to)");
    if (extra.rfind('_', 0) == 0 && extra.rfind("__", 0) != 0)
      throw InputError("ros: " + quote(extra) + ": the node takes no private parameters (its settings are flags and the spec)");
    // The node's name and namespace: an empty one would be roscpp's default, a bad one refused by
    // roscpp in its own words that do not say which argument.
    for (const std::string own : {"__name:=", "__ns:="}) {
      if (extra.rfind(own, 0) != 0) continue;
      const std::string value = extra.substr(own.size());
      if (value.empty()) throw InputError("ros: " + quote(extra) + ": give a name, or leave " + own + " out");
      if (const std::string why = ros1::invalidGraphName(value); !why.empty()) throw InputError("ros: " + quote(extra) + ": " + why);
    }
  }
  return extras;
}

// roslaunch starts its nodes in ROS_HOME (~/.ros), not in the folder it was started from: a
// relative path there would read a spec or write a bag somewhere the user did not mean.
void refuseRelativePathsUnderRoslaunch(const RosArgs& a, const std::vector<std::string>& extras) {
  const bool roslaunched = std::any_of(extras.begin(), extras.end(), [](const std::string& e) { return e.rfind("__log:=", 0) == 0; });
  if (!roslaunched) return;
  const auto refuse = [](const std::string& what, const std::string& path, const std::string& launchArgument) {
    if (std::filesystem::path(path).is_absolute()) return;
    throw InputError("ros: " + what + showPath(path) + " is a relative path, but roslaunch starts its nodes in " +
                     showPath(std::filesystem::current_path().string()) + ", not where it was started: give an absolute path (" +
                     launchArgument + ":=$PWD/" + showPath(path) + ")");
  };
  refuse("", a.spec, "spec");
  if (!a.options.recordBag.empty()) refuse("--record ", a.options.recordBag, "record");
}

void runRos(RosArgs a, const CLI::App& cmd, const std::vector<std::string>& extras) {
  a.options.rosArguments = rosArgumentsOf(extras);
  refuseRelativePathsUnderRoslaunch(a, extras);
  // An empty value would silently mean the flag's absence (odometry, no bag).
  if (cmd.count("--tf") && a.options.tfParent.empty()) throw InputError("--tf: give a frame (map or odom)");
  if (cmd.count("--record") && a.options.recordBag.empty()) throw InputError("--record: give the new bag's file name");
  if (cmd.count("--max-pose-age") && a.options.rateHz == 0)
    throw InputError("--max-pose-age: does nothing with --rate 0 (each pose is rendered as it comes): give a rate above 0, or "
                     "leave --max-pose-age out");
  const DatasetSpec spec = loadDatasetSpec(a.spec);
  if (!a.options.recordBag.empty()) {
    checkOutputFile(a.options.recordBag, "--record");
    const auto status = std::filesystem::symlink_status(a.options.recordBag);
    if (std::filesystem::is_symlink(status))
      throw InputError("--record: " + showPath(a.options.recordBag) + ": is a symbolic link (a bag is written as a new file, never through one)");
    if (std::filesystem::exists(status))
      throw InputError("--record: " + showPath(a.options.recordBag) + ": exists already (a bag is never overwritten)");
  }
  stopGracefullyOnInterrupt();  // SIGINT/SIGTERM end the loop between frames
  a.options.onWaitingForMaster = [](const std::string& uri) {
    std::printf("ros: waiting for a ROS master at %s (start one with `roscore`, or set ROS_MASTER_URI)\n", uri.c_str());
    std::fflush(stdout);
  };
  a.options.onNotes = [](const std::vector<std::string>& notes) {
    for (const std::string& note : notes) std::fprintf(stderr, "omnicam: note: %s\n", note.c_str());
  };
  const LiveSensorReport report = runLiveSensor(spec, a.options, [&](const LiveSensorTopics& used) {
    const std::string from = a.options.tfParent.empty() ? used.odometry
                                                        : "tf (" + a.options.baseFrame + " in " + a.options.tfParent + ")";
    std::string topics;
    for (const std::string& topic : used.images) topics += (topics.empty() ? "" : ", ") + topic;
    std::printf("ros: ready: poses from %s, images on %s\n", from.c_str(), topics.c_str());
    std::fflush(stdout);
  });
  if (report.stoppedWaitingForMaster) {
    std::printf("ros: stopped while waiting for the ROS master: no pose rendered\n");
    return;
  }
  if (!report.frameGivenUp.empty())
    std::printf("ros: %s: the frame in progress was given up%s\n", report.frameGivenUp.c_str(),
                a.options.recordBag.empty() ? "" : "; the bag holds the frames before it");
  // At a fixed rate a frame is a tick's (a pose carried to it), not a pose as it came.
  const std::string rendered =
      a.options.rateHz > 0 ? countOf(report.rendered, "frame") + " rendered at ticks" : countOf(report.rendered, "pose") + " rendered";
  std::printf("ros: %s, %lld dropped for newer ones, %lld refused, %s", rendered.c_str(),
              static_cast<long long>(report.dropped), static_cast<long long>(report.refused),
              countOf(report.newMasters, "new master").c_str());
  if (a.options.rateHz > 0 && a.options.tfParent.empty())  // --max-pose-age is odometry's
    std::printf(", %s skipped (no pose within --max-pose-age)", countOf(report.skippedTicks, "tick").c_str());
  std::printf("\n");
  if (report.shutDownByRos)
    throw ExternalError("ros: the ROS master shut this node down: another node registered under its name (give each node its own "
                        "with __name:=), or rosnode kill");
}

}  // namespace

void addRosCommand(CLI::App& app) {
  auto args = std::make_shared<RosArgs>();
  CLI::App* cmd = app.add_subcommand("ros", "Run as a live ROS 1 camera: render the spec's cameras for each pose ROS sends (odometry or tf)");
  cmd->add_option("spec", args->spec, "Dataset spec JSON: the scene, the cameras and their mounts, the settings")->required();
  cmd->add_option("--odom", args->options.odometryTopic, "nav_msgs/Odometry topic of the robot's poses (default /odom)");
  cmd->add_option("--robot", args->options.robot, "Namespace of the image topics: /ROBOT/CAMERA/image_raw (default robot)");
  cmd->add_option("--tf", args->options.tfParent,
                  "Take poses from tf instead of odometry: the base frame in this frame (e.g. map or odom)")
      ->excludes(cmd->get_option("--odom"));
  cmd->add_option("--base-frame", args->options.baseFrame, "The robot's tf frame, parent of ROBOT/CAMERA (default base_link)");
  cmd->add_option("--record", args->options.recordBag,
                  "Also write the images, camera_info and transforms into this new ROS bag (complete when the node stops)");
  cmd->add_option("--frames", args->options.frames, "Stop after this many poses (default: run until SIGINT or SIGTERM)")
      ->check(integerIn(0, INT32_MAX));
  cmd->add_option("--rate", args->options.rateHz,
                  "Render at this rate (Hz, on ROS time: /clock's under /use_sim_time) with the newest pose, "
                  "stamped with each tick (default 0: each pose as it comes)")
      ->check(numberIn(0, 1000));
  cmd->add_option("--max-pose-age", args->options.maxPoseAgeSeconds,
                  "With --rate and odometry: carry the newest pose to a tick at most this many seconds (default 0.5)")
      ->check(numberIn(0, 60, true))
      ->needs(cmd->get_option("--rate"))
      ->excludes(cmd->get_option("--tf"));
  cmd->allow_extras();  // ROS's own from:=to arguments (remappings, roslaunch's __name:= and __log:=)
  cmd->footer("ROS arguments: from:=to remaps a topic by its full name (/robot/front/image_raw:=/camera/image); "
              "__name:= names the node, __log:= its log, as roslaunch passes them.");
  cmd->callback([args, cmd] { runRos(*args, *cmd, cmd->remaining()); });
}

}  // namespace omnicam::cli
