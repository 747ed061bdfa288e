#include "ros_transport.h"

#include <diagnostic_msgs/DiagnosticArray.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <ros/names.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <mutex>
#include <stdexcept>

namespace omnicam::ros1 {

namespace {

Stamp stampOf(const ros::Time& t) { return {t.sec, t.nsec}; }

Odometry odometryOf(const nav_msgs::Odometry& m) {
  Odometry o;
  o.stamp = stampOf(m.header.stamp);
  o.frame = m.header.frame_id;
  o.childFrame = m.child_frame_id;
  const auto& p = m.pose.pose;
  o.position[0] = p.position.x, o.position[1] = p.position.y, o.position[2] = p.position.z;
  o.orientationXyzw[0] = p.orientation.x, o.orientationXyzw[1] = p.orientation.y;
  o.orientationXyzw[2] = p.orientation.z, o.orientationXyzw[3] = p.orientation.w;
  const auto& t = m.twist.twist;
  o.linear[0] = t.linear.x, o.linear[1] = t.linear.y, o.linear[2] = t.linear.z;
  o.angular[0] = t.angular.x, o.angular[1] = t.angular.y, o.angular[2] = t.angular.z;
  return o;
}

sensor_msgs::Image messageOf(const Image& image) {
  sensor_msgs::Image m;
  m.header.stamp = ros::Time(image.stamp.sec, image.stamp.nsec);
  m.header.frame_id = image.frame;
  m.width = image.width, m.height = image.height, m.step = image.step;
  m.encoding = image.encoding;
  m.is_bigendian = 0;
  m.data = image.data;
  return m;
}

sensor_msgs::CameraInfo messageOf(const CameraInfo& info) {
  sensor_msgs::CameraInfo m;
  m.header.stamp = ros::Time(info.stamp.sec, info.stamp.nsec);
  m.header.frame_id = info.frame;
  m.width = info.width, m.height = info.height;
  m.distortion_model = info.distortionModel;
  m.D = info.d;
  std::copy(info.k.begin(), info.k.end(), m.K.begin());
  std::copy(info.r.begin(), info.r.end(), m.R.begin());
  std::copy(info.p.begin(), info.p.end(), m.P.begin());
  return m;
}

// The master's process id, 0 if no master answers (its getPid call).
int masterPid() {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  if (!ros::master::execute("getPid", args, result, payload, false)) return 0;
  return payload.getType() == XmlRpc::XmlRpcValue::TypeInt ? static_cast<int>(payload) : 0;
}

}  // namespace

std::string invalidGraphName(const std::string& name) {
  std::string why;
  return ros::names::validate(name, why) ? "" : why;
}

struct Transport::Impl {
  std::unique_ptr<ros::NodeHandle> node;
  std::unique_ptr<ros::AsyncSpinner> spinner;
  std::vector<ros::Subscriber> subscriptions;
  mutable std::mutex mutex;  // guards publishers (publish may come from a worker thread)
  std::map<std::string, ros::Publisher> publishers;
  ros::Publisher diagnostics;
  std::unique_ptr<tf2_ros::StaticTransformBroadcaster> staticTransforms;
  std::unique_ptr<tf2_ros::Buffer> tfBuffer;
  std::unique_ptr<rosbag::Bag> bag;  // when recording (the mutex held to write)
  std::string bagPath, bagPartial;
  // roscpp registers a topic with the master once; a master that restarts knows none. These make
  // every subscription (on the owner's thread) and publication (the mutex held) again.
  std::vector<std::function<void()>> subscribe, advertise;
  std::vector<geometry_msgs::TransformStamped> staticMessages;
  int masterPid = 0;  // the master registered with; another pid is a master that restarted
  std::unique_ptr<tf2_ros::TransformListener> tfListener;

  // Publishes `message` on `topic` and records it (the mutex held).
  template <typename Message>
  void send(const std::string& topic, const Message& message) {
    advertised(topic).publish(message);
    if (bag) bag->write(topic, message.header.stamp, message);
  }

  // The publisher of `topic` (the mutex held): a topic must be advertised first.
  ros::Publisher& advertised(const std::string& topic) {
    const auto it = publishers.find(topic);
    if (it == publishers.end()) throw std::logic_error("publish: " + topic + " was not advertised");
    return it->second;
  }
};

Transport::Transport(const std::string& name, double masterWaitSeconds, const std::function<bool()>& stopRequested)
    : impl_(std::make_unique<Impl>()) {
  int argc = 0;
  ros::init(argc, nullptr, name, ros::init_options::NoSigintHandler | ros::init_options::NoRosout);
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(masterWaitSeconds);
  while ((impl_->masterPid = masterPid()) == 0) {
    if (ros::WallTime::now() > deadline) throw std::runtime_error("no ROS master at " + ros::master::getURI());
    if (stopRequested && stopRequested()) throw std::runtime_error("stopped while waiting for the ROS master");
    ros::WallDuration(0.05).sleep();
  }
  impl_->node = std::make_unique<ros::NodeHandle>();
  Impl* impl = impl_.get();
  impl->advertise.push_back(
      [impl] { impl->diagnostics = impl->node->advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 10); });
  impl->advertise.back()();
  impl_->spinner = std::make_unique<ros::AsyncSpinner>(1);
  impl_->spinner->start();
}

Transport::~Transport() {
  impl_->spinner->stop();
  impl_->subscriptions.clear();
  impl_->tfListener.reset();
  impl_->tfBuffer.reset();
  if (impl_->bag) {  // not finished: the run failed or was cut short
    try {
      impl_->bag->close();
    } catch (const std::exception&) {
    }
    ::unlink(impl_->bagPartial.c_str());
  }
  impl_->publishers.clear();
  impl_->diagnostics.shutdown();
  impl_->staticTransforms.reset();
  impl_->node.reset();
  ros::shutdown();
}

void Transport::subscribeOdometry(const std::string& topic, OdometryHandler handler) {
  Impl* impl = impl_.get();
  impl->subscribe.push_back([impl, topic, handler] {
    impl->subscriptions.push_back(impl->node->subscribe<nav_msgs::Odometry>(
        topic, 10, [handler](const nav_msgs::Odometry::ConstPtr& m) { handler(odometryOf(*m)); }));
  });
  impl->subscribe.back()();
}

void Transport::subscribeTransform(const std::string& parent, const std::string& child, OdometryHandler handler,
                                   GapHandler gap) {
  if (!impl_->tfBuffer) {
    impl_->tfBuffer = std::make_unique<tf2_ros::Buffer>();
    impl_->tfListener = std::make_unique<tf2_ros::TransformListener>(*impl_->tfBuffer);  // its own thread
  }
  tf2_ros::Buffer& buffer = *impl_->tfBuffer;
  Impl* impl = impl_.get();
  impl->subscribe.push_back([impl, &buffer, parent, child, handler, gap] {
  impl->subscriptions.push_back(impl->node->subscribe<tf2_msgs::TFMessage>(
      "/tf", 100, [&buffer, parent, child, handler, gap](const tf2_msgs::TFMessage::ConstPtr& m) {
        for (const geometry_msgs::TransformStamped& moved : m->transforms) {
          if (moved.child_frame_id != child) continue;
          const Stamp stamp = stampOf(moved.header.stamp);
          std::string why;
          // The listener (its own thread) may not have this message yet: wait for it up to 1 s.
          if (!buffer.canTransform(parent, child, moved.header.stamp, ros::Duration(1.0), &why)) {
            gap(stamp, why);
            continue;
          }
          const geometry_msgs::TransformStamped t = buffer.lookupTransform(parent, child, moved.header.stamp);
          Odometry o;
          o.stamp = stamp;
          o.frame = parent;
          o.childFrame = child;
          o.position[0] = t.transform.translation.x, o.position[1] = t.transform.translation.y;
          o.position[2] = t.transform.translation.z;
          o.orientationXyzw[0] = t.transform.rotation.x, o.orientationXyzw[1] = t.transform.rotation.y;
          o.orientationXyzw[2] = t.transform.rotation.z, o.orientationXyzw[3] = t.transform.rotation.w;
          handler(o);
        }
      }));
  });
  impl->subscribe.back()();
}

void Transport::advertiseImage(const std::string& topic, bool latched) {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  Impl* impl = impl_.get();
  impl->advertise.push_back(
      [impl, topic, latched] { impl->publishers[topic] = impl->node->advertise<sensor_msgs::Image>(topic, 2, latched); });
  impl->advertise.back()();
}

void Transport::publish(const std::string& topic, const Image& image) {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->send(topic, messageOf(image));
}

void Transport::publish(const Diagnostic& diagnostic) {
  diagnostic_msgs::DiagnosticStatus status;
  status.level = diagnostic.level;
  status.name = diagnostic.name;
  status.message = diagnostic.message;
  status.hardware_id = diagnostic.hardwareId;
  for (const auto& [key, value] : diagnostic.values) {
    diagnostic_msgs::KeyValue pair;
    pair.key = key, pair.value = value;
    status.values.push_back(pair);
  }
  diagnostic_msgs::DiagnosticArray array;
  array.header.stamp = ros::Time::now();
  array.status.push_back(status);
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->diagnostics.publish(array);
}

void Transport::advertiseCameraInfo(const std::string& topic) {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  Impl* impl = impl_.get();
  impl->advertise.push_back([impl, topic] { impl->publishers[topic] = impl->node->advertise<sensor_msgs::CameraInfo>(topic, 2); });
  impl->advertise.back()();
}

void Transport::publish(const std::string& topic, const CameraInfo& info) {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->send(topic, messageOf(info));
}

void Transport::publishStaticTransforms(const std::vector<Transform>& transforms) {
  std::vector<geometry_msgs::TransformStamped> messages;
  for (const Transform& t : transforms) {
    geometry_msgs::TransformStamped m;
    m.header.stamp = ros::Time::now();
    m.header.frame_id = t.parent;
    m.child_frame_id = t.child;
    m.transform.translation.x = t.translation[0], m.transform.translation.y = t.translation[1];
    m.transform.translation.z = t.translation[2];
    m.transform.rotation.x = t.rotationXyzw[0], m.transform.rotation.y = t.rotationXyzw[1];
    m.transform.rotation.z = t.rotationXyzw[2], m.transform.rotation.w = t.rotationXyzw[3];
    messages.push_back(m);
  }
  std::lock_guard<std::mutex> lock(impl_->mutex);
  if (!impl_->staticTransforms) impl_->staticTransforms = std::make_unique<tf2_ros::StaticTransformBroadcaster>();
  impl_->staticTransforms->sendTransform(messages);
  impl_->staticMessages.insert(impl_->staticMessages.end(), messages.begin(), messages.end());
  if (impl_->bag) {
    tf2_msgs::TFMessage all;
    all.transforms = messages;
    impl_->bag->write("/tf_static", messages.empty() ? ros::Time::now() : messages.front().header.stamp, all);
  }
}

void Transport::publishLatchedText(const std::string& topic, const std::string& text) {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  Impl* impl = impl_.get();
  impl->advertise.push_back([impl, topic, text] {
    ros::Publisher& publisher = impl->publishers[topic];
    publisher = impl->node->advertise<std_msgs::String>(topic, 1, /*latch=*/true);
    std_msgs::String m;
    m.data = text;
    publisher.publish(m);
    if (impl->bag) impl->bag->write(topic, ros::Time::now(), m);
  });
  impl->advertise.back()();
}

bool Transport::registerAgainIfTheMasterCameBack() {
  const int pid = masterPid();
  if (pid == 0 || pid == impl_->masterPid) return false;  // away, or the same master
  impl_->masterPid = pid;
  // Subscriptions first, outside the mutex: a callback may be waiting for it.
  for (ros::Subscriber& s : impl_->subscriptions) s.shutdown();
  impl_->subscriptions.clear();
  if (impl_->tfListener) {
    impl_->tfListener.reset();
    impl_->tfListener = std::make_unique<tf2_ros::TransformListener>(*impl_->tfBuffer);
  }
  for (const auto& make : impl_->subscribe) make();
  std::lock_guard<std::mutex> lock(impl_->mutex);
  for (auto& [topic, publisher] : impl_->publishers) publisher.shutdown();
  impl_->publishers.clear();
  impl_->diagnostics.shutdown();
  for (const auto& make : impl_->advertise) make();
  if (impl_->staticTransforms) {
    impl_->staticTransforms = std::make_unique<tf2_ros::StaticTransformBroadcaster>();
    impl_->staticTransforms->sendTransform(impl_->staticMessages);
  }
  return true;
}

void Transport::record(const std::string& partialPath, const std::string& path) {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->bagPath = path;
  impl_->bagPartial = partialPath;
  impl_->bag = std::make_unique<rosbag::Bag>();
  try {
    impl_->bag->open(impl_->bagPartial, rosbag::bagmode::Write);
  } catch (const rosbag::BagException& e) {
    impl_->bag.reset();
    throw std::runtime_error(e.what());
  }
}

void Transport::finishRecording() {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  if (!impl_->bag) return;
  std::unique_ptr<rosbag::Bag> bag = std::move(impl_->bag);
  try {
    bag->close();
  } catch (const rosbag::BagException& e) {
    ::unlink(impl_->bagPartial.c_str());
    throw std::runtime_error(e.what());
  }
  // link(2) fails if the name exists: a file someone made there meanwhile stays theirs.
  const bool linked = ::link(impl_->bagPartial.c_str(), impl_->bagPath.c_str()) == 0;
  const int error = errno;
  ::unlink(impl_->bagPartial.c_str());
  if (!linked) throw std::runtime_error(std::strerror(error));
}

uint32_t Transport::subscribers(const std::string& topic) const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  const auto it = impl_->publishers.find(topic);
  return it == impl_->publishers.end() ? 0 : it->second.getNumSubscribers();
}

}  // namespace omnicam::ros1
