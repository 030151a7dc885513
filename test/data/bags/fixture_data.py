"""The deterministic content of every bag fixture, shared by make_fixtures.py (which
writes it with independent writers) and verify_bag.py (which checks a bag, ours
included, with the `rosbags` reader). test/drivers/bag_test_util.h mirrors it in C++.

Radar samples are multiples of 1/64 and positions multiples of 1/16, so float32 and
float64 hold them exactly and every reader must return them bit for bit.
"""

import math

T0 = 1_700_000_000_000_000_000  # ns since the epoch
RADAR_TOPICS = ['/UWBradar0/readings', '/UWBradar1/readings']
NUM_SCANS = 8        # per radar
NUM_SAMPLES = 64     # per scan
NUM_ODOM = 10
NUM_GROUND_TRUTH = 5
NUM_LASER = 2
NUM_TF = 2
NUM_CHATTER = 3      # std_msgs/msg/String: a type the project skips


def radar_time(sensor, k):
    return T0 + k * 25_000_000 + sensor * 5_000_000


def radar_samples(sensor, k):
    return [((k * 37 + i * 11 + sensor * 101) % 1000) / 64.0 - 7.5 for i in range(NUM_SAMPLES)]


def odom_time(i):
    return T0 + i * 20_000_000 + 1_000_000


def odom_pose(i):
    """x, y, yaw of odometry message i."""
    return i * 0.125, -i * 0.0625, (i - 3) * 0.1


def odom_covariance(i):
    return [0.01 * (i + 1) if r % 7 == 0 else 0.0 for r in range(36)]


def ground_truth_time(j):
    return T0 + j * 40_000_000 + 2_000_000


def ground_truth_pose(j):
    return j * 0.25, j * 0.0625, -j * 0.05


def laser_time(j):
    return T0 + j * 50_000_000 + 3_000_000


def laser_ranges(j):
    return [1.0 + 0.5 * r + j for r in range(16)]


def laser_intensities(j):
    return [r * 2.0 for r in range(16)] if j == 1 else []


def tf_time(j):
    return T0 + j * 60_000_000 + 4_000_000


def chatter_time(j):
    return T0 + j * 70_000_000 + 6_000_000


def split_stamp(t):
    return t // 1_000_000_000, t % 1_000_000_000


def quaternion_from_yaw(yaw):
    return 0.0, 0.0, math.sin(0.5 * yaw), math.cos(0.5 * yaw)


def all_messages():
    """(time, topic, type, description) of every message, unsorted."""
    out = []
    for s, topic in enumerate(RADAR_TOPICS):
        for k in range(NUM_SCANS):
            out.append((radar_time(s, k), topic, 'std_msgs/msg/Float32MultiArray', ('radar', s, k)))
    for i in range(NUM_ODOM):
        out.append((odom_time(i), '/odom', 'nav_msgs/msg/Odometry', ('odom', i)))
    for j in range(NUM_GROUND_TRUTH):
        out.append((ground_truth_time(j), '/ground_truth/odom', 'nav_msgs/msg/Odometry', ('gt', j)))
    for j in range(NUM_LASER):
        out.append((laser_time(j), '/scan', 'sensor_msgs/msg/LaserScan', ('laser', j)))
    for j in range(NUM_TF):
        out.append((tf_time(j), '/tf', 'tf2_msgs/msg/TFMessage', ('tf', j)))
    for j in range(NUM_CHATTER):
        out.append((chatter_time(j), '/chatter', 'std_msgs/msg/String', ('chatter', j)))
    return out
