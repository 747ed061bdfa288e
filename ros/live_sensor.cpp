#include "live_sensor.h"

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "dataset_options.h"
#include "dataset_plan.h"
#include "errors.h"
#include "film.h"
#include "image.h"
#include "interrupts.h"
#include "ros_transport.h"

namespace omnicam {

namespace {

constexpr double kDegreesPerRadian = 180.0 / M_PI;

// The newest pose not yet rendered: the ROS thread puts, the render loop takes.
class NewestPose {
 public:
  void put(const LivePose& pose) {
    {
      std::lock_guard lock(mutex_);
      if (pending_) ++dropped_;
      pending_ = pose;
    }
    ready_.notify_one();
  }
  // The newest pose, or nothing if none came within `wait`.
  std::optional<LivePose> take(std::chrono::milliseconds wait) {
    std::unique_lock lock(mutex_);
    ready_.wait_for(lock, wait, [&] { return pending_.has_value(); });
    return std::exchange(pending_, std::nullopt);
  }
  int64_t dropped() const {
    std::lock_guard lock(mutex_);
    return dropped_;
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::optional<LivePose> pending_;
  int64_t dropped_ = 0;
};

std::string imageTopic(const LiveSensorOptions& options, const std::string& camera) {
  return "/" + options.robot + "/" + camera + "/image_raw";
}

// Camera `camera`'s frame at `live`, as the dataset renders it (frame_scheduler.cpp).
ros1::Image renderCamera(const DatasetPlan& plan, size_t camera, const LivePose& live, uint64_t drawIndex) {
  const DatasetSpec& spec = plan.spec();
  const CameraSetup& setup = plan.setups()[camera];
  const RenderSettings settings = spec.request.settings(setup.rig);
  const CameraPlacement placement(live.pose, live.velocity, setup.camera->mount, spec.robotTiltDeg);
  Film film = filmFor(settings, false);
  plan.engine().render(placement, settings, film);
  if (spec.recording) film.setResolvedColour(recordFrame(spec.recording->draw(drawIndex), film.image(), drawIndex));
  const ImageRGBA& image = film.image();
  const std::vector<unsigned char> rgba = srgb8Codes(image);
  ros1::Image out;
  out.stamp = live.stamp;
  out.frame = setup.camera->name;
  out.width = static_cast<uint32_t>(image.width);
  out.height = static_cast<uint32_t>(image.height);
  out.step = out.width * 3;
  out.encoding = "rgb8";
  out.data.resize(static_cast<size_t>(out.step) * out.height);
  for (size_t p = 0, n = rgba.size() / 4; p < n; ++p)
    for (size_t c = 0; c < 3; ++c) out.data[p * 3 + c] = rgba[p * 4 + c];
  return out;
}

}  // namespace

LivePose livePoseOf(const ros1::Odometry& odometry) {
  const double* q = odometry.orientationXyzw;
  const double yaw = std::atan2(2.0 * (q[3] * q[2] + q[0] * q[1]), 1.0 - 2.0 * (q[1] * q[1] + q[2] * q[2]));
  LivePose live;
  live.pose = {odometry.position[0], odometry.position[1], yaw * kDegreesPerRadian};
  live.velocity = {odometry.linear[0], odometry.linear[1], odometry.angular[2] * kDegreesPerRadian};
  live.stamp = odometry.stamp;
  return live;
}

LiveSensorReport runLiveSensor(const DatasetSpec& spec, const LiveSensorOptions& options) {
  const DatasetPlan plan(spec, DatasetRunOptions{});
  std::optional<ros1::Transport> transport;
  try {
    transport.emplace("omnicam_" + options.robot, options.masterWaitSeconds);
  } catch (const std::runtime_error& e) {
    throw ExternalError(std::string("ros: ") + e.what() + " (start one with `roscore`, or set ROS_MASTER_URI)");
  }
  for (const CameraSetup& setup : plan.setups()) transport->advertiseImage(imageTopic(options, setup.camera->name));
  NewestPose newest;
  transport->subscribeOdometry(options.odometryTopic, [&](const ros1::Odometry& o) { newest.put(livePoseOf(o)); });

  LiveSensorReport report;
  while (!interruptRequested() && (options.frames == 0 || report.rendered < options.frames)) {
    const std::optional<LivePose> live = newest.take(std::chrono::milliseconds(100));
    if (!live) continue;
    for (size_t c = 0; c < plan.setups().size(); ++c) {
      const uint64_t drawIndex = static_cast<uint64_t>(report.rendered) * plan.setups().size() + c;
      transport->publish(imageTopic(options, plan.setups()[c].camera->name), renderCamera(plan, c, *live, drawIndex));
    }
    ++report.rendered;
  }
  report.dropped = newest.dropped();
  return report;
}

}  // namespace omnicam
