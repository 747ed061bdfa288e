#pragma once
// `omnicam ros SPEC` (issue #49): the cameras of a dataset spec on a robot that ROS drives, as a
// live ROS 1 sensor. Each nav_msgs/Odometry message is a pose (its twist the robot's velocity,
// so motion blur and rolling shutter follow the robot as in datasets), or each tf transform that
// moves the robot's base frame. The newest pose is
// rendered off the ROS thread and every camera's image published on /<robot>/<camera>/image_raw
// (rgb8, the codes a dataset's PNG holds), stamped with the pose's stamp: the exposure start.
// Poses that arrive while a frame renders replace each other; the replaced ones are dropped,
// counted and reported on /diagnostics, as are refused poses (problemWith). Each camera's frame
// (ROBOT/CAMERA: the intrinsics files' camera frame, as poses.tum) is on /tf_static under the
// robot's base frame, through the one frame chain (placement.h), the robot's tilt included.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "dataset_spec.h"
#include "motion.h"
#include "robot_pose.h"
#include "ros_messages.h"

namespace omnicam {

struct LiveSensorOptions {
  std::string odometryTopic = "/odom";
  // Poses from tf instead: the base frame in this frame (map or odom), whenever /tf moves the
  // base frame. tf has no twist: the robot is still over each exposure.
  std::string tfParent;
  std::string robot = "robot";  // the topics' namespace; frames are ROBOT/CAMERA
  std::string baseFrame = "base_link";  // the robot's frame, parent of the cameras' on /tf_static
  int64_t frames = 0;           // stop after this many rendered poses; 0: until SIGINT or SIGTERM
  // 0: render each pose as it comes. Otherwise render at this rate, on ROS time's grid of
  // round(10⁹/rate) ns (the /clock's under simulated time), each frame stamped with its tick: from
  // odometry, the newest pose carried to the tick with its twist (the dataset's motion); from
  // tf, the tree's pose at the tick, once tf has it.
  double rateHz = 0.0;
  // At a fixed rate from odometry: a tick whose newest pose is further from it than this renders
  // nothing and says so on /diagnostics (a robot whose odometry stopped).
  double maxPoseAgeSeconds = 0.5;
  // A ROS node's own command-line arguments (from:=to): remappings of the full topic names,
  // __name:= and __log:= (roslaunch's). The topics are absolute (/ROBOT/CAMERA/...): __ns:=
  // moves the node's name only.
  std::vector<std::string> rosArguments;
  double masterWaitSeconds = 30.0;
  // Told the master's URI once if the master does not answer at once (the node then waits).
  std::function<void(const std::string& masterUri)> onWaitingForMaster;
  // Told, before anything is rendered, what the user should know of the spec as a live sensor
  // renders it: the dataset's notes (a lens camera's size scaled, outputs the engine does not
  // write) and the spec's fields that do nothing live (a calibration sequence, the EuRoC layout).
  std::function<void(const std::vector<std::string>& notes)> onNotes;
  // When set: every message published also goes into this ROS bag (written under a temporary
  // name, renamed when the sensor stops). The path must be a new file (checkOutputFile).
  std::string recordBag;
};

struct LiveSensorReport {
  bool stoppedWaitingForMaster = false;  // a signal came before any master answered
  int64_t rendered = 0, refused = 0;
  int64_t dropped = 0;  // poses a newer one replaced before they were rendered
  int64_t skippedTicks = 0;  // at a fixed rate: ticks that had no pose within maxPoseAgeSeconds
  int64_t newMasters = 0;  // masters that restarted, with which every topic was registered again
  bool shutDownByRos = false;  // the master ended the node (its name taken by another, rosnode kill)
  // A signal ended the external renderer (POV-Ray, Blender) of the frame in progress: that frame
  // was given up, the node stopped, and the bag holds every frame before it. What ended, as
  // Interrupted says it; empty if no frame was given up.
  std::string frameGivenUp;
};

// An odometry message as the robot's pose (x, y, yaw about +Z from the quaternion) and velocity
// (the twist's forward, left and yaw rate, in the robot's frame).
struct LivePose {
  RobotPose pose;
  BodyVelocity velocity;
  ros1::Stamp stamp;
};
LivePose livePoseOf(const ros1::Odometry& odometry);

// Whether the `count`th of a repeating event (a pose dropped; a tick skipped, counted from the
// outage's first) is said on /diagnostics: the 1st, 2nd, 4th, 8th … and then every 1024th, each
// with the total count. A robot
// sending odometry at 1 kHz to a 10 Hz camera drops about 990 poses a second; one message each
// would flood every aggregator, and the counts say as much. Refusals, whose reasons differ, are
// each said.
bool saysRepeat(int64_t count);

// The newest pose not yet rendered: the ROS thread puts, the render loop takes. A pose put while
// another waits replaces it; the replaced one is dropped and counted.
class NewestPose {
 public:
  // Whether it replaced a pose not yet rendered.
  bool put(const LivePose& pose);
  // The newest pose, or nothing if none came within `wait`.
  std::optional<LivePose> take(std::chrono::milliseconds wait);
  int64_t dropped() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::optional<LivePose> pending_;
  int64_t dropped_ = 0;
};

// Why an odometry message is refused ("" if it is not): a number that is not finite, a
// quaternion far from unit length, a pose or speed beyond a dataset's limits, a stamp not after
// `lastAccepted`'s, or one more than ros1::kMostStampAheadSeconds after ROS time `now` (not
// checked while `now` is zero, before /clock's first message). A refused pose is not rendered; the
// sensor says why on /diagnostics and goes on.
std::string problemWith(const ros1::Odometry& odometry, const ros1::Stamp* lastAccepted, const ros1::Stamp& now = {});

// The tick of a fixed-rate camera (LiveSensorOptions::rateHz) at or before `now`: the grid of
// `periodNs` from the epoch.
ros1::Stamp tickAtOrBefore(const ros1::Stamp& now, int64_t periodNs);

// `latest` carried to `tick` with its own velocity (poseAfter, the dataset's motion), stamped
// with the tick; nothing, with why in `problem`, if the tick is more than `maxAgeSeconds` from
// the pose.
std::optional<LivePose> poseAtTick(const LivePose& latest, const ros1::Stamp& tick, double maxAgeSeconds,
                                   std::string& problem);

// The topics a running sensor uses, as ROS resolved them (after from:=to remappings).
struct LiveSensorTopics {
  std::string odometry;             // empty with poses from tf
  std::vector<std::string> images;  // each camera's image_raw, in the spec's order
};

// Runs the sensor until options.frames poses are rendered or a signal arrives (then within
// 0.1 s of the frame being rendered). `ready`, if set, is called once the topics are announced
// and the odometry subscribed, with the topics it uses.
// InputError for a spec the dataset reader refuses; ExternalError if no master answers.
LiveSensorReport runLiveSensor(const DatasetSpec& spec, const LiveSensorOptions& options,
                               const std::function<void(const LiveSensorTopics& topics)>& ready = {});

}  // namespace omnicam
