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
#include <tf2/buffer_core.h>
#include <ros/callback_queue.h>

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <utility>
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

// Runs a callback's work on the spinner thread. roscpp lets a callback's exception through to
// std::terminate: one is said on stderr instead, and the node goes on with the next message.
template <typename Work>
void guarded(const char* what, const Work& work) {
  try {
    work();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "omnicam: ros: %s left out: %s\n", what, e.what());
  }
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

// Poses of `child` in `parent`, asked for at stamps and handed over once the tree reaches them
// (as tf2's MessageFilter does, without its thread): everything here runs on the spinner thread.
class TfPoses {
 public:
  TfPoses(std::string parent, std::string child, bool eachMove, TransformHandlers handlers)
      : parent_(std::move(parent)), child_(std::move(child)), eachMove_(eachMove), handlers_(std::move(handlers)) {}

  void take(const tf2_msgs::TFMessage& message, bool isStatic) {
    forgetIfTimeWentBack();
    for (const geometry_msgs::TransformStamped& t : message.transforms) {
      if (!taken(t, isStatic)) continue;
      if (isStatic) continue;
      newestData_ = std::max(newestData_, t.header.stamp);
      if (eachMove_ && t.child_frame_id == child_) pending_.push_back(t.header.stamp);
    }
    handOver();
  }
  void request(const ros::Time& stamp) {
    forgetIfTimeWentBack();
    pending_.push_back(stamp);
    handOver();
  }

 private:
  static constexpr size_t kMostWaiting = 1000;

  // Whether tf2 takes `t` (it says why not on the log). A stamp far after ROS time now is not
  // given to it: tf2 would keep it and then drop every later transform of that frame as older
  // than its newest by 10 s; at the end of ROS time its own arithmetic throws, after keeping it.
  // Refused for the base frame as a gap of its poses, for another frame on stderr.
  bool taken(const geometry_msgs::TransformStamped& t, bool isStatic) {
    const ros::Time now = ros::Time::now();
    std::string why;
    if (!isStatic && !now.isZero() && t.header.stamp.toSec() - now.toSec() > kMostStampAheadSeconds) {
      why = "the transform's stamp " + stampText(stampOf(t.header.stamp)) + " is more than " +
            std::to_string(static_cast<int>(kMostStampAheadSeconds)) + " s after ROS time now, " + stampText(stampOf(now));
    } else {
      try {
        return buffer_.setTransform(t, "omnicam", isStatic);
      } catch (const std::exception& e) {
        why = std::string("tf cannot take it: ") + e.what();
      }
    }
    if (t.child_frame_id == child_)
      handlers_.gap(stampOf(t.header.stamp), "the transform to " + child_ + " is left out: " + why);
    else
      std::fprintf(stderr, "omnicam: ros: the transform to %s is left out: %s\n", t.child_frame_id.c_str(), why.c_str());
    return false;
  }

  // Every request the tree reaches is handed over, oldest first. One it does not reach is
  // refused with tf's reason when a later one was handed over (poses only go forward), when tf
  // is kTfPatienceSeconds past it, or when more than kMostWaiting wait; else it waits.
  void handOver() {
    std::sort(pending_.begin(), pending_.end());
    pending_.erase(std::unique(pending_.begin(), pending_.end()), pending_.end());
    std::vector<std::pair<ros::Time, std::string>> unreached;
    for (const ros::Time& stamp : pending_) {
      std::string why;
      if (!buffer_.canTransform(parent_, child_, stamp, &why)) {
        unreached.emplace_back(stamp, why);
        continue;
      }
      for (const auto& [older, whyNot] : unreached) handlers_.gap(stampOf(older), whyNot);
      unreached.clear();
      handlers_.pose(odometryAt(stamp));
    }
    pending_.clear();
    // In seconds: ros::Time + Duration throws beyond ROS time's end, where a hostile stamp can be.
    const double reference = patienceReference().toSec();
    for (size_t i = 0; i < unreached.size(); ++i) {
      const auto& [stamp, why] = unreached[i];
      if (reference - stamp.toSec() >= Transport::kTfPatienceSeconds || unreached.size() - i > kMostWaiting)
        handlers_.gap(stampOf(stamp), why);
      else
        pending_.push_back(stamp);
    }
  }
  // What a request's patience is measured against: /tf's own data for stamps taken from it; for
  // stamps of ROS time (a fixed rate's ticks) ROS time too, so requests expire while /tf is silent.
  ros::Time patienceReference() const { return eachMove_ ? newestData_ : std::max(newestData_, ros::Time::now()); }
  // A simulation reset sends ROS time back: what tf knew belongs to the old run (as
  // tf2_ros::TransformListener clears its buffer then).
  void forgetIfTimeWentBack() {
    const ros::Time now = ros::Time::now();
    if (now < lastNow_) {
      buffer_.clear();
      pending_.clear();
      newestData_ = ros::Time();
    }
    lastNow_ = now;
  }
  Odometry odometryAt(const ros::Time& stamp) const {
    const geometry_msgs::TransformStamped t = buffer_.lookupTransform(parent_, child_, stamp);
    Odometry o;
    o.stamp = stampOf(stamp);
    o.frame = parent_;
    o.childFrame = child_;
    o.position[0] = t.transform.translation.x, o.position[1] = t.transform.translation.y;
    o.position[2] = t.transform.translation.z;
    o.orientationXyzw[0] = t.transform.rotation.x, o.orientationXyzw[1] = t.transform.rotation.y;
    o.orientationXyzw[2] = t.transform.rotation.z, o.orientationXyzw[3] = t.transform.rotation.w;
    return o;
  }

  const std::string parent_, child_;
  const bool eachMove_;
  const TransformHandlers handlers_;
  tf2::BufferCore buffer_;  // tf2's 10 s of each frame, filled by take()
  std::vector<ros::Time> pending_;
  ros::Time newestData_, lastNow_;
};

struct Transport::Impl {
  std::unique_ptr<ros::NodeHandle> node;
  std::unique_ptr<ros::AsyncSpinner> spinner;
  std::vector<ros::Subscriber> subscriptions;
  mutable std::mutex mutex;  // guards publishers (publish may come from a worker thread)
  std::map<std::string, ros::Publisher> publishers;
  ros::Publisher diagnostics;
  std::unique_ptr<tf2_ros::StaticTransformBroadcaster> staticTransforms;
  std::unique_ptr<rosbag::Bag> bag;  // when recording (the mutex held to write)
  std::string bagPath, bagPartial;
  // What goes into the bag at the first stamped message's stamp: static transforms, latched texts.
  std::vector<std::function<void(const ros::Time&)>> bagAtFirstStamp;
  // roscpp registers a topic with the master once; a master that restarts knows none. These make
  // every subscription (on the owner's thread) and publication (the mutex held) again.
  std::vector<std::function<void()>> subscribe, advertise;
  std::vector<geometry_msgs::TransformStamped> staticMessages;
  int masterPid = 0;  // the master registered with; another pid is a master that restarted
  std::unique_ptr<TfPoses> tfPoses;  // the spinner thread's own

  // Publishes `message` on `topic` and records it (the mutex held).
  template <typename Message>
  void send(const std::string& topic, const Message& message) {
    advertised(topic).publish(message);
    if (bag) {
      writeWaitingBagMessages(message.header.stamp);
      bag->write(topic, message.header.stamp, message);
    }
  }
  // A latched topic's connection in the bag, as `rosbag record` writes it from the publisher:
  // `rosbag play` then latches it again, for the subscribers that come late (tf listeners, RViz).
  // A header given to rosbag is stored as it is: it carries the message's type, checksum and
  // definition too, which rosbag fills in only for a connection it makes itself.
  template <typename Message>
  static boost::shared_ptr<ros::M_string> latchedConnection(const std::string& topic) {
    auto header = boost::make_shared<ros::M_string>();
    (*header)["topic"] = topic;
    (*header)["type"] = ros::message_traits::datatype<Message>();
    (*header)["md5sum"] = ros::message_traits::md5sum<Message>();
    (*header)["message_definition"] = ros::message_traits::definition<Message>();
    (*header)["callerid"] = ros::this_node::getName();
    (*header)["latching"] = "1";
    return header;
  }
  void writeWaitingBagMessages(const ros::Time& stamp) {
    for (const auto& write : bagAtFirstStamp) write(stamp);
    bagAtFirstStamp.clear();
  }

  // The publisher of `topic` (the mutex held): a topic must be advertised first.
  ros::Publisher& advertised(const std::string& topic) {
    const auto it = publishers.find(topic);
    if (it == publishers.end()) throw std::logic_error("publish: " + topic + " was not advertised");
    return it->second;
  }
};

Transport::Transport(const std::string& name, double masterWaitSeconds, const std::function<bool()>& stopRequested,
                     const std::vector<std::string>& rosArguments, const std::function<void(const std::string&)>& waiting)
    : impl_(std::make_unique<Impl>()) {
  ros::M_string remappings;
  for (const std::string& argument : rosArguments) {
    const size_t split = argument.find(":=");
    if (split == std::string::npos || split == 0) throw std::invalid_argument("not a ROS argument (from:=to): " + argument);
    remappings[argument.substr(0, split)] = argument.substr(split + 2);
  }
  try {
    ros::init(remappings, name, ros::init_options::NoSigintHandler | ros::init_options::NoRosout);
  } catch (const ros::Exception& e) {  // a node name or namespace ROS cannot take
    throw std::invalid_argument(e.what());
  }
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(masterWaitSeconds);
  bool told = false;
  while ((impl_->masterPid = masterPid()) == 0) {
    if (ros::WallTime::now() > deadline) throw std::runtime_error("no ROS master at " + ros::master::getURI());
    if (stopRequested && stopRequested()) throw StoppedWaitingForMaster("stopped while waiting for the ROS master");
    if (waiting && !told) waiting(ros::master::getURI()), told = true;
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
  impl_->tfPoses.reset();
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
        topic, 10, [handler](const nav_msgs::Odometry::ConstPtr& m) { guarded("an odometry message", [&] { handler(odometryOf(*m)); }); }));
  });
  impl->subscribe.back()();
}

void Transport::subscribeTransform(const std::string& parent, const std::string& child, bool eachMove,
                                   TransformHandlers handlers) {
  Impl* impl = impl_.get();
  impl->tfPoses = std::make_unique<TfPoses>(parent, child, eachMove, std::move(handlers));
  TfPoses* poses = impl->tfPoses.get();
  for (const bool isStatic : {false, true}) {
    impl->subscribe.push_back([impl, poses, isStatic] {
      impl->subscriptions.push_back(impl->node->subscribe<tf2_msgs::TFMessage>(
          isStatic ? "/tf_static" : "/tf", 100,
          [poses, isStatic](const tf2_msgs::TFMessage::ConstPtr& m) { guarded("a tf message", [&] { poses->take(*m, isStatic); }); }));
    });
    impl->subscribe.back()();
  }
}

void Transport::requestTransform(const Stamp& stamp) {
  if (!impl_->tfPoses) throw std::logic_error("requestTransform: no subscribeTransform");
  impl_->tfPoses->request(ros::Time(stamp.sec, stamp.nsec));
}

namespace {

// Work handed to the spinner thread (post).
class PostedWork : public ros::CallbackInterface {
 public:
  explicit PostedWork(std::function<void()> work) : work_(std::move(work)) {}
  CallResult call() override {
    guarded("a tick", work_);
    return Success;
  }

 private:
  std::function<void()> work_;
};

}  // namespace

void Transport::post(std::function<void()> work) {
  ros::getGlobalCallbackQueue()->addCallback(boost::make_shared<PostedWork>(std::move(work)));
}

Stamp Transport::now() const { return stampOf(ros::Time::now()); }

bool Transport::simulatedTime() const { return ros::Time::isSimTime(); }

std::string Transport::resolvedName(const std::string& name) const { return ros::names::resolve(name); }

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
    impl_->bagAtFirstStamp.push_back([impl = impl_.get(), messages](const ros::Time& stamp) {
      tf2_msgs::TFMessage all;
      all.transforms = messages;
      for (geometry_msgs::TransformStamped& t : all.transforms) t.header.stamp = stamp;
      impl->bag->write("/tf_static", stamp, all, Impl::latchedConnection<tf2_msgs::TFMessage>("/tf_static"));
    });
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
  });
  if (impl->bag) impl->bagAtFirstStamp.push_back([impl, topic, text](const ros::Time& stamp) {
    std_msgs::String m;
    m.data = text;
    impl->bag->write(topic, stamp, m, Impl::latchedConnection<std_msgs::String>(topic));
  });
  impl->advertise.back()();
}

bool Transport::shutDownByRos() const { return !ros::ok(); }

bool Transport::registerAgainIfTheMasterCameBack() {
  const int pid = masterPid();
  if (pid == 0 || pid == impl_->masterPid) return false;  // away, or the same master
  impl_->masterPid = pid;
  // Subscriptions first, outside the mutex: a callback may be waiting for it.
  for (ros::Subscriber& s : impl_->subscriptions) s.shutdown();
  impl_->subscriptions.clear();
  for (const auto& make : impl_->subscribe) make();
  std::lock_guard<std::mutex> lock(impl_->mutex);
  for (auto& [topic, publisher] : impl_->publishers) publisher.shutdown();
  impl_->publishers.clear();
  impl_->diagnostics.shutdown();
  for (const auto& make : impl_->advertise) make();
  if (impl_->staticTransforms) {
    // The old broadcaster goes first: while its publication lives, a new one joins it and is
    // never registered with the new master.
    impl_->staticTransforms.reset();
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
  try {
    // No image came: they go in now (at least rosbag's first time: under simulated time before
    // any /clock, now is 0, which a bag cannot hold).
    impl_->writeWaitingBagMessages(std::max(ros::Time::now(), ros::TIME_MIN));
    std::unique_ptr<rosbag::Bag> bag = std::move(impl_->bag);
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
