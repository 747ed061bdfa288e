#pragma once
// omnicam's one connection to a ROS 1 master (roscpp): a node that subscribes to odometry and
// publishes images. Built as C++17 (ros_messages.h says why). Callbacks run on roscpp's own
// spinner thread; a handler must hand work off rather than render there.
#include <functional>
#include <memory>
#include <string>

#include "ros_messages.h"

namespace omnicam::ros1 {

// Why `name` is not a valid ROS graph name (a topic or a node's), "" if it is.
std::string invalidGraphName(const std::string& name);

class Transport {
 public:
  // Registers node `name` with the master of ROS_MASTER_URI (roscpp reads the environment);
  // SIGINT is left to the caller. Throws std::runtime_error if the master cannot be reached
  // within `masterWaitSeconds`, or if `stopRequested` (asked while it waits) says so.
  Transport(const std::string& name, double masterWaitSeconds, const std::function<bool()>& stopRequested = {});
  ~Transport();
  Transport(const Transport&) = delete;
  Transport& operator=(const Transport&) = delete;

  // Odometry messages of `topic`, to `handler` on the spinner thread.
  void subscribeOdometry(const std::string& topic, OdometryHandler handler);
  // Poses from tf: each /tf message that moves `child` is looked up as `child` in `parent` at
  // its stamp, through the whole tree (map → odom → base_link), and handed over as an odometry
  // without twist (tf has none). A lookup that fails goes to `gap`.
  void subscribeTransform(const std::string& parent, const std::string& child, OdometryHandler handler, GapHandler gap);
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
  // Subscribers of `topic` connected now.
  uint32_t subscribers(const std::string& topic) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace omnicam::ros1
