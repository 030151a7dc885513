#!/usr/bin/env python3
"""Checks a bag holding the fixture_data.py content with independent readers: the
`rosbags` reader (every message decoded and compared exactly) and, for MCAP, the `mcap`
reader with CRC validation and its summary. Used by the C++ tests on bags that our
BagWriter wrote. Exit status 0 and a last line "OK ..." when everything matches.

    .venv/bin/python test/data/bags/verify_bag.py BAG_DIR
"""

import math
import pathlib
import sys

import numpy as np
from mcap.reader import make_reader
from rosbags.highlevel import AnyReader
from rosbags.typesys import Stores, get_typestore
from ruamel.yaml import YAML

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import fixture_data as fd  # noqa: E402


def fail(msg):
    print(f'MISMATCH: {msg}')
    sys.exit(1)


def same(a, b, what):
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or not np.array_equal(a, b):
        fail(f'{what}: {a!r} != {b!r}')


def check_odometry(msg, t, pose, cov, twist, what):
    x, y, yaw = pose
    qx, qy, qz, qw = fd.quaternion_from_yaw(yaw)
    sec, nsec = fd.split_stamp(t)
    p, q = msg.pose.pose.position, msg.pose.pose.orientation
    same([msg.header.stamp.sec, msg.header.stamp.nanosec], [sec, nsec], what + ' stamp')
    if msg.header.frame_id != 'odom' or msg.child_frame_id != 'base_link':
        fail(what + ' frames')
    same([p.x, p.y, p.z], [x, y, 0.0], what + ' position')
    same([q.x, q.y, q.z, q.w], [qx, qy, qz, qw], what + ' orientation')
    same(msg.pose.covariance, cov, what + ' covariance')
    tw = msg.twist.twist
    same([tw.linear.x, tw.angular.z], list(twist), what + ' twist')


def check_message(msg, t, desc):
    kind = desc[0]
    what = f'{kind} {desc[1:]} at {t}'
    if kind == 'radar':
        _, s, k = desc
        same(msg.data, np.array(fd.radar_samples(s, k), dtype=np.float32), what + ' samples')
        d = msg.layout.dim
        if len(d) != 1 or d[0].label != 'samples' or d[0].size != fd.NUM_SAMPLES:
            fail(what + ' layout')
    elif kind == 'odom':
        i = desc[1]
        check_odometry(msg, t, fd.odom_pose(i), fd.odom_covariance(i), (0.25, 0.1 * (i % 3)), what)
    elif kind == 'gt':
        check_odometry(msg, t, fd.ground_truth_pose(desc[1]), [0.0] * 36, (0.0, 0.0), what)
    elif kind == 'laser':
        j = desc[1]
        same(msg.ranges, np.array(fd.laser_ranges(j), dtype=np.float32), what + ' ranges')
        same(msg.intensities, np.array(fd.laser_intensities(j), dtype=np.float32),
             what + ' intensities')
        same([msg.angle_min, msg.angle_increment, msg.range_max], [-1.5, 0.1875, 8.0], what)
    elif kind == 'tf':
        j = desc[1]
        if len(msg.transforms) != 2:
            fail(what + ' count')
        for n, tr in enumerate(msg.transforms):
            qx, qy, qz, qw = fd.quaternion_from_yaw(0.5 * n + j)
            r = tr.transform.rotation
            same([tr.transform.translation.x, tr.transform.translation.y], [1.0 * j, 0.18 * n], what)
            same([r.x, r.y, r.z, r.w], [qx, qy, qz, qw], what + ' rotation')
    elif kind == 'chatter':
        if msg.data != f'hello {desc[1]}':
            fail(what)


def main():
    bag = pathlib.Path(sys.argv[1])
    expected = {(t, topic): (msgtype, desc) for t, topic, msgtype, desc in fd.all_messages()}
    typestore = get_typestore(Stores.ROS2_HUMBLE)
    seen = 0
    last = -1
    with AnyReader([bag], default_typestore=typestore) as reader:
        for conn, t, raw in reader.messages():
            key = (t, conn.topic)
            if key not in expected:
                fail(f'unexpected message {key}')
            msgtype, desc = expected[key]
            if conn.msgtype != msgtype:
                fail(f'{conn.topic} has type {conn.msgtype}, expected {msgtype}')
            if t < last:
                fail('messages out of time order')
            last = t
            check_message(reader.deserialize(raw, conn.msgtype), t, desc)
            seen += 1
    if seen != len(expected):
        fail(f'read {seen} messages, expected {len(expected)}')
    meta = YAML(typ='safe').load((bag / 'metadata.yaml').read_text())['rosbag2_bagfile_information']
    if meta['message_count'] != len(expected):
        fail('metadata.yaml message_count')
    extra = ''
    if meta['storage_identifier'] == 'mcap':
        with (bag / meta['relative_file_paths'][0]).open('rb') as f:
            r = make_reader(f, validate_crcs=True)
            summary = r.get_summary()
            if summary is None or summary.statistics is None:
                fail('MCAP file has no summary statistics')
            if summary.statistics.message_count != len(expected) or not summary.chunk_indexes:
                fail('MCAP summary statistics/chunk indexes')
            n = sum(1 for _ in r.iter_messages(log_time_order=True))
            if n != len(expected):
                fail(f'mcap reader read {n} messages')
            profile = r.get_header().profile
            if profile != 'ros2':
                fail(f'MCAP profile {profile!r}')
            for schema in summary.schemas.values():
                if schema.encoding != 'ros2msg' or not schema.data:
                    fail(f'schema {schema.name} without ros2msg definition')
        extra = f', mcap: {len(summary.chunk_indexes)} chunks, CRCs valid'
    print(f'OK {seen} messages read back exactly with rosbags{extra}')


if __name__ == '__main__':
    main()
