#!/usr/bin/python3
"""omnicam.Renderer driven from a rospy callback: a live mirror camera in a page of Python.

    python3 ros_camera.py SCENE [--odom /odom] [--image /omnicam/image_raw] [--frames N]

Each nav_msgs/Odometry message is a pose (x, y and the yaw of its quaternion). The newest pose
is rendered off the ROS thread, in this script's main loop, and published as rgb8, stamped with
the pose's stamp. Poses that come while a frame renders replace each other. `omnicam ros SPEC`
(docs/ros.md) is the full node, with every camera of a dataset spec, camera_info, planes, tf and
diagnostics; this is the few lines to start from when a Python stack wants its own.

Debian's rospy and omnicam's module must both be importable: /usr/bin/python3 with
PYTHONPATH=build/python, or the venv of docs/python.md ("Installing").
"""

import argparse
import math
import queue

import numpy as np
import rospy
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Image

import omnicam


def pose_of(message):
    """(x, y, yaw in degrees) of an odometry message, as `omnicam ros` reads it."""
    p, q = message.pose.pose.position, message.pose.pose.orientation
    yaw = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
    return (p.x, p.y, yaw * (180.0 / math.pi))


def image_message(rgba, stamp, frame):
    codes = omnicam.srgb8(rgba)[..., :3]  # the codes a PNG of the frame holds
    message = Image(height=codes.shape[0], width=codes.shape[1], encoding="rgb8", is_bigendian=0,
                    step=codes.shape[1] * 3, data=np.ascontiguousarray(codes).tobytes())
    message.header.stamp, message.header.frame_id = stamp, frame
    return message


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene")
    parser.add_argument("--odom", default="/odom")
    parser.add_argument("--image", default="/omnicam/image_raw")
    parser.add_argument("--frames", type=int, default=0, help="stop after N poses (default: until Ctrl-C)")
    args = parser.parse_args(rospy.myargv()[1:])

    renderer = omnicam.Renderer(omnicam.load_scene(args.scene))
    newest = queue.Queue(maxsize=1)  # the newest pose only: a new one replaces one not yet rendered

    def on_odometry(message):
        try:
            newest.get_nowait()
        except queue.Empty:
            pass
        newest.put((pose_of(message), message.header.stamp))

    rospy.init_node("omnicam_python_camera", disable_signals=False)
    publisher = rospy.Publisher(args.image, Image, queue_size=2)
    rospy.Subscriber(args.odom, Odometry, on_odometry, queue_size=10)
    print("ros_camera: ready", flush=True)
    rendered = 0
    while not rospy.is_shutdown() and (args.frames == 0 or rendered < args.frames):
        try:
            pose, stamp = newest.get(timeout=0.1)
        except queue.Empty:
            continue
        frame = renderer.render(pose, spp=4, shading="lit")
        publisher.publish(image_message(frame["rgb"], stamp, "omnicam"))
        rendered += 1
    print(f"ros_camera: {rendered} pose{'' if rendered == 1 else 's'} rendered", flush=True)


if __name__ == "__main__":
    main()
