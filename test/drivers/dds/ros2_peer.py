#!/usr/bin/env python3
"""An independent ROS 2 peer for the drivers/dds tests.

It speaks DDS the way a ROS 2 node on rmw_cyclonedds does, using the `cyclonedds`
Python package (its own bundled Cyclone DDS, not the Debian library uwbsar links):
the message types are defined here from their .msg files in the rosidl DDS mapping
(type names like nav_msgs::msg::dds_::Odometry_), endpoints use classic CDR (XCDR1)
and ROS topic "/x" is DDS topic "rt/x". It prints one JSON object on stdout.

Modes:
  publish   radar scans (std_msgs/Float32MultiArray) and odometry (nav_msgs/Odometry)
  garbled   an /odom sample whose bytes are not an Odometry, then a valid one
  wrongtype geometry_msgs/PoseStamped on the odometry topic
  subscribe map, pose, path and loop markers uwbsar publishes; prints what it decoded

Discovery configuration comes from $CYCLONEDDS_URI (the tests pin it to loopback).
"""
import argparse
import json
import math
import sys
import time
from dataclasses import dataclass, field

from cyclonedds.domain import DomainParticipant
from cyclonedds.idl import IdlStruct
from cyclonedds.idl.annotations import final
from cyclonedds.idl.types import array, float32, float64, int8, int32, sequence, uint8, uint32
from cyclonedds.pub import DataWriter
from cyclonedds.qos import Policy, Qos
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic


@dataclass
@final
class Time_(IdlStruct, typename="builtin_interfaces::msg::dds_::Time_"):
    sec_: int32 = 0
    nanosec_: uint32 = 0


@dataclass
@final
class Duration_(IdlStruct, typename="builtin_interfaces::msg::dds_::Duration_"):
    sec_: int32 = 0
    nanosec_: uint32 = 0


@dataclass
@final
class Header_(IdlStruct, typename="std_msgs::msg::dds_::Header_"):
    stamp_: Time_ = field(default_factory=Time_)
    frame_id_: str = ""


@dataclass
@final
class MultiArrayDimension_(IdlStruct, typename="std_msgs::msg::dds_::MultiArrayDimension_"):
    label_: str = ""
    size_: uint32 = 0
    stride_: uint32 = 0


@dataclass
@final
class MultiArrayLayout_(IdlStruct, typename="std_msgs::msg::dds_::MultiArrayLayout_"):
    dim_: sequence[MultiArrayDimension_] = field(default_factory=list)
    data_offset_: uint32 = 0


@dataclass
@final
class Float32MultiArray_(IdlStruct, typename="std_msgs::msg::dds_::Float32MultiArray_"):
    layout_: MultiArrayLayout_ = field(default_factory=MultiArrayLayout_)
    data_: sequence[float32] = field(default_factory=list)


@dataclass
@final
class ColorRGBA_(IdlStruct, typename="std_msgs::msg::dds_::ColorRGBA_"):
    r_: float32 = 0.0
    g_: float32 = 0.0
    b_: float32 = 0.0
    a_: float32 = 0.0


@dataclass
@final
class Point_(IdlStruct, typename="geometry_msgs::msg::dds_::Point_"):
    x_: float64 = 0.0
    y_: float64 = 0.0
    z_: float64 = 0.0


@dataclass
@final
class Vector3_(IdlStruct, typename="geometry_msgs::msg::dds_::Vector3_"):
    x_: float64 = 0.0
    y_: float64 = 0.0
    z_: float64 = 0.0


@dataclass
@final
class Quaternion_(IdlStruct, typename="geometry_msgs::msg::dds_::Quaternion_"):
    x_: float64 = 0.0
    y_: float64 = 0.0
    z_: float64 = 0.0
    w_: float64 = 1.0


@dataclass
@final
class Pose_(IdlStruct, typename="geometry_msgs::msg::dds_::Pose_"):
    position_: Point_ = field(default_factory=Point_)
    orientation_: Quaternion_ = field(default_factory=Quaternion_)


@dataclass
@final
class PoseWithCovariance_(IdlStruct, typename="geometry_msgs::msg::dds_::PoseWithCovariance_"):
    pose_: Pose_ = field(default_factory=Pose_)
    covariance_: array[float64, 36] = field(default_factory=lambda: [0.0] * 36)


@dataclass
@final
class Twist_(IdlStruct, typename="geometry_msgs::msg::dds_::Twist_"):
    linear_: Vector3_ = field(default_factory=Vector3_)
    angular_: Vector3_ = field(default_factory=Vector3_)


@dataclass
@final
class TwistWithCovariance_(IdlStruct, typename="geometry_msgs::msg::dds_::TwistWithCovariance_"):
    twist_: Twist_ = field(default_factory=Twist_)
    covariance_: array[float64, 36] = field(default_factory=lambda: [0.0] * 36)


@dataclass
@final
class PoseStamped_(IdlStruct, typename="geometry_msgs::msg::dds_::PoseStamped_"):
    header_: Header_ = field(default_factory=Header_)
    pose_: Pose_ = field(default_factory=Pose_)


@dataclass
@final
class Odometry_(IdlStruct, typename="nav_msgs::msg::dds_::Odometry_"):
    header_: Header_ = field(default_factory=Header_)
    child_frame_id_: str = ""
    pose_: PoseWithCovariance_ = field(default_factory=PoseWithCovariance_)
    twist_: TwistWithCovariance_ = field(default_factory=TwistWithCovariance_)


@dataclass
@final
class NotAnOdometry_(IdlStruct, typename="nav_msgs::msg::dds_::Odometry_"):
    """Same type name as Odometry_, other layout: its bytes are garbage as an Odometry."""
    junk_: uint32 = 0


@dataclass
@final
class MapMetaData_(IdlStruct, typename="nav_msgs::msg::dds_::MapMetaData_"):
    map_load_time_: Time_ = field(default_factory=Time_)
    resolution_: float32 = 0.0
    width_: uint32 = 0
    height_: uint32 = 0
    origin_: Pose_ = field(default_factory=Pose_)


@dataclass
@final
class OccupancyGrid_(IdlStruct, typename="nav_msgs::msg::dds_::OccupancyGrid_"):
    header_: Header_ = field(default_factory=Header_)
    info_: MapMetaData_ = field(default_factory=MapMetaData_)
    data_: sequence[int8] = field(default_factory=list)


@dataclass
@final
class Path_(IdlStruct, typename="nav_msgs::msg::dds_::Path_"):
    header_: Header_ = field(default_factory=Header_)
    poses_: sequence[PoseStamped_] = field(default_factory=list)


@dataclass
@final
class CompressedImage_(IdlStruct, typename="sensor_msgs::msg::dds_::CompressedImage_"):
    header_: Header_ = field(default_factory=Header_)
    format_: str = ""
    data_: sequence[uint8] = field(default_factory=list)


@dataclass
@final
class UVCoordinate_(IdlStruct, typename="visualization_msgs::msg::dds_::UVCoordinate_"):
    u_: float32 = 0.0
    v_: float32 = 0.0


@dataclass
@final
class MeshFile_(IdlStruct, typename="visualization_msgs::msg::dds_::MeshFile_"):
    filename_: str = ""
    data_: sequence[uint8] = field(default_factory=list)


@dataclass
@final
class Marker_(IdlStruct, typename="visualization_msgs::msg::dds_::Marker_"):
    # visualization_msgs/msg/Marker.msg of ROS 2 Humble, field for field.
    header_: Header_ = field(default_factory=Header_)
    ns_: str = ""
    id_: int32 = 0
    type_: int32 = 0
    action_: int32 = 0
    pose_: Pose_ = field(default_factory=Pose_)
    scale_: Vector3_ = field(default_factory=Vector3_)
    color_: ColorRGBA_ = field(default_factory=ColorRGBA_)
    lifetime_: Duration_ = field(default_factory=Duration_)
    frame_locked_: bool = False
    points_: sequence[Point_] = field(default_factory=list)
    colors_: sequence[ColorRGBA_] = field(default_factory=list)
    texture_resource_: str = ""
    texture_: CompressedImage_ = field(default_factory=CompressedImage_)
    uv_coordinates_: sequence[UVCoordinate_] = field(default_factory=list)
    text_: str = ""
    mesh_resource_: str = ""
    mesh_file_: MeshFile_ = field(default_factory=MeshFile_)
    mesh_use_embedded_materials_: bool = False


@dataclass
@final
class MarkerArray_(IdlStruct, typename="visualization_msgs::msg::dds_::MarkerArray_"):
    markers_: sequence[Marker_] = field(default_factory=list)


def dds_topic(ros_topic):
    return "rt" + (ros_topic if ros_topic.startswith("/") else "/" + ros_topic)


def qos(reliable=True, depth=10, transient_local=False):
    policies = [
        Policy.Reliability.Reliable(max_blocking_time=1_000_000_000)
        if reliable else Policy.Reliability.BestEffort,
        Policy.History.KeepLast(depth),
        Policy.Durability.TransientLocal if transient_local else Policy.Durability.Volatile,
        Policy.DataRepresentation(use_cdrv0_representation=True),
    ]
    return Qos(*policies)


def wait_matched(writers, timeout_s):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if all(len(w.get_matched_subscriptions()) > 0 for w in writers):
            return True
        time.sleep(0.02)
    return False


def stamp(t_s):
    sec = math.floor(t_s)
    return Time_(sec, int(round((t_s - sec) * 1e9)))


def odometry(t_s, x, y, yaw, v, w):
    msg = Odometry_(header_=Header_(stamp(t_s), "odom"), child_frame_id_="base_footprint")
    msg.pose_.pose_.position_ = Point_(x, y, 0.0)
    msg.pose_.pose_.orientation_ = Quaternion_(0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))
    msg.twist_.twist_.linear_ = Vector3_(v, 0.0, 0.0)
    msg.twist_.twist_.angular_ = Vector3_(0.0, 0.0, w)
    return msg


def publish(dp, args):
    radar_writers = [DataWriter(dp, Topic(dp, dds_topic(t), Float32MultiArray_),
                                qos=qos(args.reliable, args.depth))
                     for t in args.radar_topics.split(",") if t]
    odom_writer = DataWriter(dp, Topic(dp, dds_topic(args.odom_topic), Odometry_),
                             qos=qos(args.reliable, args.depth))
    if not wait_matched(radar_writers + [odom_writer], args.timeout):
        return {"error": "no subscriber matched"}
    sent = {"radar": [], "odometry": []}
    for i in range(args.count):
        for sensor, w in enumerate(radar_writers):
            data = [sensor * 1000.0 + i + 0.5 * k for k in range(args.samples)]
            w.write(Float32MultiArray_(
                MultiArrayLayout_([MultiArrayDimension_("samples", args.samples, args.samples)], 0),
                data))
            sent["radar"].append({"sensor": sensor, "first": data[0], "n": len(data)})
        t = 1000.0 + 0.1 * i
        odom_writer.write(odometry(t, 0.1 * i, -0.05 * i, 0.01 * i, 0.5, 0.1))
        sent["odometry"].append(t)
        time.sleep(args.period)
    if args.disorder:
        # A duplicate of the last stamp, then one from the past, then a good one.
        last = 1000.0 + 0.1 * (args.count - 1)
        for t in (last, last - 0.25, last + 0.1):
            odom_writer.write(odometry(t, 9.0, 9.0, 0.0, 0.0, 0.0))
            sent["odometry"].append(t)
            time.sleep(args.period)
    for w in radar_writers + [odom_writer]:
        w.wait_for_acks(2_000_000_000)
    time.sleep(args.linger)
    return sent


def garbled(dp, args):
    bad = DataWriter(dp, Topic(dp, dds_topic(args.odom_topic), NotAnOdometry_),
                     qos=qos(True, args.depth))
    good = DataWriter(dp, Topic(dp, dds_topic(args.odom_topic), Odometry_), qos=qos(True, args.depth))
    if not wait_matched([bad, good], args.timeout):
        return {"error": "no subscriber matched"}
    bad.write(NotAnOdometry_(0xDEADBEEF))
    bad.wait_for_acks(2_000_000_000)
    time.sleep(0.2)
    good.write(odometry(2000.0, 1.5, 2.5, 0.3, 0.0, 0.0))
    good.wait_for_acks(2_000_000_000)
    time.sleep(args.linger)
    return {"sent": ["garbled", "valid"]}


def wrongtype(dp, args):
    w = DataWriter(dp, Topic(dp, dds_topic(args.odom_topic), PoseStamped_), qos=qos(True, 10))
    w.write(PoseStamped_())
    time.sleep(args.linger)
    return {"sent": "PoseStamped_ on " + args.odom_topic}


def subscribe(dp, args):
    readers = {
        "map": DataReader(dp, Topic(dp, dds_topic(args.map_topic), OccupancyGrid_),
                          qos=qos(True, 1, transient_local=True)),
        "pose": DataReader(dp, Topic(dp, dds_topic(args.pose_topic), PoseStamped_), qos=qos()),
        "path": DataReader(dp, Topic(dp, dds_topic(args.path_topic), Path_), qos=qos()),
        "loops": DataReader(dp, Topic(dp, dds_topic(args.loops_topic), MarkerArray_), qos=qos()),
    }
    out = {}
    deadline = time.monotonic() + args.timeout
    while len(out) < len(readers) and time.monotonic() < deadline:
        for name, reader in readers.items():
            if name in out:
                continue
            for msg in reader.take(N=10):
                out[name] = describe(name, msg)
        time.sleep(0.02)
    return out


def yaw_of(q):
    return math.atan2(2 * (q.w_ * q.z_ + q.x_ * q.y_), 1 - 2 * (q.y_ ** 2 + q.z_ ** 2))


def describe(name, msg):
    if name == "map":
        i = msg.info_
        return {"frame": msg.header_.frame_id_, "sec": msg.header_.stamp_.sec_,
                "nanosec": msg.header_.stamp_.nanosec_, "width": i.width_, "height": i.height_,
                "resolution": i.resolution_, "origin": [i.origin_.position_.x_,
                                                       i.origin_.position_.y_,
                                                       yaw_of(i.origin_.orientation_)],
                "data": list(msg.data_)}
    if name == "pose":
        p = msg.pose_
        return {"frame": msg.header_.frame_id_, "sec": msg.header_.stamp_.sec_,
                "nanosec": msg.header_.stamp_.nanosec_,
                "pose": [p.position_.x_, p.position_.y_, yaw_of(p.orientation_)]}
    if name == "path":
        return {"frame": msg.header_.frame_id_,
                "poses": [[ps.header_.stamp_.sec_, ps.header_.stamp_.nanosec_,
                           ps.pose_.position_.x_, ps.pose_.position_.y_,
                           yaw_of(ps.pose_.orientation_)] for ps in msg.poses_]}
    return {"markers": [{"ns": m.ns_, "id": m.id_, "type": m.type_, "action": m.action_,
                         "frame": m.header_.frame_id_,
                         "points": [[p.x_, p.y_] for p in m.points_],
                         "texture_format": m.texture_.format_, "text": m.text_,
                         "mesh_use_embedded_materials": m.mesh_use_embedded_materials_}
                        for m in msg.markers_]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mode", choices=["publish", "garbled", "wrongtype", "subscribe"])
    parser.add_argument("--domain", type=int, required=True)
    parser.add_argument("--radar-topics", default="/UWBradar0/readings,/UWBradar1/readings")
    parser.add_argument("--odom-topic", default="/odom")
    parser.add_argument("--map-topic", default="/uwbsar/map")
    parser.add_argument("--pose-topic", default="/uwbsar/pose")
    parser.add_argument("--path-topic", default="/uwbsar/path")
    parser.add_argument("--loops-topic", default="/uwbsar/loops")
    parser.add_argument("--count", type=int, default=10)
    parser.add_argument("--samples", type=int, default=64)
    parser.add_argument("--period", type=float, default=0.01)
    parser.add_argument("--depth", type=int, default=100)
    parser.add_argument("--best-effort", dest="reliable", action="store_false")
    parser.add_argument("--disorder", action="store_true")
    parser.add_argument("--linger", type=float, default=0.2)
    parser.add_argument("--timeout", type=float, default=10.0)
    args = parser.parse_args()
    dp = DomainParticipant(args.domain)
    result = {"publish": publish, "garbled": garbled, "wrongtype": wrongtype,
              "subscribe": subscribe}[args.mode](dp, args)
    print(json.dumps(result))
    return 1 if isinstance(result, dict) and "error" in result else 0


if __name__ == "__main__":
    sys.exit(main())
