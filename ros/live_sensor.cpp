#include "live_sensor.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>

#include "atomic_file.h"
#include "dataset_options.h"
#include "dataset_plan.h"
#include "engine_capabilities.h"
#include "errors.h"
#include "film.h"
#include "frame_planes.h"
#include "image.h"
#include "number_format.h"
#include "interrupts.h"
#include "intrinsics_files.h"
#include "input_limits.h"
#include "placement.h"
#include "render_settings.h"
#include "ros_camera_info.h"
#include "ros_transport.h"

namespace omnicam {

namespace {

constexpr double kDegreesPerRadian = 180.0 / M_PI;

// /<robot>/<camera>/<leaf>: image_raw, camera_info, intrinsics.
std::string cameraTopic(const LiveSensorOptions& options, const std::string& camera, const char* leaf) {
  return "/" + options.robot + "/" + camera + "/" + leaf;
}

ros1::CameraInfo cameraInfoMessage(const RosCameraInfo& info, const ros1::Stamp& stamp, const std::string& frame) {
  return {stamp, frame, info.width, info.height, info.distortionModel, info.d, info.k, info.r, info.p};
}

// Camera `camera` on the robot at `live`: its mount, the spec's robot tilt (as a dataset frame's).
CameraPlacement placementOf(const DatasetPlan& plan, size_t camera, const LivePose& live) {
  return CameraPlacement(live.pose, live.velocity, plan.setups()[camera].camera->mount, plan.spec().robotTiltDeg);
}

// InputError if the engine cannot render camera `camera` at `live` as the dataset would refuse
// the frame (dataset_plan.cpp's checks of moving frames).
void checkLiveRender(const DatasetPlan& plan, size_t camera, const LivePose& live) {
  const CameraSetup& setup = plan.setups()[camera];
  const CameraPlacement placement = placementOf(plan, camera, live);
  // As a dataset's frame: the camera within the world (a mount can put it outside where the robot
  // is not, and a fixed rate carries a pose forward), the motion within its limits.
  checkPlacement(placement, {"spp", "image size", "the twist (camera " + quote(setup.camera->name) + ")",
                             "the pose (camera " + quote(setup.camera->name) + ")"});
  checkEngineRenders(plan.engine().kind(), setup.rig, placement);
  if (plan.spec().request.adaptiveSpp > 0 && moving(placement, setup.rig))
    throw InputError("adaptive_spp: not while the robot moves during an exposure (camera " + quote(setup.camera->name) + ")");
}

// The kinds of frame file a live sensor publishes besides the colour, each on its kind's name.
constexpr OutputKind kPlaneKinds[] = {OutputKind::Depth, OutputKind::Instance, OutputKind::Semantic, OutputKind::Normal};

ros1::Image imageHeader(const LivePose& live, const std::string& frame, int width, int height) {
  ros1::Image out;
  out.stamp = live.stamp;
  out.frame = frame;
  out.width = static_cast<uint32_t>(width);
  out.height = static_cast<uint32_t>(height);
  return out;
}

// A plane as the dataset's file holds its values (frame_planes.h): floats as 32FC<n>, ids as 16UC1.
ros1::Image planeImage(const FramePlanes& planes, OutputKind kind, const LivePose& live, const std::string& frame) {
  const OutputKindRow& row = outputRow(kind);
  ros1::Image out = imageHeader(live, frame, planes.width(), planes.height());
  const size_t pixels = static_cast<size_t>(planes.width()) * planes.height();
  if (row.encoding == OutputEncoding::Uint16Png) {
    const std::vector<uint16_t> ids = planes.ids(row.plane);
    out.encoding = "16UC1";
    out.step = out.width * 2;
    out.data.assign(reinterpret_cast<const uint8_t*>(ids.data()), reinterpret_cast<const uint8_t*>(ids.data() + pixels));
  } else {
    const float* values = planes.floats(row.plane);
    out.encoding = "32FC" + std::to_string(row.valuesPerPixel());
    out.step = out.width * 4 * static_cast<uint32_t>(row.valuesPerPixel());
    out.data.assign(reinterpret_cast<const uint8_t*>(values),
                    reinterpret_cast<const uint8_t*>(values + pixels * row.valuesPerPixel()));
  }
  return out;
}

// Camera `camera`'s frame at `live`, as the dataset renders it (frame_scheduler.cpp): the colour
// as rgb8 (the codes of the dataset's PNG), then each plane the spec's outputs ask for.
std::vector<std::pair<const char*, ros1::Image>> renderCamera(const DatasetPlan& plan, size_t camera,
                                                              const LivePose& live, uint64_t drawIndex,
                                                              const std::string& frame) {
  const DatasetSpec& spec = plan.spec();
  const CameraSetup& setup = plan.setups()[camera];
  const RenderSettings settings = spec.request.settings(setup.rig);
  const CameraPlacement placement = placementOf(plan, camera, live);
  const bool wantsAovs = plan.outputs().anyAov();
  Film film = filmFor(settings, wantsAovs);
  plan.engine().render(placement, settings, film);
  if (spec.recording) film.setResolvedColour(recordFrame(spec.recording->draw(drawIndex), film.image(), drawIndex));
  const ImageRGBA& image = film.image();
  const std::vector<unsigned char> rgba = srgb8Codes(image);
  ros1::Image rgb = imageHeader(live, frame, image.width, image.height);
  rgb.step = rgb.width * 3;
  rgb.encoding = "rgb8";
  rgb.data.resize(static_cast<size_t>(rgb.step) * rgb.height);
  for (size_t p = 0, n = rgba.size() / 4; p < n; ++p)
    for (size_t c = 0; c < 3; ++c) rgb.data[p * 3 + c] = rgba[p * 4 + c];
  std::vector<std::pair<const char*, ros1::Image>> images;
  images.emplace_back("image_raw", std::move(rgb));
  const FramePlanes planes{image, film.aovs(), plan.ids().classOfInstance};
  for (const OutputKind kind : kPlaneKinds)
    if (plan.outputs().wants(kind)) images.emplace_back(outputName(kind), planeImage(planes, kind, live, frame));
  return images;
}

using ros1::stampText;

ros1::Diagnostic diagnostic(const LiveSensorOptions& options, const std::string& message, const ros1::Stamp& stamp,
                            int64_t count) {
  ros1::Diagnostic d;
  d.level = ros1::Diagnostic::Warn;
  d.name = "omnicam ros: " + options.robot;
  d.hardwareId = options.robot;
  d.message = message;
  d.values = {{"pose_stamp", stampText(stamp)}, {"count", std::to_string(count)}};
  return d;
}

std::string cameraFrame(const LiveSensorOptions& options, const std::string& camera) {
  return options.robot + "/" + camera;
}

// Camera `camera`'s frame in the robot's: the frame chain of a robot at the origin.
ros1::Transform baseFromCamera(const DatasetPlan& plan, size_t camera, const LiveSensorOptions& options) {
  const CameraSetup& setup = plan.setups()[camera];
  // The frame of the intrinsics camera_info carries (a physical rig's: its best fit's).
  const Rigid chain = worldFromModelCamera(placementOf(plan, camera, LivePose{}), *setup.model);
  const Eigen::Quaterniond q(chain.linear());
  ros1::Transform t;
  t.parent = options.baseFrame;
  t.child = cameraFrame(options, setup.camera->name);
  for (int i = 0; i < 3; ++i) t.translation[i] = chain.translation()[i];
  t.rotationXyzw[0] = q.x(), t.rotationXyzw[1] = q.y(), t.rotationXyzw[2] = q.z(), t.rotationXyzw[3] = q.w();
  return t;
}

}  // namespace

std::string problemWith(const ros1::Odometry& o, const ros1::Stamp* lastAccepted, const ros1::Stamp& now) {
  const double* numbers[] = {o.position, o.orientationXyzw, o.linear, o.angular};
  const size_t counts[] = {3, 4, 3, 3};
  for (size_t k = 0; k < 4; ++k)
    for (size_t i = 0; i < counts[k]; ++i)
      if (!std::isfinite(numbers[k][i])) return "a number of the pose or twist is not finite";
  const double* q = o.orientationXyzw;
  if (std::abs(std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]) - 1.0) > 1e-3)
    return "the orientation is not a unit quaternion";
  if (o.stamp.sec == 0 && o.stamp.nsec == 0) return "its stamp is zero (set header.stamp, e.g. rostopic pub -s with stamp: now)";
  // The limits of every pose and velocity (base/input_limits.h, as a dataset's).
  if (std::abs(o.position[0]) > limits::kMaxWorldCoordinate || std::abs(o.position[1]) > limits::kMaxWorldCoordinate)
    return "the position is beyond ±" + shortNumber(limits::kMaxWorldCoordinate / 1000.0) + " km";
  if (std::hypot(o.linear[0], o.linear[1]) > limits::kMaxSpeed)
    return "the speed is above " + shortNumber(limits::kMaxSpeed) + " m/s";
  if (std::abs(o.angular[2]) * kDegreesPerRadian > limits::kMaxYawRateDegPerS)
    return "the yaw rate is above " + shortNumber(limits::kMaxYawRateDegPerS) + " degrees/s (" +
           shortNumber(limits::kMaxYawRateDegPerS / kDegreesPerRadian) + " rad/s)";
  if (lastAccepted && (o.stamp.sec < lastAccepted->sec || (o.stamp.sec == lastAccepted->sec && o.stamp.nsec <= lastAccepted->nsec)))
    return "its stamp " + stampText(o.stamp) + " is not after the last pose's, " + stampText(*lastAccepted);
  if (!now.zero() && o.stamp.nanoseconds() - now.nanoseconds() > std::llround(ros1::kMostStampAheadSeconds * 1e9))
    return "its stamp " + stampText(o.stamp) + " is more than " + shortNumber(ros1::kMostStampAheadSeconds) + " s after ROS time now, " +
           stampText(now) + " (a clock that far ahead would hold every later pose back)";
  return "";
}

bool NewestPose::put(const LivePose& pose) {
  bool replaced = false;
  {
    std::lock_guard lock(mutex_);
    replaced = pending_.has_value();
    if (replaced) ++dropped_;
    pending_ = pose;
  }
  ready_.notify_one();
  return replaced;
}

std::optional<LivePose> NewestPose::take(std::chrono::milliseconds wait) {
  std::unique_lock lock(mutex_);
  ready_.wait_for(lock, wait, [&] { return pending_.has_value(); });
  return std::exchange(pending_, std::nullopt);
}

bool saysRepeat(int64_t count) { return count > 0 && ((count & (count - 1)) == 0 || count % 1024 == 0); }

int64_t NewestPose::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

ros1::Stamp tickAtOrBefore(const ros1::Stamp& now, int64_t periodNs) {
  return ros1::Stamp::ofNanoseconds(now.nanoseconds() / periodNs * periodNs);
}

std::optional<LivePose> poseAtTick(const LivePose& latest, const ros1::Stamp& tick, double maxAgeSeconds,
                                   std::string& problem) {
  const double seconds = static_cast<double>(tick.nanoseconds() - latest.stamp.nanoseconds()) * 1e-9;
  if (std::abs(seconds) > maxAgeSeconds) {
    char text[160];
    std::snprintf(text, sizeof text, "the newest pose, at %s, is %.3f s from the tick at %s (more than %g s)",
                  stampText(latest.stamp).c_str(), std::abs(seconds), stampText(tick).c_str(), maxAgeSeconds);
    problem = text;
    return std::nullopt;
  }
  return LivePose{poseAfter(latest.pose, latest.velocity, seconds), latest.velocity, tick};
}

LivePose livePoseOf(const ros1::Odometry& odometry) {
  const double* q = odometry.orientationXyzw;
  const double yaw = std::atan2(2.0 * (q[3] * q[2] + q[0] * q[1]), 1.0 - 2.0 * (q[1] * q[1] + q[2] * q[2]));
  LivePose live;
  live.pose = {odometry.position[0], odometry.position[1], yaw * kDegreesPerRadian};
  live.velocity = {odometry.linear[0], odometry.linear[1], odometry.angular[2] * kDegreesPerRadian};
  live.stamp = odometry.stamp;
  return live;
}

namespace {

// A tf2 frame id: a ROS name, not empty, without the leading '/' that tf1 took and tf2 refuses
// (every pose would be refused for it).
void checkFrameId(const std::string& frame, const std::string& what) {
  if (frame.empty()) throw InputError("ros: " + what + " is empty: give a tf frame id (such as map, odom or base_link)");
  if (frame.front() == '/') {
    const size_t name = frame.find_first_not_of('/');
    throw InputError("ros: " + what + " " + quote(frame) + ": a tf2 frame id does not start with '/'" +
                     (name == std::string::npos ? std::string() : " (give " + quote(frame.substr(name)) + ")"));
  }
}

// What a live sensor cannot take, before any master is looked for: names ROS refuses (a camera
// called "front-left"), frame ids tf2 refuses, the base frame as its own parent, a spec with
// vibration (of its rigs or the robot's tilt).
void checkLiveSpec(const DatasetPlan& plan, const LiveSensorOptions& options) {
  if (options.robot.empty() || options.robot.find('/') != std::string::npos)
    throw InputError("ros: robot name " + quote(options.robot) +
                     ": one name, without '/' (it is the topics' namespace, the frames' prefix and the node's name omnicam_ROBOT)");
  if (options.tfParent.empty() && options.odometryTopic.empty()) throw InputError("ros: the odometry topic is empty");
  checkFrameId(options.baseFrame, "the robot's frame");
  if (!options.tfParent.empty()) {
    checkFrameId(options.tfParent, "the poses' frame");
    if (options.tfParent == options.baseFrame)
      throw InputError("ros: the poses' frame is the robot's frame itself (" + quote(options.baseFrame) +
                       "): give the frame the robot moves in (map or odom)");
  }
  // Each name ROS will see, with what the user gave it as.
  std::vector<std::pair<std::string, std::string>> names = {
      {"/" + options.robot, "the robot name"},
      options.tfParent.empty() ? std::pair{options.odometryTopic, std::string("the odometry topic")}
                               : std::pair{"/" + options.tfParent, std::string("the poses' frame")},
      {"/" + options.baseFrame, "the robot's frame"}};
  for (size_t c = 0; c < plan.setups().size(); ++c) {
    const std::string& camera = plan.setups()[c].camera->name;
    names.push_back({cameraTopic(options, camera, "image_raw"),
                     "camera " + quote(camera) + " (" + showPath(plan.spec().file) + ": cameras[" + std::to_string(c) + "].name)"});
  }
  for (const auto& [name, given] : names)
    if (const std::string why = ros1::invalidGraphName(name); !why.empty())
      throw InputError("ros: " + given + ": " + quote(name) + " is not a ROS name: " + why);
  // Any vibration, the robot's tilt alone included (a rig that does not shake still rocks).
  if (!plan.spec().vibration.none())
    throw InputError(showPath(plan.spec().file) +
                     ": vibration: a live sensor renders each pose as it comes; shake the rig or rock the robot in a dataset instead");
}

// A fixed-rate camera's clock: each tick of the grid of round(10⁹/rate) ns that ROS time passes is
// posted to the spinner thread. Ticks the clock jumps over (simulated time) are not made up for.
class Ticker {
 public:
  Ticker(ros1::Transport& transport, double rateHz, std::function<void(const ros1::Stamp&)> tick)
      : transport_(transport),
        periodNs_(std::max<int64_t>(1, std::llround(1e9 / rateHz))),
        tick_(std::move(tick)),
        thread_([this] { run(); }) {}
  ~Ticker() {
    stop_ = true;
    thread_.join();
  }
  Ticker(const Ticker&) = delete;
  Ticker& operator=(const Ticker&) = delete;

 private:
  void run() {
    int64_t last = 0;
    while (!stop_) {
      const ros1::Stamp now = transport_.now();  // zero under simulated time until /clock comes
      const ros1::Stamp tick = tickAtOrBefore(now, periodNs_);
      if (tick.nanoseconds() < last) last = 0;  // time went back (a simulation reset): tick anew
      if (!now.zero() && tick.nanoseconds() > last) {
        last = tick.nanoseconds();
        transport_.post([work = tick_, tick] { work(tick); });  // may run after this Ticker is gone
        continue;
      }
      // Simulated time moves when /clock says: look again each millisecond.
      const int64_t untilNext = tick.nanoseconds() + periodNs_ - now.nanoseconds();
      std::this_thread::sleep_for(transport_.simulatedTime() || now.zero()
                                      ? std::chrono::nanoseconds(1000000)
                                      : std::chrono::nanoseconds(std::clamp<int64_t>(untilNext, 0, 50000000)));
    }
  }

  ros1::Transport& transport_;
  const int64_t periodNs_;
  const std::function<void(const ros1::Stamp&)> tick_;
  std::atomic<bool> stop_ = false;
  std::thread thread_;  // last: starts once the rest is set
};

void startRecording(ros1::Transport& transport, const std::string& path) {
  const std::filesystem::path bag(path);
  const std::filesystem::path partial = bag.parent_path() / atomicTemporaryName(bag.filename().string());
  try {
    transport.record(partial.string(), bag.string());
  } catch (const std::runtime_error& e) {
    throw OutputError(showPath(path) + ": cannot write the bag (" + e.what() + ")");
  }
}

void finishRecording(ros1::Transport& transport, const std::string& path) {
  try {
    transport.finishRecording();
  } catch (const std::runtime_error& e) {
    throw OutputError(showPath(path) + ": cannot finish the bag (" + e.what() + ")");
  }
}

// Every camera's topics announced, its mount on /tf_static, a model ROS has no name for on a
// latched topic; returns each camera's camera_info, sent with every frame.
std::vector<RosCameraInfo> announceCameras(ros1::Transport& transport, const DatasetPlan& plan, const LiveSensorOptions& options) {
  std::vector<RosCameraInfo> infos;
  std::vector<ros1::Transform> mounts;
  for (const CameraSetup& setup : plan.setups()) {
    const std::string& name = setup.camera->name;
    transport.advertiseImage(cameraTopic(options, name, "image_raw"));
    for (const OutputKind kind : kPlaneKinds)
      if (plan.outputs().wants(kind)) transport.advertiseImage(cameraTopic(options, name, outputName(kind)));
    transport.advertiseCameraInfo(cameraTopic(options, name, "camera_info"));
    infos.push_back(rosCameraInfoOf(*setup.model));
    mounts.push_back(baseFromCamera(plan, infos.size() - 1, options));
    if (!infos.back().intrinsicsJson.empty())
      transport.publishLatchedText(cameraTopic(options, name, "intrinsics"), infos.back().intrinsicsJson);
  }
  transport.publishStaticTransforms(mounts);
  return infos;
}

// Every camera's frame at `live`, rendered first and then published: a pose the engine cannot
// render (a motion it does not take, adaptive sampling while the shutter moves) throws
// InputError before anything is sent. `frameIndex` draws the recording camera's faults.
void renderAndPublish(ros1::Transport& transport, const DatasetPlan& plan, const LiveSensorOptions& options,
                      const std::vector<RosCameraInfo>& infos, const LivePose& live, int64_t frameIndex) {
  std::vector<std::vector<std::pair<const char*, ros1::Image>>> frames;
  for (size_t c = 0; c < plan.setups().size(); ++c) {
    checkLiveRender(plan, c, live);
    const uint64_t drawIndex = static_cast<uint64_t>(frameIndex) * plan.setups().size() + c;
    frames.push_back(renderCamera(plan, c, live, drawIndex, cameraFrame(options, plan.setups()[c].camera->name)));
  }
  for (size_t c = 0; c < plan.setups().size(); ++c) {
    const std::string& name = plan.setups()[c].camera->name;
    for (const auto& [leaf, image] : frames[c]) transport.publish(cameraTopic(options, name, leaf), image);
    transport.publish(cameraTopic(options, name, "camera_info"), cameraInfoMessage(infos[c], live.stamp, cameraFrame(options, name)));
  }
}

// The poses ROS sends and what becomes of them: everything here runs on the transport's spinner
// thread but `newest` (which the render loop takes from) and the count of refusals.
struct LivePoses {
  explicit LivePoses(const LiveSensorOptions& o) : options(o) {}
  const LiveSensorOptions& options;
  ros1::Transport* transport = nullptr;
  NewestPose newest;
  std::optional<ros1::Stamp> lastAccepted;
  std::optional<LivePose> latest;  // at a fixed rate from odometry: the newest pose
  ros1::Stamp lastNow;             // ROS time when the last pose or tick came
  std::atomic<int64_t> refused = 0;
  std::atomic<int64_t> skippedTicks = 0;  // at a fixed rate: ticks with no pose near enough
  int64_t skippedSinceAFrame = 0;         // of those, since the last tick that rendered: an outage's
  bool saidWaitingForTf = false;          // at a fixed rate from tf: before the tree's first pose

  void refuse(const std::string& why, const ros1::Stamp& stamp) {
    transport->publish(diagnostic(options, "pose refused: " + why, stamp, ++refused));
  }
  // A tick is not a pose: counted apart, so that a robot that stops sending odometry is not
  // taken for one whose poses are wrong.
  // Each outage is said from its first tick on (saysRepeat of its own count), with the total.
  void skipTick(const std::string& why, const ros1::Stamp& stamp) {
    const int64_t total = ++skippedTicks;
    if (saysRepeat(++skippedSinceAFrame)) transport->publish(diagnostic(options, "tick skipped: " + why, stamp, total));
  }
  void render(const LivePose& live) {
    if (newest.put(live))
      if (const int64_t count = newest.dropped(); saysRepeat(count))
        transport->publish(diagnostic(options, "pose dropped: a newer one came before it was rendered", live.stamp, count));
  }
  // A simulation reset sends ROS time back: the stamps of the new run start anew.
  void startAnewIfTimeWentBack() {
    const ros1::Stamp now = transport->now();
    if (now < lastNow) {
      lastAccepted.reset();
      latest.reset();
      saidWaitingForTf = false;
      skippedSinceAFrame = 0;
      transport->publish(diagnostic(options, "ROS time went back (a simulation reset?): poses start anew", now, 0));
    }
    lastNow = now;
  }
  void accept(const ros1::Odometry& o) {
    startAnewIfTimeWentBack();
    if (const std::string problem = problemWith(o, lastAccepted ? &*lastAccepted : nullptr, transport->now()); !problem.empty())
      return refuse(problem, o.stamp);
    lastAccepted = o.stamp;
    if (options.rateHz > 0 && options.tfParent.empty())
      latest = livePoseOf(o);
    else
      render(livePoseOf(o));
  }
  void tick(const ros1::Stamp& stamp) {
    startAnewIfTimeWentBack();
    if (!options.tfParent.empty()) return transport->requestTransform(stamp);
    if (!latest) return;  // no odometry yet
    std::string problem;
    if (const std::optional<LivePose> live = poseAtTick(*latest, stamp, options.maxPoseAgeSeconds, problem)) {
      skippedSinceAFrame = 0;
      render(*live);
    } else
      skipTick(problem, stamp);
  }
  void subscribe() {
    if (options.tfParent.empty())
      return transport->subscribeOdometry(options.odometryTopic, [this](const ros1::Odometry& o) { accept(o); });
    ros1::TransformHandlers handlers;
    handlers.pose = [this](const ros1::Odometry& o) { accept(o); };
    handlers.gap = [this](const ros1::Stamp& stamp, const std::string& why) {
      const std::string reason = "no transform from " + options.tfParent + " to " + options.baseFrame + ": " + why;
      // Ticks before the tree's first pose are no poses, as ticks before the first odometry: said
      // once, not refused at the rate (a tree that comes up after the node would flood /diagnostics).
      if (options.rateHz > 0 && !lastAccepted) {
        if (!std::exchange(saidWaitingForTf, true))
          transport->publish(diagnostic(options, "waiting for the tree's first pose (said once): " + reason, stamp, 0));
        return;
      }
      refuse(reason, stamp);
    };
    transport->subscribeTransform(options.tfParent, options.baseFrame, /*eachMove=*/options.rateHz == 0, std::move(handlers));
  }
};

// The transport, registered with a master; nullptr if a signal came while waiting for one.
ros1::Transport* connect(std::optional<ros1::Transport>& transport, const LiveSensorOptions& options) {
  try {
    return &transport.emplace("omnicam_" + options.robot, options.masterWaitSeconds,
                              [] { return interruptRequested().load(); }, options.rosArguments, options.onWaitingForMaster);
  } catch (const ros1::StoppedWaitingForMaster&) {
    return nullptr;
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("ros: ") + e.what());
  } catch (const std::runtime_error& e) {
    throw ExternalError(std::string("ros: ") + e.what() + " (start one with `roscore`, or set ROS_MASTER_URI)");
  }
}

}  // namespace

LiveSensorReport runLiveSensor(const DatasetSpec& spec, const LiveSensorOptions& options,
                               const std::function<void(const LiveSensorTopics& topics)>& ready) {
  const DatasetPlan plan(spec, DatasetRunOptions{});
  checkLiveSpec(plan, options);
  if (options.onNotes) {
    std::vector<std::string> notes = plan.notes();
    if (spec.calibration)
      notes.push_back(showPath(spec.file) + ": calibration: does nothing live (the robot's poses come from ROS, and each "
                                            "calibration target stays where the scene puts it)");
    if (spec.euroc) notes.push_back(showPath(spec.file) + ": euroc: does nothing live (images go out as ROS messages)");
    if (!notes.empty()) options.onNotes(notes);
  }
  // Declared before the transport: its destructor stops the callbacks before these go.
  LivePoses poses(options);
  std::optional<ros1::Transport> connection;
  ros1::Transport* connected = connect(connection, options);
  if (!connected) {
    LiveSensorReport stopped;
    stopped.stoppedWaitingForMaster = true;
    return stopped;
  }
  ros1::Transport& transport = *connected;
  poses.transport = &transport;
  if (!options.recordBag.empty()) startRecording(transport, options.recordBag);
  const std::vector<RosCameraInfo> infos = announceCameras(transport, plan, options);
  poses.subscribe();
  std::optional<Ticker> ticker;  // after the transport: stops before it
  if (options.rateHz > 0) ticker.emplace(transport, options.rateHz, [&poses](const ros1::Stamp& tick) { poses.tick(tick); });

  if (ready) {
    LiveSensorTopics topics;
    if (options.tfParent.empty()) topics.odometry = transport.resolvedName(options.odometryTopic);
    for (const CameraSetup& setup : plan.setups())
      topics.images.push_back(transport.resolvedName(cameraTopic(options, setup.camera->name, "image_raw")));
    ready(topics);
  }
  LiveSensorReport report;
  auto masterChecked = std::chrono::steady_clock::now();
  while (!interruptRequested() && (options.frames == 0 || report.rendered < options.frames)) {
    if (transport.shutDownByRos()) {  // deaf from now on: no pose would come
      report.shutDownByRos = true;
      break;
    }
    // Once a second: a master that went away and came back gets every topic again.
    if (std::chrono::steady_clock::now() - masterChecked > std::chrono::seconds(1)) {
      masterChecked = std::chrono::steady_clock::now();
      if (transport.registerAgainIfTheMasterCameBack())
        transport.publish(
            diagnostic(options, "the ROS master came back: every topic registered again", ros1::Stamp{}, ++report.newMasters));
    }
    const std::optional<LivePose> live = poses.newest.take(std::chrono::milliseconds(100));
    if (!live) continue;
    try {
      renderAndPublish(transport, plan, options, infos, *live, report.rendered);
      ++report.rendered;
    } catch (const InputError& e) {
      poses.refuse(e.what(), live->stamp);  // (the render loop's refusals race no callback: refused is atomic)
    } catch (const Interrupted& e) {
      // The external renderer was ended with the process group (base/interrupts.h): the frame is
      // lost, the frames before it are not — the bag is finished below.
      report.frameGivenUp = e.what();
      break;
    }
  }
  ticker.reset();
  if (!options.recordBag.empty()) finishRecording(transport, options.recordBag);
  report.dropped = poses.newest.dropped();
  report.refused = poses.refused;
  report.skippedTicks = poses.skippedTicks;
  return report;
}

}  // namespace omnicam
