#pragma once
// omnicam's one connection to a ROS 1 master (roscpp): a node that subscribes to odometry and
// publishes images. Built as C++17 (ros_messages.h says why). Callbacks run on roscpp's own
// spinner thread; a handler must hand work off rather than render there.
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "ros_messages.h"

namespace omnicam::ros1 {

// Why `name` is not a valid ROS graph name (a topic or a node's), "" if it is.
std::string invalidGraphName(const std::string& name);

// Thrown by Transport's constructor when its caller asked it to stop while it waited for a master.
class StoppedWaitingForMaster : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Transport {
 public:
  // Registers node `name` with the master of ROS_MASTER_URI (roscpp reads the environment);
  // SIGINT is left to the caller. `rosArguments` are a ROS node's command-line arguments, each
  // `from:=to`: remappings (`/robot/front/image_raw:=/camera`), `__name:=`, `__ns:=`, `__log:=`
  // (roslaunch's); std::invalid_argument for one that is not, or a name ROS refuses. (A private
  // parameter `_name:=value` makes roscpp wait for a master without limit: callers refuse it.)
  // Throws std::runtime_error if the master cannot be reached within `masterWaitSeconds`, and
  // StoppedWaitingForMaster if `stopRequested` (asked while it waits) says so. `waiting`, if set,
  // is told the master's URI once when the master does not answer at once.
  Transport(const std::string& name, double masterWaitSeconds, const std::function<bool()>& stopRequested = {},
            const std::vector<std::string>& rosArguments = {},
            const std::function<void(const std::string& masterUri)>& waiting = {});
  ~Transport();
  Transport(const Transport&) = delete;
  Transport& operator=(const Transport&) = delete;

  // Odometry messages of `topic`, to `handler` on the spinner thread.
  void subscribeOdometry(const std::string& topic, OdometryHandler handler);
  // Poses of `child` in `parent` from tf, through the whole tree (map → odom → base_link), each
  // handed over as an odometry without twist (tf has none). /tf and /tf_static go into the
  // node's own buffer on the spinner thread; a pose is asked for at a stamp (each /tf message
  // that moves `child` asks at its stamp when `eachMove`; requestTransform asks too) and handed
  // over as soon as the tree reaches it, oldest first, never by blocking the spinner. A request
  // goes to `handlers.gap` with tf's reason when a later one was handed over first (poses only go
  // forward), or once tf is kTfPatienceSeconds past its stamp without reaching it: /tf's newest
  // data for stamps from /tf, and ROS time too for requestTransform's. A ROS time that goes back
  // (a simulation reset) empties the buffer and the requests.
  void subscribeTransform(const std::string& parent, const std::string& child, bool eachMove, TransformHandlers handlers);
  // Asks subscribeTransform's tree for its pose at `stamp`. On the spinner thread only (post).
  void requestTransform(const Stamp& stamp);
  static constexpr double kTfPatienceSeconds = 1.0;
  // Runs `work` on the spinner thread, after the callbacks already waiting: the one thread that
  // owns what the callbacks share.
  void post(std::function<void()> work);
  // ROS time: the wall clock, or /clock's when the master's /use_sim_time is set.
  Stamp now() const;
  bool simulatedTime() const;
  // `name` as ROS resolves it, after the node's from:=to remappings: the topic a subscriber or a
  // publisher of `name` really uses.
  std::string resolvedName(const std::string& name) const;
  // Announces `topic` as sensor_msgs/Image; `latched` keeps the last message for late subscribers.
  void advertiseImage(const std::string& topic, bool latched = false);
  void publish(const std::string& topic, const Image& image);
  // sensor_msgs/CameraInfo, as images.
  void advertiseCameraInfo(const std::string& topic);
  void publish(const std::string& topic, const CameraInfo& info);
  // std_msgs/String, latched: published once, kept for every later subscriber.
  void publishLatchedText(const std::string& topic, const std::string& text);
  // Transforms that never change, on /tf_static (latched, as tf2's static broadcaster does).
  void publishStaticTransforms(const std::vector<Transform>& transforms);
  // One status on /diagnostics (advertised by the constructor), stamped now.
  void publish(const Diagnostic& diagnostic);
  // From now on the images, camera_info, static transforms and latched texts this node
  // publishes also go into a ROS bag, under their topics, stamped with their headers' stamps.
  // Static transforms and latched texts, which have no stamp of their own, go in at the first
  // image's stamp (or when the bag is finished, if no image came): `rosbag play` then sends
  // them first, not at a wall-clock time far from the images' (simulated) ones.
  // The bag is written as `partialPath`; finishRecording() gives it the name `path`. A node that
  // ends otherwise removes the partial bag: nothing half-written is left under either name.
  // std::runtime_error if it cannot be opened.
  void record(const std::string& partialPath, const std::string& path);
  // Closes the bag and links it to its name, never replacing a file that appeared there since,
  // then removes the partial name. std::runtime_error saying why it could not.
  void finishRecording();
  // Whether another master answers now than the one registered with (it restarted, whether or
  // not a call saw it away); then every subscription, publication, latched message and static
  // transform is registered again (roscpp registers once, and a new master knows none). Call it
  // now and then from the owner's thread.
  bool registerAgainIfTheMasterCameBack();
  // Whether ROS itself has ended the node: the master's shutdown call, made when another node
  // registers under its name, or by `rosnode kill`. roscpp then unregisters every topic; the
  // node hears and publishes nothing more.
  bool shutDownByRos() const;
  // Subscribers of `topic` connected now.
  uint32_t subscribers(const std::string& topic) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace omnicam::ros1
