#!/usr/bin/env python3
"""Plays a ROS 2 bag over DDS the way the paper's robot publishes, for `uwbsar run --source ros2`.

An independent peer: the `cyclonedds` Python package (its own bundled Cyclone DDS) with the
ROS 2 message types of test/drivers/dds/ros2_peer.py (rosidl DDS names, classic CDR, "rt/"
topics). Radar scans (std_msgs/Float32MultiArray) and odometry (nav_msgs/Odometry) are
written in the bag's order at --speed times real time, each with the DDS source timestamp
set to the bag's log time: the robot's clock when its node published.

Modes:
  play     the bag from --start for --duration seconds (optionally with faults:
           --duplicate-every N repeats every Nth odometry sample, --out-of-order-at K sends
           odometry sample K again after K+1); a publisher that goes away and comes back is
           two plays of consecutive parts of the bag with a gap between them
  listen   keeps the LAST map, path, loop markers, pose and /tf uwbsar publishes until --idle seconds
           pass without a new one (after the first), then prints them
Prints one JSON object on stdout.
"""
import argparse
import json
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "drivers",
                                "dds"))
import ros2_peer as peer  # noqa: E402  (the shared ROS 2 type definitions)

from dataclasses import dataclass, field  # noqa: E402

from cyclonedds.domain import DomainParticipant  # noqa: E402
from cyclonedds.idl import IdlStruct  # noqa: E402
from cyclonedds.idl.annotations import final  # noqa: E402
from cyclonedds.idl.types import sequence  # noqa: E402
from cyclonedds.pub import DataWriter  # noqa: E402
from cyclonedds.sub import DataReader  # noqa: E402
from cyclonedds.topic import Topic  # noqa: E402
from rosbags.rosbag2 import Reader  # noqa: E402
from rosbags.typesys import Stores, get_typestore  # noqa: E402


@dataclass
@final
class Transform_(IdlStruct, typename="geometry_msgs::msg::dds_::Transform_"):
    translation_: peer.Vector3_ = field(default_factory=peer.Vector3_)
    rotation_: peer.Quaternion_ = field(default_factory=peer.Quaternion_)


@dataclass
@final
class TransformStamped_(IdlStruct, typename="geometry_msgs::msg::dds_::TransformStamped_"):
    header_: peer.Header_ = field(default_factory=peer.Header_)
    child_frame_id_: str = ""
    transform_: Transform_ = field(default_factory=Transform_)


@dataclass
@final
class TFMessage_(IdlStruct, typename="tf2_msgs::msg::dds_::TFMessage_"):
    transforms_: sequence[TransformStamped_] = field(default_factory=list)


def describe(name, msg):
    if name != "tf":
        return peer.describe(name, msg)
    return {"transforms": [{"frame": t.header_.frame_id_, "child": t.child_frame_id_,
                            "sec": t.header_.stamp_.sec_, "nanosec": t.header_.stamp_.nanosec_,
                            "pose": [t.transform_.translation_.x_, t.transform_.translation_.y_,
                                     peer.yaw_of(t.transform_.rotation_)]}
                           for t in msg.transforms_]}


def to_dds_odometry(m):
    o = peer.Odometry_(header_=peer.Header_(peer.Time_(m.header.stamp.sec,
                                                       m.header.stamp.nanosec),
                                            m.header.frame_id),
                       child_frame_id_=m.child_frame_id)
    p, q = m.pose.pose.position, m.pose.pose.orientation
    o.pose_.pose_.position_ = peer.Point_(p.x, p.y, p.z)
    o.pose_.pose_.orientation_ = peer.Quaternion_(q.x, q.y, q.z, q.w)
    o.pose_.covariance_ = list(m.pose.covariance)
    t = m.twist.twist
    o.twist_.twist_.linear_ = peer.Vector3_(t.linear.x, t.linear.y, t.linear.z)
    o.twist_.twist_.angular_ = peer.Vector3_(t.angular.x, t.angular.y, t.angular.z)
    o.twist_.covariance_ = list(m.twist.covariance)
    return o


def to_dds_array(m):
    dims = [peer.MultiArrayDimension_(d.label, d.size, d.stride) for d in m.layout.dim]
    return peer.Float32MultiArray_(peer.MultiArrayLayout_(dims, m.layout.data_offset),
                                   [float(v) for v in m.data])


class Writers:
    def __init__(self, domain, radar_topics, odom_topic, depth):
        self.dp = DomainParticipant(domain)
        q = peer.qos(True, depth)
        self.radar = {t: DataWriter(self.dp, Topic(self.dp, peer.dds_topic(t),
                                                   peer.Float32MultiArray_), qos=q)
                      for t in radar_topics}
        self.odom = DataWriter(self.dp, Topic(self.dp, peer.dds_topic(odom_topic),
                                              peer.Odometry_), qos=q)

    def all(self):
        return list(self.radar.values()) + [self.odom]


def play(args):
    radar_topics = [t for t in args.radar_topics.split(",") if t]
    store = get_typestore(Stores.ROS2_HUMBLE)
    messages = []
    with Reader(args.bag) as reader:
        conns = [c for c in reader.connections if c.topic in radar_topics + [args.odom_topic]]
        for conn, log_ns, raw in reader.messages(connections=conns):
            messages.append((log_ns, conn.topic, store.deserialize_cdr(raw, conn.msgtype)))
    if not messages:
        return {"error": "no radar or odometry messages in " + args.bag}
    begin = messages[0][0] + int(args.start * 1e9)
    end = begin + int(args.duration * 1e9) if args.duration > 0 else messages[-1][0]
    messages = [m for m in messages if begin <= m[0] <= end]
    writers = Writers(args.domain, radar_topics, args.odom_topic, args.depth)
    if not peer.wait_matched(writers.all(), args.timeout):
        return {"error": "no subscriber matched"}
    sent = {"radar": 0, "odometry": 0, "duplicates": 0, "out_of_order": 0}
    t0_bag, t0_wall = messages[0][0], time.monotonic()
    odom_index, previous_odom = 0, None
    for log_ns, topic, msg in messages:
        bag_s = (log_ns - t0_bag) * 1e-9
        delay = t0_wall + bag_s / args.speed - time.monotonic()
        if delay > 0:
            time.sleep(delay)
        if topic == args.odom_topic:
            sample = to_dds_odometry(msg)
            writers.odom.write(sample, timestamp=log_ns)
            sent["odometry"] += 1
            if args.duplicate_every > 0 and odom_index % args.duplicate_every == 0:
                writers.odom.write(sample, timestamp=log_ns)
                sent["odometry"] += 1
                sent["duplicates"] += 1
            if args.out_of_order_at == odom_index - 1 and previous_odom is not None:
                writers.odom.write(previous_odom[1], timestamp=previous_odom[0])
                sent["odometry"] += 1
                sent["out_of_order"] += 1
            previous_odom = (log_ns, sample)
            odom_index += 1
        else:
            writers.radar[topic].write(to_dds_array(msg), timestamp=log_ns)
            sent["radar"] += 1
    time.sleep(args.linger)
    return sent


def listen(args):
    dp = DomainParticipant(args.domain)
    readers = {
        "map": DataReader(dp, Topic(dp, peer.dds_topic(args.map_topic), peer.OccupancyGrid_),
                          qos=peer.qos(True, 1, transient_local=True)),
        "path": DataReader(dp, Topic(dp, peer.dds_topic(args.path_topic), peer.Path_),
                           qos=peer.qos()),
        "loops": DataReader(dp, Topic(dp, peer.dds_topic(args.loops_topic), peer.MarkerArray_),
                            qos=peer.qos()),
        "pose": DataReader(dp, Topic(dp, peer.dds_topic(args.pose_topic), peer.PoseStamped_),
                           qos=peer.qos()),
        "tf": DataReader(dp, Topic(dp, "rt/tf", TFMessage_), qos=peer.qos(True, 100)),
    }
    last, counts, last_new = {}, {k: 0 for k in readers}, None
    deadline = time.monotonic() + args.timeout
    while time.monotonic() < deadline:
        for name, reader in readers.items():
            for msg in reader.take(N=100):
                if type(msg).__name__ == "InvalidSample":  # a writer left: no data
                    continue
                last[name] = msg
                counts[name] += 1
                last_new = time.monotonic()
        if last_new is not None and time.monotonic() - last_new > args.idle:
            break
        time.sleep(0.02)
    out = {name: describe(name, msg) for name, msg in last.items()}
    out["counts"] = counts
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mode", choices=["play", "listen"])
    parser.add_argument("--domain", type=int, required=True)
    parser.add_argument("--bag", default="")
    parser.add_argument("--radar-topics", default="/UWBradar0/readings,/UWBradar1/readings")
    parser.add_argument("--odom-topic", default="/odom")
    parser.add_argument("--map-topic", default="/uwbsar/map")
    parser.add_argument("--path-topic", default="/uwbsar/path")
    parser.add_argument("--loops-topic", default="/uwbsar/loops")
    parser.add_argument("--pose-topic", default="/uwbsar/pose")
    parser.add_argument("--speed", type=float, default=1.0)
    parser.add_argument("--duration", type=float, default=0.0, help="play only this many s")
    parser.add_argument("--depth", type=int, default=100)
    parser.add_argument("--start", type=float, default=0.0, help="skip this many s of the bag")
    parser.add_argument("--duplicate-every", type=int, default=0)
    parser.add_argument("--out-of-order-at", type=int, default=-1)
    parser.add_argument("--linger", type=float, default=0.5)
    parser.add_argument("--idle", type=float, default=3.0)
    parser.add_argument("--timeout", type=float, default=30.0)
    args = parser.parse_args()
    result = play(args) if args.mode == "play" else listen(args)
    print(json.dumps(result))
    return 1 if "error" in result else 0


if __name__ == "__main__":
    sys.exit(main())
