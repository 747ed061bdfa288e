"""Writes images to a ROS 1 bag with Debian's python3-rosbag (calibration/rosbag_file.h).

Run by omnicam in a private job folder: reads `images.bin` (written by omnicam, layout below)
and writes `images.bag` there, uncompressed; omnicam then moves the bag's bytes into the
dataset. Takes no paths from anyone: both names are fixed.

images.bin: b"OMNIBAG2", then per image up to the end of the file (little-endian):
  u32 topic length, topic (UTF-8), u32 frame_id length, frame_id, i64 stamp (ns), u32 seq,
  u32 width, u32 height, width*height*3 bytes of rgb8, row by row from the top.

One image at a time is read and written (rosbag flushes its chunk when an image fills it), so
memory does not grow with the bag; `peak.txt` gets this process's peak resident memory (KiB),
which omnicam's tests check.
"""
import resource
import struct
import sys

import genpy
import rosbag
from sensor_msgs.msg import Image
from std_msgs.msg import Header

# ros::TIME_MIN: the earliest record time C++ rosbag writes or reads back.
TIME_MIN = genpy.Time(0, 1)


def read_exactly(f, n):
    data = f.read(n)
    if len(data) != n:
        raise SystemExit("write_rosbag: images.bin is truncated")
    return data


def read_string(f):
    (length,) = struct.unpack("<I", read_exactly(f, 4))
    return read_exactly(f, length).decode("utf-8")


def main():
    with open("images.bin", "rb") as f, rosbag.Bag("images.bag", "w") as bag:
        if read_exactly(f, 8) != b"OMNIBAG2":
            raise SystemExit("write_rosbag: images.bin is not omnicam's")
        while True:
            length = f.read(4)
            if not length:
                break
            if len(length) != 4:
                raise SystemExit("write_rosbag: images.bin is truncated")
            topic = read_exactly(f, struct.unpack("<I", length)[0]).decode("utf-8")
            frame_id = read_string(f)
            stamp_ns, seq, width, height = struct.unpack("<qIII", read_exactly(f, 20))
            # Exact: secs and nsecs from the integer, never through a float.
            stamp = genpy.Time(stamp_ns // 1_000_000_000, stamp_ns % 1_000_000_000)
            message = Image(header=Header(seq=seq, stamp=stamp, frame_id=frame_id), height=height, width=width,
                            encoding="rgb8", is_bigendian=0, step=3 * width,
                            data=read_exactly(f, 3 * width * height))
            # Kalibr reads header.stamp; the bag's record time is the same, but at least ROS's
            # TIME_MIN (0 s 1 ns): C++ rosbag (rosbag play, rosbag::View) skips earlier messages.
            bag.write(topic, message, max(stamp, TIME_MIN))
            del message
    with open("peak.txt", "w") as peak:
        peak.write("%d\n" % resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)


if __name__ == "__main__":
    sys.exit(main())
