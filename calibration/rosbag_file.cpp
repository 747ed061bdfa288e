#include "rosbag_file.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "data_files.h"
#include "errors.h"
#include "external_process.h"
#include "job_folder.h"
#include "safe_files.h"
#include "sha256.h"

namespace omnicam {

namespace {

// The writer's interpreter: Debian's, where python3-rosbag is installed (not a virtualenv's).
constexpr const char* kPython = "/usr/bin/python3";
// Bags omnicam writes: a calibration sequence's images (the dataset's frame limits bound them).
constexpr int64_t kMaxBagBytes = int64_t{1} << 40;
constexpr double kWriterTimeoutSeconds = 3600.0;
// The bag is copied into the dataset this much at a time.
constexpr size_t kCopyPieceBytes = size_t{1} << 20;

// Absolute: the writer runs in its job folder.
std::string writerScript() {
  const char* env = std::getenv("OMNICAM_ROSBAG_WRITER");
  return std::filesystem::absolute(env ? std::filesystem::path(env) : dataFile("calibration/write_rosbag.py")).string();
}

// Little-endian, as write_rosbag.py reads them, whatever the host's order.
void putLittleEndian(std::ofstream& out, uint64_t v, int bytes) {
  for (int k = 0; k < bytes; ++k) out.put(static_cast<char>((v >> (8 * k)) & 0xff));
}
void put32(std::ofstream& out, uint32_t v) { putLittleEndian(out, v, 4); }
void putString(std::ofstream& out, const std::string& s) {
  put32(out, static_cast<uint32_t>(s.size()));
  out.write(s.data(), static_cast<std::streamsize>(s.size()));
}

}  // namespace

WrittenBag writeImageBag(const SafeFolder& dir, const std::string& relative, const BagImageSource& next) {
  const JobFolder job("omnicam-rosbag", false);
  WrittenBag written;
  {
    // The writer's input, image by image: each is dropped once written.
    std::ofstream out(job.path() + "/images.bin", std::ios::binary);
    out.write("OMNIBAG2", 8);
    while (std::optional<BagImage> image = next()) {
      if (image->rgb8.size() != static_cast<size_t>(image->width) * image->height * 3)
        throw std::logic_error("writeImageBag: an image's bytes are not width × height × 3");
      putString(out, image->topic);
      putString(out, image->frameId);
      putLittleEndian(out, static_cast<uint64_t>(image->stampNs), 8);
      put32(out, image->seq);
      put32(out, static_cast<uint32_t>(image->width));
      put32(out, static_cast<uint32_t>(image->height));
      out.write(image->rgb8.data(), static_cast<std::streamsize>(image->rgb8.size()));
      written.largestImageBytes = std::max(written.largestImageBytes, static_cast<int64_t>(image->rgb8.size()));
      ++written.images;
    }
    if (!out) throw OutputError("ROS bag: cannot write the writer's input in " + showPath(job.path()));
  }
  const ProcessResult run = runProcess({kPython, writerScript()}, job.path(), job.path() + "/writer.log", kWriterTimeoutSeconds);
  if (run.notFound) throw ExternalError(std::string("ROS bag: ") + kPython + " not found (make deps installs it with python3-rosbag)");
  if (run.exitCode != 0 || run.timedOut)
    throw ExternalError("ROS bag: python3-rosbag's writer failed (make deps installs python3-rosbag and python3-sensor-msgs): " +
                             run.logTail);
  // The writer's own account of its memory (peak.txt: ru_maxrss in KiB).
  std::ifstream peak(job.path() + "/peak.txt");
  int64_t peakKiB = 0;
  if (peak >> peakKiB) written.writerPeakBytes = peakKiB * 1024;
  // Into the dataset piece by piece, hashed on the way.
  checkFileInside(job.path(), "images.bag", kMaxBagBytes);
  std::ifstream bag(job.path() + "/images.bag", std::ios::binary);
  Sha256 hash;
  std::string piece(kCopyPieceBytes, '\0');
  dir.writeFileFrom(relative, [&](std::string_view& view) {
    bag.read(piece.data(), static_cast<std::streamsize>(piece.size()));
    const std::streamsize got = bag.gcount();
    if (got <= 0) {
      if (bag.bad()) throw OutputError("ROS bag: cannot read the writer's bag in " + showPath(job.path()));
      return false;
    }
    view = std::string_view(piece.data(), static_cast<size_t>(got));
    hash.update(view);
    written.bytes += got;
    return true;
  }, Durability::Unsynced);
  written.sha256 = hash.hex();
  return written;
}

void checkImageBagWriter() {
  const JobFolder job("omnicam-rosbag", false);
  const ProcessResult run = runProcess({kPython, "-c", "import genpy, rosbag, sensor_msgs.msg, std_msgs.msg"}, job.path(),
                                       job.path() + "/check.log", kWriterTimeoutSeconds);
  if (run.notFound) throw ExternalError(std::string("ROS bag: ") + kPython + " not found (make deps installs it with python3-rosbag)");
  if (run.exitCode != 0 || run.timedOut)
    throw ExternalError("ROS bag: Debian's python3-rosbag or python3-sensor-msgs is missing (make deps installs them): " + run.logTail);
}

}  // namespace omnicam
